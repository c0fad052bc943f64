#include "graph/Pass.h"

#include "graph/Plan.h"

namespace inkgraph {

void PassBuilder::read(std::string_view resource, ReadExtent extent) {
    mReads.push_back({std::string(resource), {}, extent});
}

void PassBuilder::readObject(std::string_view resource, std::string_view type) {
    // An empty type is recorded as given: compile() reports it with every other problem.
    mReads.push_back({std::string(resource), type.empty() ? std::string("?") : std::string(type)});
}

void PassBuilder::writeObject(std::string_view field, const ObjectDesc& desc, Need need, Presentation presentation) {
    mWrites.push_back({std::string(field),
                       {desc.pictureFormat, desc.scale, 1, desc.divisor},
                       need,
                       std::move(presentation),
                       ResourceKind::Object,
                       desc});
}

bool PassBuilder::runsAnyway(std::string_view name) {
    mAskedCompileData = true;
    return mCompileData && mCompileData->firstRound && mCompileData->firstRound->findPass(std::string(name));
}

std::vector<std::string> PassBuilder::liveFieldsAnyway(std::string_view name) {
    mAskedCompileData = true;
    std::vector<std::string> fields;
    if (!mCompileData || !mCompileData->firstRound) return fields;
    if (const PlannedPass* pass = mCompileData->firstRound->findPass(std::string(name)))
        for (const std::string& resource : pass->liveWrites) fields.push_back(ResourceName::split(resource).field);
    return fields;
}

void PassBuilder::write(std::string_view field, const TextureDesc& desc, Need need, Presentation presentation) {
    // Recorded as given, even when malformed: compile() reports it together with every other problem.
    mWrites.push_back({std::string(field), desc, need, std::move(presentation), ResourceKind::Texture, {}});
}

} // namespace inkgraph
