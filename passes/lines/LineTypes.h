#pragma once
/** @file The registry of line types, in composite order (later ones are drawn on top). The one list of line types:
 *  what iterates over line types iterates over this. */

#include "passes/lines/LineType.h"

#include <string>
#include <string_view>
#include <vector>

namespace inkgraph {

/** Every line type, in composite order. */
const std::vector<LineType>& lineTypes();
/** The type named `name`, or null. */
const LineType* findLineType(std::string_view name);
/** Every parameter of the line types, each once, in the order the registry first lists them. */
std::vector<const LineParameter*> lineParameters();
/** The names of the types that list `parameter` ("crease, normal-edge"), or that are stroked on the CPU when
 *  `parameter` is null (the types --supersample applies to). */
std::vector<std::string> lineTypesUsing(const LineParameter* parameter);

} // namespace inkgraph
