// --animation and --time, --expression and --look-at: parsed into RenderOptions, carried to the still's load, refused
// when they cannot apply.
#include "tests/app/OptionsTestSupport.h"
#include "app/Cli.h"
#include "flags/FlagTable.h"
#include "flags/Options.h"
#include "app/Render.h"
#include "flags/StyleFile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace inkgraph {
namespace {

using test::usageMessage;

TEST(AnimationFlags, DefaultIsTheRestPose) {
    const RenderOptions options = parseRenderOptions({"m.glb", "-o", "x.png"});
    EXPECT_EQ(options.animation, "");
    EXPECT_EQ(options.animationTime, 0.0);
}

TEST(AnimationFlags, NameAndTimeReachTheStillRequest) {
    const RenderOptions options =
        parseRenderOptions({"m.glb", "-o", "x.png", "--animation", "Walk Cycle", "--time", "1.25"});
    EXPECT_EQ(options.animation, "Walk Cycle");
    EXPECT_EQ(options.animationTime, 1.25);
    const StillRequest request = stillRequestOf(options);
    EXPECT_EQ(request.animation, "Walk Cycle");
    EXPECT_EQ(request.animationTime, 1.25);
}

TEST(AnimationFlags, TimeWithoutAnimationIsTheUvAnimationsClock) {
    // MToon's UV animation runs on --time in a file without animations (models/characters/mtoon-uv-animation-test.vrm).
    const RenderOptions options = parseRenderOptions({"m.glb", "-o", "x.png", "--time", "2"});
    EXPECT_TRUE(options.animation.empty());
    EXPECT_EQ(stillRequestOf(options).animationTime, 2.0);
}

TEST(AnimationFlags, NegativeOrNonFiniteTimeIsRefused) {
    for (const std::string bad : {"-1", "nan", "inf", "1e999", "two"}) {
        const std::string message = usageMessage({"m.glb", "-o", "x.png", "--animation", "0", "--time", bad});
        EXPECT_EQ(message.rfind("--time: ", 0), 0u) << bad << ": " << message;
    }
    EXPECT_EQ(usageMessage({"m.glb", "-o", "x.png", "--animation", ""}).rfind("--animation: ", 0), 0u);
}

TEST(AnimationFlags, PoseReachesTheStillRequest) {
    EXPECT_EQ(parseRenderOptions({"m.vrm", "-o", "x.png"}).pose, "");
    const RenderOptions options = parseRenderOptions({"m.vrm", "-o", "x.png", "--pose", "a-pose"});
    EXPECT_EQ(options.pose, "a-pose");
    EXPECT_EQ(stillRequestOf(options).pose, "a-pose");
    EXPECT_EQ(stillRequestOf(parseRenderOptions({"m.vrm", "-o", "x.png", "--pose", "sit.json"})).pose, "sit.json");
    EXPECT_EQ(usageMessage({"m.vrm", "-o", "x.png", "--pose", ""}), "--pose: empty value");
}

TEST(AnimationFlags, ExpressionsAndLookAtReachTheStillRequest) {
    const RenderOptions options = parseRenderOptions(
        {"m.vrm", "-o", "x.png", "--expression", "happy=0.5,Blink_L=1,my=odd=0", "--look-at", "1,-2,3.5"});
    const std::vector<ExpressionWeight> expected = {{"happy", 0.5}, {"Blink_L", 1.0}, {"my=odd", 0.0}};
    EXPECT_EQ(options.expressions, expected) << "the last '=' splits, so a name may hold one";
    const StillRequest request = stillRequestOf(options);
    EXPECT_EQ(request.expressions, expected);
    ASSERT_TRUE(request.lookAt.has_value());
    EXPECT_EQ(*request.lookAt, glm::dvec3(1.0, -2.0, 3.5));
}

TEST(AnimationFlags, MalformedExpressionsAreRefused) {
    for (const std::string bad :
         {"happy", "=1", "happy=", "happy=2", "happy=-0.1", "happy=nan", "happy=1,,blink=1", "happy=1,happy=0"}) {
        const std::string message = usageMessage({"m.vrm", "-o", "x.png", "--expression", bad});
        EXPECT_EQ(message.rfind("--expression: ", 0), 0u) << bad << ": " << message;
    }
    EXPECT_EQ(usageMessage({"m.vrm", "-o", "x.png", "--look-at", "1,2"}).rfind("--look-at: ", 0), 0u);
}

TEST(AnimationFlags, AreNotStyleSettings) {
    // A pose belongs to a model, not to a look shared by many.
    const std::vector<std::string>& names = styleSettingNames();
    EXPECT_EQ(std::find(names.begin(), names.end(), "animation"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "time"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "pose"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "expression"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "look-at"), names.end());
    EXPECT_NE(renderFlagsHelp().find("--animation NAME"), std::string::npos);
    EXPECT_NE(renderFlagsHelp().find("--time SECONDS"), std::string::npos);
}

} // namespace
} // namespace inkgraph
