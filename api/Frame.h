#pragma once
/** @file A Frame's typed fields as the command line's options, each checked by its flag's own parser. */

#include "api/Internal.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {

/** Applies every field `frame` sets to `options` (--size always), appending each flag to `given` for the rules
 *  between flags (checkFlagRules()). Throws UsageError "Frame::<field>: --<flag>: ...". */
void applyFrame(const Frame& frame, RenderOptions& options, std::vector<std::string>& given);

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
