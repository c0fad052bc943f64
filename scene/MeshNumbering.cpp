#include "scene/MeshNumbering.h"

#include <stdexcept>
#include <string>

namespace inkgraph {

MeshNumbering::MeshNumbering(const Scene& scene) : mScene(scene) {
    const std::size_t count = scene.meshes.size() + scene.skippedMeshes.size();
    mDrawnIndex.reserve(count);
    mSkippedIndex.reserve(count);
    mNumberOfDrawn.reserve(scene.meshes.size());
    std::size_t drawn = 0;
    for (std::size_t skipped = 0; skipped <= scene.skippedMeshes.size(); ++skipped) {
        const std::size_t until =
            skipped < scene.skippedMeshes.size() ? scene.skippedMeshes[skipped].before : scene.meshes.size();
        if (until < drawn || until > scene.meshes.size())
            throw std::invalid_argument("MeshNumbering(): skipped mesh " + std::to_string(skipped) + " stands before " +
                                        "drawn mesh " + std::to_string(until) + ", out of order among the " +
                                        std::to_string(scene.meshes.size()) + " drawn meshes");
        for (; drawn < until; ++drawn) {
            mNumberOfDrawn.push_back(mDrawnIndex.size());
            mDrawnIndex.emplace_back(drawn);
            mSkippedIndex.push_back(0);
        }
        if (skipped < scene.skippedMeshes.size()) {
            mDrawnIndex.emplace_back(std::nullopt);
            mSkippedIndex.push_back(skipped);
        }
    }
}

const Mesh& MeshNumbering::mesh(std::size_t number) const {
    const std::optional<std::size_t> drawn = mDrawnIndex.at(number);
    return drawn ? mScene.meshes[*drawn] : mScene.skippedMeshes[mSkippedIndex[number]].mesh;
}

} // namespace inkgraph
