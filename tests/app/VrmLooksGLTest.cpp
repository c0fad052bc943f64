// A VRM character in every look (issue 34): the KHR_materials_unlit that VRM exporters write beside MToon, as the
// fallback of viewers without MToon, is not a request for unlit shading, so every look lights the character; and the
// default look, auto, shades each material with its own MToon. Run through the real executable on godette.vrm.
#include "GltfTestFiles.h"

#include "render/ImageFiles.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path kGodette = fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "godette.vrm";

/** From the left and from the right, both in front and a little above: the figure's sides swap light and shade. */
const std::string kLightLeft = " --light -1,0.3,0.5";
const std::string kLightRight = " --light 1,0.3,0.5";

class VrmLooks : public Cli {
protected:
    /** Renders `model` with `arguments` (exit 0 expected) and reads the picture back. */
    cv::Mat render(const std::string& model, const std::string& arguments, const std::string& picture) {
        const CliRun result =
            run("render " + test::shellQuoted(model) + " -o " + picture + " --size 160x160 --lines none" + arguments);
        EXPECT_EQ(result.exitCode, 0) << arguments << ": " << result.err;
        return readImage(directory / picture);
    }

    /** The share of the pixels where either picture shows the model (not the white paper) that differ by more than 2
     *  codes in some channel. */
    static double changedShare(const cv::Mat& a, const cv::Mat& b) {
        int model = 0;
        int changed = 0;
        for (int row = 0; row < a.rows; ++row) {
            for (int col = 0; col < a.cols; ++col) {
                const cv::Vec3b p = a.at<cv::Vec3b>(row, col);
                const cv::Vec3b q = b.at<cv::Vec3b>(row, col);
                if (p == cv::Vec3b(255, 255, 255) && q == cv::Vec3b(255, 255, 255)) continue;
                ++model;
                for (int c = 0; c < 3; ++c) {
                    if (std::abs(int(p[c]) - int(q[c])) > 2) {
                        ++changed;
                        break;
                    }
                }
            }
        }
        return model == 0 ? 0.0 : double(changed) / model;
    }
};

TEST_F(VrmLooks, MovingTheLightFromLeftToRightChangesTheCharacterInEveryLook) {
    // Before, godette's MToon materials (also KHR_materials_unlit) were flat texture colour in every look but mtoon:
    // the light changed nothing. --shading none has no lighting at all: the control that the measure can say 0.
    for (const std::string shading :
         {"", " --shading comic", " --shading cel", " --shading phong", " --shading mtoon"}) {
        SCOPED_TRACE(shading.empty() ? "default look" : shading);
        const cv::Mat left = render(kGodette.string(), shading + kLightLeft, "left.png");
        const cv::Mat right = render(kGodette.string(), shading + kLightRight, "right.png");
        const double share = changedShare(left, right);
        EXPECT_GE(share, 0.10);
        std::printf("  godette%s: light left -> right changes %.1f%% of the figure's pixels\n",
                    shading.empty() ? " (default look)" : shading.c_str(), 100.0 * share);
    }
    EXPECT_EQ(changedShare(render(kGodette.string(), " --shading none" + kLightLeft, "left.png"),
                           render(kGodette.string(), " --shading none" + kLightRight, "right.png")),
              0.0);
}

TEST_F(VrmLooks, AWhiteMToonCharacterIsNotWhiteOnWhite) {
    // Every MToon material white and untextured (lit colour = the paper's), its shade colour as the file has it: the
    // shaded side must show. With the unlit fallback obeyed, the picture was empty paper.
    const std::string white = test::editedGlb(kGodette, [](Json& gltf) {
        for (Json& entry : gltf["extensions"]["VRM"]["materialProperties"]) {
            entry["vectorProperties"]["_Color"] = {1.0, 1.0, 1.0, 1.0};
            if (entry.contains("textureProperties"))
                for (const char* texture : {"_MainTex", "_ShadeTexture"}) entry["textureProperties"].erase(texture);
        }
    });
    std::ofstream(directory / "white.vrm", std::ios::binary) << white;
    const cv::Mat picture = render((directory / "white.vrm").string(), "", "white.png");
    const int notPaper = cv::countNonZero(picture.reshape(1) != 255);
    // Godette covers about a quarter of the frame; her shaded side is far more than 2% of it.
    EXPECT_GT(notPaper, 160 * 160 * 3 / 50) << "the default look of a white MToon character is white on white";

    // A material that is only KHR_materials_unlit stays unlit: drop the MToon entries' shader, and the glTF
    // material's unlit flag decides again (flat white).
    const std::string unlitOnly = test::editedGlb(directory / "white.vrm", [](Json& gltf) {
        for (Json& entry : gltf["extensions"]["VRM"]["materialProperties"]) entry["shader"] = "VRM_USE_GLTFSHADER";
        for (Json& material : gltf["materials"]) {
            material["pbrMetallicRoughness"]["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
            if (material.contains("pbrMetallicRoughness")) material["pbrMetallicRoughness"].erase("baseColorTexture");
            material["extensions"]["KHR_materials_unlit"] = Json::object();
        }
    });
    std::ofstream(directory / "unlit.vrm", std::ios::binary) << unlitOnly;
    const cv::Mat unlit = render((directory / "unlit.vrm").string(), " --shading comic", "unlit.png");
    EXPECT_EQ(cv::countNonZero(unlit.reshape(1) != 255), 0) << "an unlit white material is the paper's white";
}

// --expression and --look-at on a VRM 0.x character (issue 35): godette's Blink and Joy groups move her face's morph
// targets, her look-at (type BlendShape) weights LookLeft; names are checked against the file's groups.
TEST_F(VrmLooks, ExpressionsAndLookAtChangeGodettesFace) {
    const std::string face = " --frame Face";
    const cv::Mat rest = render(kGodette.string(), face, "rest.png");
    const cv::Mat blink = render(kGodette.string(), face + " --expression blink=1", "blink.png");
    const cv::Mat happy = render(kGodette.string(), face + " --expression happy=1", "happy.png");
    const cv::Mat joy = render(kGodette.string(), face + " --expression Joy=1", "joy.png");
    // Godette faces -Z: a point far to her left is -X (and the look-at origin is about 1.3 units up).
    const cv::Mat look = render(kGodette.string(), face + " --look-at -5,1.3,-2", "look.png");
    const double blinkShare = changedShare(rest, blink);
    const double happyShare = changedShare(rest, happy);
    const double lookShare = changedShare(rest, look);
    std::printf("  godette's face: blink changes %.1f%%, happy %.1f%%, a look to her left %.1f%% of its pixels\n",
                100.0 * blinkShare, 100.0 * happyShare, 100.0 * lookShare);
    EXPECT_GE(blinkShare, 0.02);
    EXPECT_GE(happyShare, 0.005);
    EXPECT_GE(lookShare, 0.005);
    EXPECT_EQ(changedShare(happy, joy), 0.0) << "happy is the 0.x group Joy";
    EXPECT_EQ(changedShare(rest, render(kGodette.string(), face + " --expression blink=0", "blink0.png")), 0.0);
}

TEST_F(VrmLooks, AnExpressionTheFileLacksExits3ListingItsNames) {
    const CliRun unknown = run("render " + test::shellQuoted(kGodette) + " -o x.png --expression smile=1");
    EXPECT_EQ(unknown.exitCode, 3) << unknown.err;
    EXPECT_NE(unknown.err.find("godette.vrm': --expression: no expression 'smile' (names are case-sensitive; the "
                               "file has 'neutral' (0.x 'Neutral'), 'aa' (0.x 'A')"),
              std::string::npos)
        << unknown.err;
    const CliRun malformed = run("render " + test::shellQuoted(kGodette) + " -o x.png --expression blink");
    EXPECT_EQ(malformed.exitCode, 2) << malformed.err;
    EXPECT_NE(malformed.err.find("--expression: expected NAME=WEIGHT[,NAME=WEIGHT...], got 'blink'"), std::string::npos)
        << malformed.err;
    const CliRun heavy = run("render " + test::shellQuoted(kGodette) + " -o x.png --expression blink=1.5");
    EXPECT_EQ(heavy.exitCode, 2) << heavy.err;
    const fs::path duck = fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "duck.glb";
    const CliRun plain = run("render " + test::shellQuoted(duck) + " -o x.png --look-at 0,0,1");
    EXPECT_EQ(plain.exitCode, 3) << plain.err;
    EXPECT_NE(plain.err.find("--look-at: the file has no VRM look-at settings"), std::string::npos) << plain.err;
    EXPECT_FALSE(fs::exists(directory / "x.png"));
}

} // namespace
} // namespace inkgraph
