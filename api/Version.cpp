#include "inkgraph/inkgraph.h"

#include "render/BuildInfo.h"

namespace inkgraph::api {
inline namespace INKGRAPH_ABI_NAMESPACE {

std::string version() { return inkgraphVersion(); }

std::string gitCommit() { return inkgraphGitCommit(); }

} // namespace INKGRAPH_ABI_NAMESPACE
} // namespace inkgraph::api
