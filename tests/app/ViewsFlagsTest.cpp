// --views and its companions (flags/FlagTable.cpp) and the stills they make (app/Batch.h): values, refusals, {view},
// the checks of a batch's outputs and what each still's options get. No GL.

#include "app/Batch.h"
#include "OptionsTestSupport.h"

#include <gtest/gtest.h>

#include <sstream>

namespace inkgraph {
namespace {

using test::usageMessage;

std::vector<std::string> withViews(std::vector<std::string> extra) {
    std::vector<std::string> arguments = {"m.obj", "-o", "out/{view}.png", "--views", "16"};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    return arguments;
}

bool refusedWith(const std::vector<std::string>& arguments, const std::string& part) {
    const std::string message = usageMessage(arguments);
    EXPECT_NE(message.find(part), std::string::npos) << message;
    return message.find(part) != std::string::npos;
}

TEST(ViewsFlags, ValuesAreParsed) {
    const RenderOptions options = parseRenderOptions(
        withViews({"--seed", "18446744073709551615", "--view-elevation", "5,20,-10,40", "--view-distance-jitter",
                   "0.25", "--light", "0,2,0", "--light-jitter", "30", "--expressions",
                   "happy=1;angry=1,blink=0.5;none", "--poses", "rest,a-pose,wave.json"}));
    EXPECT_TRUE(options.viewsGiven);
    const ViewSampling& sampling = options.viewSampling;
    EXPECT_EQ(sampling.count, 16u);
    EXPECT_EQ(sampling.seed, 18446744073709551615ull);
    EXPECT_EQ(sampling.elevationMean, 5.0);
    EXPECT_EQ(sampling.elevationDeviation, 20.0);
    EXPECT_EQ(sampling.elevationLow, -10.0);
    EXPECT_EQ(sampling.elevationHigh, 40.0);
    EXPECT_EQ(sampling.distanceJitter, 0.25);
    EXPECT_EQ(sampling.lightJitterDegrees, 30.0);
    ASSERT_EQ(sampling.expressionChoices.size(), 3u);
    EXPECT_EQ(sampling.expressionChoices[0], (std::vector<ExpressionWeight>{{"happy", 1.0}}));
    EXPECT_EQ(sampling.expressionChoices[1], (std::vector<ExpressionWeight>{{"angry", 1.0}, {"blink", 0.5}}));
    EXPECT_TRUE(sampling.expressionChoices[2].empty()) << "none";
    EXPECT_EQ(sampling.poseChoices, (std::vector<std::string>{"rest", "a-pose", "wave.json"}));

    const RenderOptions defaults = parseRenderOptions(withViews({"--view-elevation", "0,5"}));
    EXPECT_EQ(defaults.viewSampling.seed, 0u);
    EXPECT_EQ(defaults.viewSampling.elevationLow, -30.0) << "MEAN,SD keeps the default clamp";
    EXPECT_EQ(defaults.viewSampling.elevationHigh, 60.0);
}

TEST(ViewsFlags, RefusalsNameTheFlagAndValue) {
    refusedWith(withViews({"--orbit", "30,10"}), "--views places the eye of each view: it does not go with --orbit");
    refusedWith(withViews({"--eye", "1,2,3"}), "it does not go with --eye");
    refusedWith(withViews({"--expressions", "happy=1", "--expression", "sad=1"}), "does not go with --expression");
    refusedWith(withViews({"--poses", "rest", "--pose", "a-pose"}), "does not go with --pose");
    refusedWith({"m.obj", "-o", "a.png", "--views", "0"}, "--views: expected a whole number from 1 to 100000, got '0'");
    refusedWith({"m.obj", "-o", "a.png", "--views", "100001"}, "got '100001'");
    refusedWith({"m.obj", "-o", "a.png", "--views", "2.5"}, "got '2.5'");
    refusedWith(withViews({"--seed", "-1"}),
                "--seed: expected a whole number from 0 to 18446744073709551615, got '-1'");
    refusedWith(withViews({"--seed", "18446744073709551616"}), "got '18446744073709551616'");
    refusedWith(withViews({"--view-elevation", "10,10,50,40"}), "--view-elevation: LOW must not exceed HIGH");
    refusedWith(withViews({"--view-elevation", "95,10"}), "--view-elevation: MEAN, LOW and HIGH must lie in");
    refusedWith(withViews({"--view-elevation", "10,-1"}), "--view-elevation: SD must lie in [0, 180]");
    refusedWith(withViews({"--view-elevation", "10"}), "expected MEAN,SD or MEAN,SD,LOW,HIGH");
    refusedWith(withViews({"--view-distance-jitter", "0.95"}),
                "--view-distance-jitter: expected a number from 0 to 0.9, got '0.95'");
    refusedWith(withViews({"--light-jitter", "181", "--light", "0,1,0"}),
                "--light-jitter: expected degrees from 0 to 180, got '181'");
    refusedWith(withViews({"--light-jitter", "10"}), "--light-jitter turns --light's direction: give --light");
    refusedWith(withViews({"--expressions", "happy=1;;none"}), "--expressions: an empty alternative in");
    refusedWith(withViews({"--expressions", "happy=2"}), "--expressions: the weight of 'happy' must lie in [0, 1]");
    refusedWith(withViews({"--poses", "rest,,a-pose"}), "--poses: an empty alternative in 'rest,,a-pose'");
    // The companions need --views.
    refusedWith({"m.obj", "-o", "a.png", "--seed", "3"}, "--seed applies to --views N, which is not given");
    refusedWith({"m.obj", "-o", "a.png", "--poses", "rest"}, "--poses applies to --views N");
    refusedWith({"m.obj", "-o", "a.png", "--orbit", "1,2,x0"}, "--orbit: the distance scale xS must have S above 0");
}

TEST(ViewsFlags, OrbitTakesADistanceScale) {
    const RenderOptions options = parseRenderOptions({"m.obj", "-o", "a.png", "--orbit", "12.5,-3,x1.25"});
    ASSERT_TRUE(options.orbit);
    EXPECT_EQ(options.orbit->azimuthDegrees, 12.5);
    EXPECT_EQ(options.orbit->elevationDegrees, -3.0);
    EXPECT_FALSE(options.orbit->distance);
    EXPECT_EQ(options.orbit->distanceScale, 1.25);
}

TEST(ViewsBatch, ViewPlaceholderIsZeroPaddedToTheLastIndex) {
    const BatchModel model{"dir/bunny.obj", 2};
    EXPECT_EQ(expandOutputPattern("{name}-{view}.png", model, 3, 4, 16), "bunny-04.png");
    EXPECT_EQ(expandOutputPattern("{view}.png", model, 3, 9, 10), "9.png") << "0 to 9 is one digit";
    EXPECT_EQ(expandOutputPattern("{view}.png", model, 3, 10, 11), "10.png");
    EXPECT_EQ(expandOutputPattern("{view}.png", model, 3, 3, 101), "003.png");
    EXPECT_EQ(expandOutputPattern("{view}-{index}.png", model, 3), "0-3.png") << "without --views, view 0";
}

TEST(ViewsBatch, StillsAreEachModelsViewsInOrderAndGetTheirView) {
    std::istringstream none;
    RenderOptions options = parseRenderOptions({"a.obj",
                                                "b.obj",
                                                "-o",
                                                "out/{name}-{view}.png",
                                                "--stats",
                                                "out/{index}-{view}.json",
                                                "--views",
                                                "3",
                                                "--seed",
                                                "5",
                                                "--view-distance-jitter",
                                                "0.2",
                                                "--light",
                                                "0,1,0",
                                                "--light-jitter",
                                                "20",
                                                "--expressions",
                                                "happy=1;none",
                                                "--poses",
                                                "rest,a-pose"});
    const BatchList list = batchList(options, none);
    EXPECT_TRUE(list.isBatch);
    const std::vector<BatchStill> stills = batchStills(options, list);
    ASSERT_EQ(stills.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(stills[i].model.path, i < 3 ? "a.obj" : "b.obj");
        EXPECT_EQ(stills[i].viewIndex, i % 3);
        ASSERT_TRUE(stills[i].view);
        EXPECT_EQ(*stills[i].view, sampleView(viewSamplingOf(options), stills[i].model.path, i % 3));
    }
    const RenderOptions still = stillOptions(options, stills[4], list.total);
    const ViewSample& view = *stills[4].view;
    EXPECT_EQ(still.outputPath, "out/b-1.png");
    EXPECT_EQ(still.statsPath, "out/2-1.json");
    ASSERT_TRUE(still.orbit);
    EXPECT_EQ(still.orbit->azimuthDegrees, view.azimuthDegrees);
    EXPECT_EQ(still.orbit->elevationDegrees, view.elevationDegrees);
    EXPECT_EQ(still.orbit->distanceScale, view.distanceScale);
    EXPECT_FALSE(still.orbit->distance) << "the auto-framing distance, scaled";
    // The light as --light would make the recorded numbers: unit length, along them.
    ASSERT_TRUE(still.look.towardLight);
    EXPECT_NEAR(glm::length(*still.look.towardLight), 1.0, 1e-15);
    EXPECT_NEAR(glm::dot(*still.look.towardLight, glm::normalize(*view.towardLight)), 1.0, 1e-15);
    EXPECT_EQ(still.expressions, *view.expressions);
    EXPECT_EQ(still.pose, *view.pose == "rest" ? "" : *view.pose);
    ASSERT_TRUE(still.view);
    EXPECT_EQ(*still.view, view);
    // A shard takes whole models: the views of a model are the same in any split.
    options.shard = Shard{1, 2};
    const std::vector<BatchStill> share = batchStills(options, batchList(options, none));
    ASSERT_EQ(share.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(*share[i].view, *stills[3 + i].view);
}

TEST(ViewsBatch, EveryOutputNeedsViewWithSeveralViewsAndStillsMustNotCollide) {
    std::istringstream none;
    const auto refusal = [&none](const std::vector<std::string>& arguments) -> std::string {
        const RenderOptions options = parseRenderOptions(arguments);
        try {
            checkBatchOutputs(options, batchList(options, none));
        } catch (const UsageError& error) {
            return error.what();
        }
        return "";
    };
    std::string message = refusal({"a.obj", "-o", "out/a.png", "--views", "4"});
    EXPECT_NE(message.find("-o 'out/a.png' would be the same file for all 4 views of --views; put {view} in it, e.g. "
                           "'out/{name}-{view}.png'"),
              std::string::npos)
        << message;
    message = refusal({"a.obj", "b.obj", "-o", "out/{view}.png", "--views", "2"});
    EXPECT_NE(message.find("would be the same file for all 2 models; put {name} or {index} in it, e.g. "
                           "'out/{name}-{view}.png'"),
              std::string::npos)
        << message;
    message = refusal({"a.obj", "-o", "out/{view}.png", "--stats", "s.json", "--views", "2"});
    EXPECT_NE(message.find("--stats 's.json' would be the same file for all 2 views"), std::string::npos) << message;
    EXPECT_EQ(refusal({"a.obj", "b.obj", "-o", "out/{name}-{view}.png", "--views", "2"}), "");
    EXPECT_EQ(refusal({"a.obj", "-o", "out/a.png", "--views", "1"}), "") << "one view needs no {view}";
    // Two models of one name: their views collide without {index}.
    message = refusal({"x/a.obj", "y/a.obj", "-o", "out/{name}-{view}.png", "--views", "2"});
    EXPECT_NE(message.find("-o 'out/a-0.png' is written for both 'x/a.obj' (list position 1, view 0) and 'y/a.obj' "
                           "(list position 2, view 0); models of one name need {index}"),
              std::string::npos)
        << message;
}

} // namespace
} // namespace inkgraph
