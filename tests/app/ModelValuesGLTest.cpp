// Values a model file gives that the renderer's float arithmetic cannot take as they are, run through the real
// executable (issue 31): a model placed 1e17 units out by a node, a parent or an animation once collapsed to a point
// or a line; now it renders like itself at the origin.
#include "GltfTestFiles.h"

#include "app/ImageFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;
using Json = nlohmann::json;

const std::string kLook = " --size 96x96 --lines contour,silhouette,crease";

fs::path sourceModel(const std::string& name) { return fs::path(INKGRAPH_SOURCE_ROOT) / "models" / name; }

/** A unit cube centred on its node's origin: 8 corners, 12 triangles wound outward, and a buffer for one translation
 *  animation (times 0 and 1, translations `from` and `to`); `nodes` (JSON) places it by mesh 0. With `colour`, every
 *  corner has that COLOR_0. */
std::string cubeGltf(const std::string& nodes, const std::string& extra = "", const float from[3] = nullptr,
                     const float to[3] = nullptr, const float colour[4] = nullptr) {
    std::string buffer;
    const auto put = [&](const void* data, std::size_t size) { buffer.append(static_cast<const char*>(data), size); };
    for (int corner = 0; corner < 8; ++corner) {
        const float xyz[3] = {(corner & 1) ? 0.5f : -0.5f, (corner & 2) ? 0.5f : -0.5f, (corner & 4) ? 0.5f : -0.5f};
        put(xyz, sizeof xyz);
    }
    // Corners by bits (x = 1, y = 2, z = 4); each face counter-clockwise seen from outside.
    const std::uint16_t indices[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 4, 6, 0, 6, 2,
                                       1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 6, 7, 2, 7, 3};
    put(indices, sizeof indices);
    const float times[2] = {0.0f, 1.0f};
    put(times, sizeof times);
    const float none[3] = {0.0f, 0.0f, 0.0f};
    put(from ? from : none, 3 * sizeof(float));
    put(to ? to : none, 3 * sizeof(float));
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    for (int corner = 0; corner < 8; ++corner) put(colour ? colour : white, 4 * sizeof(float));
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes + extra +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0)" + (colour ? R"(,"COLOR_0":4)" : "") +
           R"(},"indices":1}]}],"accessors":[)"
           R"({"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[-0.5,-0.5,-0.5],"max":[0.5,0.5,0.5]},)"
           R"({"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"},)"
           R"({"bufferView":2,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},)"
           R"({"bufferView":3,"componentType":5126,"count":2,"type":"VEC3"},)"
           R"({"bufferView":4,"componentType":5126,"count":8,"type":"VEC4"}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":96},{"buffer":0,"byteOffset":96,"byteLength":72},)"
           R"({"buffer":0,"byteOffset":168,"byteLength":8},{"buffer":0,"byteOffset":176,"byteLength":24},)"
           R"({"buffer":0,"byteOffset":200,"byteLength":128}],)"
           R"("buffers":[{"byteLength":)" +
           std::to_string(buffer.size()) + R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(buffer) +
           R"("}]})";
}

/** A rotation of 30 degrees about +Y, so the cube shows three faces unevenly. */
const std::string kTurned = R"("rotation":[0,0.25881904510252074,0,0.9659258262890683])";

class ModelValues : public Cli {
protected:
    void write(const std::string& name, const std::string& bytes) {
        std::ofstream(directory / name, std::ios::binary) << bytes;
    }

    /** Renders `arguments` into `picture` (exit 0 expected) and returns stderr. */
    std::string render(const std::string& arguments, const std::string& picture) {
        const CliRun result = run("render " + arguments + " -o " + picture + kLook);
        EXPECT_EQ(result.exitCode, 0) << arguments << ": " << result.err;
        return result.err;
    }

    double difference(const std::string& a, const std::string& b) {
        return cv::norm(readImage(directory / a), readImage(directory / b), cv::NORM_INF);
    }
};

TEST_F(ModelValues, AModelTranslatedFarByANodeOrAnAnimationRendersLikeItAtTheOrigin) {
    // In double 1e17 + 0.5 is 1e17: a cube baked into world space there collapsed to a point ("all triangles are
    // degenerate") or a line. The node transforms are composed to 32 digits and made relative to the scene's origin
    // before rounding, so each placement gives the picture of the cube at the origin, bit for bit.
    write("near.gltf", cubeGltf("[{\"mesh\":0," + kTurned + "}]"));
    write("far-node.gltf", cubeGltf("[{\"mesh\":0," + kTurned + R"(,"translation":[1e17,-3e17,2e17]}])"));
    write("far-parent.gltf",
          cubeGltf(R"([{"translation":[1e17,-3e17,2e17],"children":[1]},{"mesh":0,)" + kTurned + "}]"));
    const float from[3] = {0.0f, 0.0f, 0.0f};
    const float to[3] = {2e17f, -6e17f, 4e17f};
    write(
        "far-animation.gltf",
        cubeGltf("[{\"mesh\":0," + kTurned + "}]",
                 R"(,"animations":[{"name":"away","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
                 R"("samplers":[{"input":2,"output":3,"interpolation":"LINEAR"}]}])",
                 from, to));
    render("near.gltf", "near.png");
    for (const char* far : {"far-node.gltf", "far-parent.gltf"}) {
        SCOPED_TRACE(far);
        render(far, std::string(far) + ".png");
        EXPECT_EQ(difference("near.png", std::string(far) + ".png"), 0.0);
    }
    // At --time 0.5 the animation has carried the cube 3.7e17 units out.
    render("far-animation.gltf --animation away --time 0.5", "far-animation.png");
    EXPECT_EQ(difference("near.png", "far-animation.png"), 0.0);
    // Its rest pose, at the origin, is the same picture as well.
    render("far-animation.gltf", "rest.png");
    EXPECT_EQ(difference("near.png", "rest.png"), 0.0);
}

TEST_F(ModelValues, ASkinnedCharacterTranslatedFarRendersLikeItAtTheOrigin) {
    // A VRM character's skin places it by its joints: a root node 1e17 units out above all of the scene's roots moves
    // every joint there. The joint matrices (world x inverse bind) are composed to 32 digits as well.
    const fs::path vrm = sourceModel("characters/godette.vrm");
    write("far.vrm", test::editedGlb(vrm, [](Json& gltf) {
              Json& roots = gltf["scenes"][0]["nodes"];
              gltf["nodes"].push_back({{"name", "far away"}, {"translation", {1e17, 0.0, -2e17}}, {"children", roots}});
              roots = Json::array({gltf["nodes"].size() - 1});
          }));
    render(test::shellQuoted(vrm), "near.png");
    render("far.vrm", "far.png");
    EXPECT_EQ(difference("near.png", "far.png"), 0.0);
}

} // namespace
} // namespace inkgraph
