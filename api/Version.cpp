#include "inkgraph/inkgraph.h"

namespace inkgraph::api {

std::string version() { return INKGRAPH_VERSION; }

std::string gitCommit() { return INKGRAPH_GIT_COMMIT; }

} // namespace inkgraph::api
