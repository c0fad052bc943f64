// --pose and --frame by joint or bone through the real executable on godette.vrm (a VRM 0.x character, one skinned
// mesh for face and body): the camera each still reports (--dump's manifest) says what was framed. The poses'
// known-angle tests are tests/scene/VrmHumanoidTest.cpp.
#include "CliTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
namespace fs = std::filesystem;

const std::string kGodette =
    test::shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "godette.vrm");

struct ReportedView {
    glm::dvec3 eye;
    glm::dvec3 target;
    double distance() const { return glm::length(eye - target); }
};

class PoseAndFrame : public Cli {
protected:
    /** Renders godette with `arguments` (exit 0 expected) and returns the camera its manifest reports. */
    ReportedView view(const std::string& arguments) {
        const std::string dump = "dump" + std::to_string(mDumps++);
        const CliRun result = run("render " + kGodette + " -o " + dump +
                                  ".png --size 64x64 --lines none --shading "
                                  "none -q --dump " +
                                  dump + " " + arguments);
        EXPECT_EQ(result.exitCode, 0) << arguments << ": " << result.err;
        const nlohmann::json manifest = nlohmann::json::parse(test::readText(directory / dump / "manifest.json"));
        const auto vector = [](const nlohmann::json& xyz) {
            return glm::dvec3(xyz[0].get<double>(), xyz[1].get<double>(), xyz[2].get<double>());
        };
        return {vector(manifest["camera"]["eye"]), vector(manifest["camera"]["target"])};
    }

    void write(const std::string& name, const std::string& content) { std::ofstream(directory / name) << content; }

private:
    int mDumps = 0;
};

TEST_F(PoseAndFrame, FrameHeadFramesTheSkinnedFace) {
    // godette's face and body are one skinned mesh: before, no node held the head's vertices alone.
    const ReportedView whole = view("");
    const ReportedView head = view("--frame head");
    // Her head is large (about 0.4 of her height, hair included), and a joint's sphere bounds its vertices' box.
    EXPECT_LT(head.distance(), 0.7 * whole.distance()) << "the head's sphere is a fraction of the whole model's";
    EXPECT_GT(head.target.y, whole.target.y + 0.2) << "the head is above the model's middle";
    // The joint's own node name frames the same.
    const ReportedView joint = view("--frame head_Armature");
    EXPECT_LT(glm::length(joint.eye - head.eye), 1e-6);
}

TEST_F(PoseAndFrame, APoseLowersBothHands) {
    const ReportedView left = view("--frame leftHand");
    const ReportedView right = view("--frame rightHand");
    const ReportedView leftPosed = view("--frame leftHand --pose a-pose");
    const ReportedView rightPosed = view("--frame rightHand --pose a-pose");
    // Each hand swings 45 degrees down about its shoulder: lower, and nearer the body's middle (x = 0).
    EXPECT_LT(leftPosed.target.y, left.target.y - 0.1);
    EXPECT_LT(rightPosed.target.y, right.target.y - 0.1);
    EXPECT_LT(std::abs(leftPosed.target.x), std::abs(left.target.x) - 0.03);
    EXPECT_LT(std::abs(rightPosed.target.x), std::abs(right.target.x) - 0.03);
    // Both turn alike: the character is symmetric, and so is the pose.
    EXPECT_NEAR(left.target.y - leftPosed.target.y, right.target.y - rightPosed.target.y, 0.01);
    // The head stays where it was.
    EXPECT_LT(glm::length(view("--frame head --pose a-pose").target - view("--frame head").target), 1e-6);
}

TEST_F(PoseAndFrame, AVrmAnimationIsRetargetedOntoTheCharacter) {
    // three-vrm's test.vrma turns its right upper arm by the raw quarter turn (0.7071, 0, 0, 0.7071) at 0.5 s. Its
    // rest frames are Blender's (the hips turned [0.5, 0.5, -0.5, 0.5]), which make that the normalized quarter
    // turn about +Z, [0, 0, 0.7071068, 0.7071068] (worked out apart from the code, with numpy): the arm hangs down.
    const std::string vrma = model("characters/three-vrm-test.vrma");
    write("arm-down.json", "{\"rightUpperArm\": [0, 0, 0.7071068, 0.7071068]}");
    const ReportedView rest = view("--frame rightHand");
    const ReportedView animated = view("--frame rightHand --animation " + vrma + " --time 0.5");
    const ReportedView posed = view("--frame rightHand --pose arm-down.json");
    EXPECT_LT(animated.target.y, rest.target.y - 0.2);
    EXPECT_LT(glm::length(animated.target - posed.target), 1e-4) << "the retargeted arm is the pose file's";
    // At 0 s the animation is at its rest: the character's T-pose.
    EXPECT_LT(glm::length(view("--frame rightHand --animation " + vrma + " --time 0").target - rest.target), 1e-6);
}

TEST_F(PoseAndFrame, UnknownFrameNameListsNodesBonesAndJoints) {
    const CliRun result = run("render " + kGodette + " -o x.png --frame tail");
    EXPECT_EQ(result.exitCode, 3) << "the model lacks the name: a batch of mixed models fails this one alone";
    EXPECT_NE(result.err.find("--frame 'tail': no mesh lies under a node of that name, and no joint or humanoid bone "
                              "has it (the model's nodes with meshes under them: 'Face', 'Body'; its humanoid bones: "
                              "'hips', "),
              std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("; its joints: 'Armature_rootJoint', "), std::string::npos) << result.err;
}

TEST_F(PoseAndFrame, PoseRefusalsNameTheFile) {
    write("tail.json", "{\"tail\": [0, 0, 0, 1]}");
    CliRun result = run("render " + kGodette + " -o x.png --pose tail.json");
    EXPECT_EQ(result.exitCode, 3);
    EXPECT_NE(result.err.find("'tail.json': unknown humanoid bone 'tail' (VRM's humanoid bones: hips, spine, "),
              std::string::npos)
        << result.err;
    write("broken.json", "{\"head\": [0, 0, 0, 1]");
    result = run("render " + kGodette + " -o x.png --pose broken.json");
    EXPECT_EQ(result.exitCode, 3);
    EXPECT_NE(result.err.find("'broken.json': not a pose file: invalid JSON"), std::string::npos) << result.err;
    result = run("render " + model("characters/duck.glb") + " -o x.png --pose a-pose");
    EXPECT_EQ(result.exitCode, 3);
    EXPECT_NE(result.err.find("duck.glb': cannot take a humanoid pose: not a VRM model"), std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(directory / "x.png"));
}

TEST_F(PoseAndFrame, ABoneTheModelLacksIsAWarning) {
    write("jaw.json", "{\"jaw\": [0.2588190, 0, 0, 0.9659258]}");
    const CliRun result = run("render " + kGodette + " -o x.png --size 32x32 --pose jaw.json");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("warning: the pose turns 'jaw', which the model's humanoid lacks; ignored"),
              std::string::npos)
        << result.err;
}

TEST_F(PoseAndFrame, ATimeThatMovesNothingIsAWarning) {
    // --time without --animation is only MToon's UV animation clock: on a model without one it did nothing, silently
    // (the library's SceneOptions::time refuses it).
    const std::string unused = "--time 5 moves nothing: without --animation it is only the clock of MToon's UV "
                               "animation, and no material of the model has one";
    const std::string fox = model("characters/fox.glb");
    CliRun result = run("render " + fox + " -o x.png --size 32x32 --time 5");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("warning: " + unused), std::string::npos) << result.err;
    result = run("render " + fox + " -o x.png --size 32x32 --time 5 --strict");
    EXPECT_EQ(result.exitCode, 3) << result.err;
    for (const std::string& moves :
         {"render " + fox + " -o x.png --size 32x32 --time 0.5 --animation 0",
          "render " + model("characters/mtoon-uv-animation-test.vrm") + " -o x.png --size 32x32 --time 5",
          "render " + fox + " -o x.png --size 32x32 --time 0"}) {
        result = run(moves);
        EXPECT_EQ(result.exitCode, 0) << moves << ": " << result.err;
        EXPECT_EQ(result.err.find("time-unused"), std::string::npos) << moves << ": " << result.err;
        EXPECT_EQ(result.err.find("moves nothing"), std::string::npos) << moves << ": " << result.err;
    }
}

} // namespace
} // namespace inkgraph
