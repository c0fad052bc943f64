// libFuzzer target: glTF skins, morph targets and animation samplers (scene/formats/gltf/GltfPose.cpp), through the
// glTF reader: each input is loaded in its rest pose and posed by its first animation ("0", as --animation 0) at two
// times, one between keyframes and one past the last (clamped), as --time gives them.
#include "tests/fuzz/FuzzSupport.h"

#include <cmath>
#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    struct Pose {
        const char* animation;
        double time;
    };
    for (const Pose pose : {Pose{"", 0.0}, Pose{"0", 0.37}, Pose{"0", 1e9}}) {
        inkgraph::LoadOptions options;
        options.memoryLimitBytes = inkgraph::fuzz::kFuzzMemoryLimitBytes;
        options.animation = pose.animation;
        options.time = pose.time;
        inkgraph::Scene scene;
        try {
            scene = inkgraph::loadSceneFromMemory("fuzz.gltf", inkgraph::fuzz::bytesOf(data, size), options);
        } catch (const inkgraph::SceneError&) {
            continue;
        }
        // The posed positions are baked: the loader promises finite ones (a NaN joint matrix must be refused).
        for (const inkgraph::Mesh& mesh : scene.meshes)
            for (const glm::vec3& position : mesh.positions)
                if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
                    throw std::logic_error("FuzzSkin: a non-finite posed position");
    }
    return 0;
}
