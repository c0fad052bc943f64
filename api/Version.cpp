#include "inkgraph/inkgraph.h"

#include "render/BuildInfo.h"

namespace inkgraph::api {

std::string version() { return inkgraphVersion(); }

std::string gitCommit() { return inkgraphGitCommit(); }

} // namespace inkgraph::api
