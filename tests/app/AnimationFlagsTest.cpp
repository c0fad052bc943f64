// --animation and --time: parsed into RenderOptions, carried to the still's load, refused when they cannot apply.
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

TEST(AnimationFlags, AreNotStyleSettings) {
    // A pose belongs to a model, not to a look shared by many.
    const std::vector<std::string>& names = styleSettingNames();
    EXPECT_EQ(std::find(names.begin(), names.end(), "animation"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "time"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "pose"), names.end());
    EXPECT_NE(renderFlagsHelp().find("--animation NAME"), std::string::npos);
    EXPECT_NE(renderFlagsHelp().find("--time SECONDS"), std::string::npos);
}

} // namespace
} // namespace inkgraph
