// Values a model file gives that the renderer's float arithmetic cannot take as they are, run through the real
// executable (issue 31): a model placed 1e17 units out by a node or an animation, texture transforms and material
// factors beyond float or beyond sense, and a file camera that sees none of the model. Each once gave a blank, black or
// collapsed picture with exit 0; now each renders as the file means it, or says what it changed, or is refused.
#include "GltfTestFiles.h"

#include "render/ImageFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <vector>

namespace inkgraph::model_values_gl_test {
namespace {

using test::Cli;
using test::CliRun;
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

    /** Pixels of `picture` that are not the white paper: the model, its lines. */
    int drawn(const std::string& picture) { return cv::countNonZero(readImage(directory / picture).reshape(1) != 255); }
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
    ASSERT_GT(drawn("near.png"), 96 * 96 / 10) << "the cube fills a good part of the picture";
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
    ASSERT_GT(drawn("near.png"), 96 * 96 / 10);
    render("far.vrm", "far.png");
    EXPECT_EQ(difference("near.png", "far.png"), 0.0);
}

/** box-textured.glb (its texture repeats) with `edit` applied to its one material. */
std::string boxWith(const std::function<void(Json& material)>& edit) {
    return test::editedGlb(sourceModel("characters/box-textured.glb"), [&](Json& gltf) {
        gltf["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_emissive_strength"};
        edit(gltf["materials"][0]);
    });
}

Json textureTransform(const Json& transform) { return {{"KHR_texture_transform", transform}}; }

TEST_F(ModelValues, TextureOffsetsFloatCannotHoldRenderAsTheRepeatSays) {
    // A repeating texture looks the same a whole period on, so an offset is reduced modulo the period in double
    // before the shaders get it. In float an offset of 1e7 + 0.25 left no fraction to find a texel with (the box
    // turned one flat colour), and 1e38 or 1e300 reached the shaders as they are or as infinity.
    write("quarter.glb", boxWith([](Json& material) {
              material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] =
                  textureTransform({{"offset", {0.25, 0.0}}});
          }));
    write("far-quarter.glb", boxWith([](Json& material) {
              material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] =
                  textureTransform({{"offset", {1e7 + 0.25, -1e38}}});
          }));
    write("whole.glb", boxWith([](Json& material) {
              material["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] =
                  textureTransform({{"offset", {1e300, -3e300}}});
          }));
    render(test::shellQuoted(sourceModel("characters/box-textured.glb")), "box.png");
    render("quarter.glb", "quarter.png");
    EXPECT_GT(difference("box.png", "quarter.png"), 0.0) << "the offset moves the texture";
    render("far-quarter.glb", "far-quarter.png");
    EXPECT_EQ(difference("quarter.png", "far-quarter.png"), 0.0);
    render("whole.glb", "whole.png");
    EXPECT_EQ(difference("box.png", "whole.png"), 0.0);

    // VRM 0.x's _MainTex offset (UniVRM's scale/offset vector) goes through the same reduction.
    const fs::path vrm = sourceModel("characters/godette.vrm");
    const auto withMainTex = [&](const Json& offsetScale) {
        return test::editedGlb(vrm, [&](Json& gltf) {
            for (Json& properties : gltf["extensions"]["VRM"]["materialProperties"])
                properties["vectorProperties"]["_MainTex"] = offsetScale;
        });
    };
    write("far-offset.vrm", withMainTex({1e38, -1e38, 1.0, 1.0}));
    render(test::shellQuoted(vrm), "godette.png");
    render("far-offset.vrm", "far-offset.png");
    EXPECT_EQ(difference("godette.png", "far-offset.png"), 0.0);
    // A scale float cannot resolve is dropped with a warning naming the material (the VRM reader's policy).
    write("huge-scale.vrm", withMainTex({0.0, 0.0, 1e38, 1.0}));
    const std::string warned = render("huge-scale.vrm", "huge-scale.png");
    EXPECT_NE(warned.find("material 0 'Face': vectorProperties._MainTex: its scale and rotation stretch texture "
                          "coordinates 1e+38 times"),
              std::string::npos)
        << warned;
    EXPECT_EQ(difference("godette.png", "huge-scale.png"), 0.0);

    // An MTL map's -o goes through the same reduction; a -s float cannot resolve leaves the map out with a warning.
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "shademaps" / "duotone-warm.png", directory / "tex.png");
    const std::string quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                             "usemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    for (const auto& [name, options] : std::vector<std::pair<std::string, std::string>>{
             {"near", "-o 0.25 0"}, {"far", "-o 10000000.25 1e30"}, {"huge", "-s 1e30 1"}}) {
        write(name + ".mtl", "newmtl m\nmap_Kd " + options + " tex.png\n");
        write(name + ".obj", "mtllib " + name + ".mtl\n" + quad);
    }
    render("near.obj", "near-obj.png");
    render("far.obj", "far-obj.png");
    EXPECT_EQ(difference("near-obj.png", "far-obj.png"), 0.0);
    const std::string dropped = render("huge.obj", "huge-obj.png");
    EXPECT_NE(dropped.find("huge.mtl' line 2: 'map_Kd' options -s/-o: its scale and rotation stretch texture "
                           "coordinates 1e+30 times"),
              std::string::npos)
        << dropped;
    EXPECT_GT(difference("near-obj.png", "huge-obj.png"), 0.0) << "the texture shows where it is kept";
}

TEST_F(ModelValues, MaterialFactorsBeyondTheirRangeAreClampedWithAWarning) {
    // Each pair renders alike: the factor beyond its range (glTF's [0, 1] for colours and the cutoff, 1e6 for an
    // emissive strength) and the end of the range it is clamped to. Before, 1e300 reached the shaders as infinity
    // (red blown out, emissive channels NaN-dark) and a cutoff of 2 cut out the whole box: blank paper, exit 0.
    struct Pair {
        std::string name;
        std::function<void(Json&)> beyond;
        std::function<void(Json&)> clamped;
        std::string warning;
    };
    const std::vector<Pair> pairs = {
        {"base colour",
         [](Json& m) {
             m["pbrMetallicRoughness"]["baseColorFactor"] = {1e300, 0.5, 1.0, 1.0};
         },
         [](Json& m) {
             m["pbrMetallicRoughness"]["baseColorFactor"] = {1.0, 0.5, 1.0, 1.0};
         },
         "material 0 'Texture' baseColorFactor[0] 1e+300 is outside [0, 1]; 1 is used"},
        {"emissive strength",
         [](Json& m) {
             m["emissiveFactor"] = {1.0, 0.0, 0.0};
             m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 1e300;
         },
         [](Json& m) {
             m["emissiveFactor"] = {1.0, 0.0, 0.0};
             m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 1e6;
         },
         "material 0 'Texture' KHR_materials_emissive_strength emissiveStrength 1e+300 is outside [0, 1e+06]; "
         "1e+06 is used"},
        {"alpha cutoff",
         [](Json& m) {
             m["alphaMode"] = "MASK";
             m["alphaCutoff"] = 2.0;
         },
         [](Json& m) {
             m["alphaMode"] = "MASK";
             m["alphaCutoff"] = 1.0;
         },
         "material 0 'Texture' alphaCutoff 2 is outside [0, 1]; 1 is used"},
    };
    for (const Pair& pair : pairs) {
        SCOPED_TRACE(pair.name);
        write("beyond.glb", boxWith(pair.beyond));
        write("clamped.glb", boxWith(pair.clamped));
        const std::string warned = render("beyond.glb", "beyond.png");
        EXPECT_NE(warned.find("inkgraph: warning: " + pair.warning), std::string::npos) << warned;
        EXPECT_EQ(render("clamped.glb", "clamped.png").find("warning"), std::string::npos);
        EXPECT_EQ(difference("beyond.png", "clamped.png"), 0.0);
    }
    // A VRM 0.x colour is gamma-encoded; 1e38 became infinity converted to linear light.
    const fs::path vrm = sourceModel("characters/godette.vrm");
    const auto withColor = [&](double red) {
        return test::editedGlb(vrm, [&](Json& gltf) {
            gltf["extensions"]["VRM"]["materialProperties"][0]["vectorProperties"]["_Color"] = {red, 1.0, 1.0, 1.0};
        });
    };
    write("red.vrm", withColor(1e38));
    write("white.vrm", withColor(1.0));
    const std::string warned = render("red.vrm", "red.png");
    EXPECT_NE(warned.find("material 0 'Face': vectorProperties._Color[0] 1e+38 is outside [0, 1]; 1 is used"),
              std::string::npos)
        << warned;
    render("white.vrm", "white.png");
    EXPECT_EQ(difference("red.png", "white.png"), 0.0);

    // Vertex colours multiply the surface's in the shaders: 1e38 is clamped to 1e6 (both far beyond white).
    const float hot[4] = {1e38f, 1e38f, 0.5f, 1.0f};
    const float warm[4] = {1e6f, 1e6f, 0.5f, 1.0f};
    write("hot.gltf", cubeGltf("[{\"mesh\":0," + kTurned + "}]", "", nullptr, nullptr, hot));
    write("warm.gltf", cubeGltf("[{\"mesh\":0," + kTurned + "}]", "", nullptr, nullptr, warm));
    const std::string hotWarning = render("hot.gltf --shading lambert", "hot.png");
    EXPECT_NE(hotWarning.find("'mesh 0' COLOR_0 value 9.999999680285692e+37 is outside [0, 1e+06]; 1e+06 is used "
                              "(and 15 more values outside it)"),
              std::string::npos)
        << hotWarning;
    render("warm.gltf --shading lambert", "warm.png");
    EXPECT_EQ(difference("hot.png", "warm.png"), 0.0);
}

TEST_F(ModelValues, AFileCameraThatSeesNoneOfTheModelIsReported) {
    // duck.glb's camera turned about its own up looks away from the duck: blank paper, exit 0 and no word before.
    const fs::path duck = sourceModel("characters/duck.glb");
    write("away.glb", test::editedGlb(duck, [](Json& gltf) {
              Json& matrix = gltf["nodes"][1]["matrix"]; // the camera's node: columns x and z negated
              for (int i : {0, 1, 2, 8, 9, 10}) matrix[i] = -matrix[i].get<double>();
          }));
    const std::string seen = render(test::shellQuoted(duck), "duck.png");
    EXPECT_EQ(seen.find("sees none of the model"), std::string::npos) << seen;
    const std::string away = render("away.glb", "away.png");
    EXPECT_NE(away.find("inkgraph: warning: the glTF camera (camera 0 'PerspectiveCamera') sees none of the model: "
                        "every vertex lies behind the camera, so the picture shows only the background; "
                        "--camera auto frames the model instead"),
              std::string::npos)
        << away;
    EXPECT_GT(drawn("duck.png"), 0);
    EXPECT_EQ(drawn("away.png"), 0) << "paper only";
    // --camera auto frames it again, without the warning.
    EXPECT_EQ(render("away.glb --camera auto", "auto.png").find("sees none"), std::string::npos);
    EXPECT_GT(drawn("auto.png"), 0);

    // Clip planes from the flags that leave the model out say so too.
    const std::string clipped = render(test::shellQuoted(sourceModel("spot_c3d.obj")) + " --clip 100,200", "clip.png");
    EXPECT_NE(clipped.find("inkgraph: warning: the auto-framed camera sees none of the model: every vertex lies nearer "
                           "than the near plane at 100 (--clip)"),
              std::string::npos)
        << clipped;
}

} // namespace
} // namespace inkgraph::model_values_gl_test
