#include "graph/Pass.h"

namespace inkgraph {

void PassBuilder::read(std::string_view resource) { mReads.push_back({std::string(resource)}); }

void PassBuilder::write(std::string_view field, const TextureDesc& desc, Need need, Presentation presentation) {
    // Recorded as given, even when malformed: compile() reports it together with every other problem.
    mWrites.push_back({std::string(field), desc, need, std::move(presentation)});
}

} // namespace inkgraph
