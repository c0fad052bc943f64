// The random views of --views (scene/ViewSampling.h): determinism, independence of the settings' draws, and the
// distributions over 20,000 samples. Each statistical tolerance is about 5 standard errors of the estimate, so a
// correct sampler passes (the seed is fixed: the test is deterministic) and a wrong distribution fails.

#include "scene/ViewSampling.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace inkgraph {
namespace {

constexpr std::size_t kSamples = 20000;
const std::string kModel = "models/suzanne_npm_4k.obj";

ViewSampling manyViews() {
    ViewSampling sampling;
    sampling.count = kSamples;
    sampling.seed = 12345;
    return sampling;
}

TEST(ViewSamplingTest, SameInputsGiveTheSameSampleAndEachKeyChangesIt) {
    ViewSampling sampling;
    sampling.count = 8;
    sampling.seed = 7;
    sampling.distanceJitter = 0.2;
    const ViewSample first = sampleView(sampling, kModel, 3);
    EXPECT_EQ(first, sampleView(sampling, kModel, 3));
    EXPECT_EQ(first, sampleViews(sampling, kModel)[3]) << "one view alone is that view of the whole list";
    EXPECT_NE(first.azimuthDegrees, sampleView(sampling, kModel, 4).azimuthDegrees) << "another view";
    EXPECT_NE(first.azimuthDegrees, sampleView(sampling, "models/cow_c3d.obj", 3).azimuthDegrees) << "another model";
    ViewSampling otherSeed = sampling;
    otherSeed.seed = 8;
    EXPECT_NE(first.azimuthDegrees, sampleView(otherSeed, kModel, 3).azimuthDegrees) << "another seed";
    ViewSampling moreViews = sampling;
    moreViews.count = 100;
    EXPECT_EQ(first, sampleView(moreViews, kModel, 3)) << "the count only bounds the index";
}

TEST(ViewSamplingTest, SettingsThatAreOffTakeTheirDrawsSoTurningThemOnLeavesTheRest) {
    ViewSampling plain;
    plain.count = 50;
    ViewSampling everything = plain;
    everything.distanceJitter = 0.5;
    everything.lightJitterDegrees = 40.0;
    everything.light = glm::dvec3(0.0, 1.0, 0.0);
    everything.expressionChoices = {{}, {{"happy", 1.0}}};
    everything.poseChoices = {"rest", "a-pose"};
    for (std::size_t index = 0; index < plain.count; ++index) {
        const ViewSample without = sampleView(plain, kModel, index);
        const ViewSample with = sampleView(everything, kModel, index);
        EXPECT_EQ(without.azimuthDegrees, with.azimuthDegrees) << index;
        EXPECT_EQ(without.elevationDegrees, with.elevationDegrees) << index;
        EXPECT_EQ(without.distanceScale, 1.0);
        EXPECT_FALSE(without.towardLight || without.expressions || without.pose);
        EXPECT_TRUE(with.towardLight && with.expressions && with.pose);
    }
}

TEST(ViewSamplingTest, ValuesAreQuantizedSoTheirTextReadsBackExactly) {
    ViewSampling sampling;
    sampling.count = 200;
    sampling.distanceJitter = 0.3;
    sampling.lightJitterDegrees = 20.0;
    sampling.light = glm::dvec3(1.0, 1.0, 1.0);
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        EXPECT_EQ(sample.azimuthDegrees, std::round(sample.azimuthDegrees * 1e6) / 1e6);
        EXPECT_EQ(sample.elevationDegrees, std::round(sample.elevationDegrees * 1e6) / 1e6);
        EXPECT_EQ(sample.distanceScale, std::round(sample.distanceScale * 1e9) / 1e9);
        for (int axis = 0; axis < 3; ++axis)
            EXPECT_EQ((*sample.towardLight)[axis], std::round((*sample.towardLight)[axis] * 1e9) / 1e9);
    }
}

TEST(ViewSamplingTest, AzimuthIsUniformOverTheCircle) {
    const std::vector<ViewSample> samples = sampleViews(manyViews(), kModel);
    double sum = 0.0, sumSquares = 0.0;
    for (const ViewSample& sample : samples) {
        ASSERT_GE(sample.azimuthDegrees, 0.0);
        ASSERT_LT(sample.azimuthDegrees, 360.0);
        sum += sample.azimuthDegrees;
        sumSquares += sample.azimuthDegrees * sample.azimuthDegrees;
    }
    const double mean = sum / kSamples;
    const double variance = sumSquares / kSamples - mean * mean;
    // Uniform on [0, 360): mean 180 (standard error 360/sqrt(12 n) = 0.73), variance 360^2/12 = 10800 (standard error
    // 360^2 sqrt(1/80 - 1/144) / sqrt(n) = 68).
    EXPECT_NEAR(mean, 180.0, 3.7);
    EXPECT_NEAR(variance, 10800.0, 340.0);
}

TEST(ViewSamplingTest, ElevationIsNormalAboutTheMean) {
    ViewSampling sampling = manyViews();
    sampling.elevationMean = 5.0;
    sampling.elevationDeviation = 10.0;
    sampling.elevationLow = -89.9; // 9.5 deviations away: no sample is clamped
    sampling.elevationHigh = 89.9;
    double sum = 0.0, sumSquares = 0.0;
    std::size_t withinOne = 0;
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        sum += sample.elevationDegrees;
        sumSquares += sample.elevationDegrees * sample.elevationDegrees;
        withinOne += std::abs(sample.elevationDegrees - 5.0) <= 10.0;
    }
    const double mean = sum / kSamples;
    const double deviation = std::sqrt(sumSquares / kSamples - mean * mean);
    // Standard errors: of the mean 10/sqrt(n) = 0.071, of the deviation 10/sqrt(2n) = 0.05, of the fraction within one
    // deviation (0.6827) sqrt(0.6827 x 0.3173 / n) = 0.0033.
    EXPECT_NEAR(mean, 5.0, 0.36);
    EXPECT_NEAR(deviation, 10.0, 0.25);
    EXPECT_NEAR(double(withinOne) / kSamples, 0.6827, 0.017);
}

TEST(ViewSamplingTest, ElevationIsClampedToItsBounds) {
    ViewSampling sampling = manyViews();
    sampling.elevationMean = 10.0;
    sampling.elevationDeviation = 30.0;
    sampling.elevationLow = -5.0;
    sampling.elevationHigh = 20.0;
    std::size_t atLow = 0, atHigh = 0;
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        ASSERT_GE(sample.elevationDegrees, -5.0);
        ASSERT_LE(sample.elevationDegrees, 20.0);
        atLow += sample.elevationDegrees == -5.0;
        atHigh += sample.elevationDegrees == 20.0;
    }
    // P(N(10, 30) <= -5) = Phi(-0.5) = 0.3085, P(>= 20) = 1 - Phi(1/3) = 0.3694; standard errors 0.0033 and 0.0034.
    EXPECT_NEAR(double(atLow) / kSamples, 0.3085, 0.017);
    EXPECT_NEAR(double(atHigh) / kSamples, 0.3694, 0.017);
}

TEST(ViewSamplingTest, DistanceScaleIsUniformWithinTheJitter) {
    ViewSampling sampling = manyViews();
    sampling.distanceJitter = 0.2;
    double sum = 0.0, lowest = 2.0, highest = 0.0;
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        lowest = std::min(lowest, sample.distanceScale);
        highest = std::max(highest, sample.distanceScale);
        sum += sample.distanceScale;
    }
    EXPECT_GE(lowest, 0.8);
    EXPECT_LE(highest, 1.2);
    // Uniform: the extremes of n samples lie within about 0.4/n = 2e-5 of the bounds.
    EXPECT_LT(lowest, 0.8005);
    EXPECT_GT(highest, 1.1995);
    // Mean 1, standard error 0.4/sqrt(12 n) = 0.00082.
    EXPECT_NEAR(sum / kSamples, 1.0, 0.0041);
}

TEST(ViewSamplingTest, LightIsUniformOnTheCapAboutTheRunsLight) {
    ViewSampling sampling = manyViews();
    sampling.lightJitterDegrees = 30.0;
    sampling.light = glm::dvec3(1.0, 2.0, 3.0); // made unit length, as --light makes it
    const glm::dvec3 axis = glm::normalize(*sampling.light);
    double largestTurn = 0.0;
    std::size_t withinHalf = 0;
    glm::dvec3 sum(0.0);
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        const glm::dvec3 light = *sample.towardLight;
        ASSERT_NEAR(glm::length(light), 1.0, 2e-9) << "components quantized to 1e-9";
        const double turn = glm::degrees(std::acos(std::min(1.0, glm::dot(glm::normalize(light), axis))));
        largestTurn = std::max(largestTurn, turn);
        withinHalf += turn <= 15.0;
        sum += glm::normalize(light);
    }
    EXPECT_LE(largestTurn, 30.0 + 1e-6);
    EXPECT_GT(largestTurn, 29.9) << "the cap is filled to its rim";
    // Uniform on the cap, the area within 15 degrees is (1 - cos 15)/(1 - cos 30) = 0.2543 of it (standard error
    // 0.0031); the mean direction is the axis by symmetry (its sideways part has standard error ~0.2/sqrt(n) =
    // 0.0015 per axis).
    EXPECT_NEAR(double(withinHalf) / kSamples, 0.2543, 0.016);
    const glm::dvec3 mean = sum / double(kSamples);
    EXPECT_NEAR(glm::length(mean - glm::dot(mean, axis) * axis), 0.0, 0.01);
}

TEST(ViewSamplingTest, ChoicesAreUniformAmongTheAlternatives) {
    ViewSampling sampling = manyViews();
    sampling.expressionChoices = {{}, {{"happy", 1.0}}, {{"angry", 1.0}, {"blink", 0.5}}};
    sampling.poseChoices = {"rest", "a-pose", "pose.json"};
    std::size_t expressionCounts[3] = {0, 0, 0}, poseCounts[3] = {0, 0, 0};
    for (const ViewSample& sample : sampleViews(sampling, kModel)) {
        for (std::size_t i = 0; i < 3; ++i) {
            expressionCounts[i] += *sample.expressions == sampling.expressionChoices[i];
            poseCounts[i] += *sample.pose == sampling.poseChoices[i];
        }
    }
    // 1/3 each, standard error sqrt(2/9/n) = 0.0033.
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(double(expressionCounts[i]) / kSamples, 1.0 / 3.0, 0.017) << i;
        EXPECT_NEAR(double(poseCounts[i]) / kSamples, 1.0 / 3.0, 0.017) << i;
    }
    EXPECT_EQ(expressionSetText(sampling.expressionChoices[0]), "none");
    EXPECT_EQ(expressionSetText(sampling.expressionChoices[2]), "angry=1,blink=0.5");
}

// The stream itself, so an accidental change is caught (outputs of every earlier data set would change). Computed by
// an independent implementation (FNV-1a 64, splitmix64, Box-Muller as scene/ViewSampling.h states them, in Python);
// the samples are also what `PYTHONPATH=build/python python3 -c "import inkgraph; print(inkgraph.sample_views(3, 1,
// 'models/suzanne_npm_4k.obj', distance_jitter=0.1, expressions=['none', 'happy=1', 'sad=1'], poses=['rest',
// 'a-pose']))"` prints.
TEST(ViewSamplingTest, GoldenStreamForSeedOne) {
    ViewRandom random(1, kModel, 0);
    EXPECT_EQ(random.next(), 0x22093031abb7efebull);
    EXPECT_EQ(random.next(), 0xdacec4bb822ae06bull);

    ViewSampling sampling;
    sampling.count = 3;
    sampling.seed = 1;
    sampling.distanceJitter = 0.1;
    sampling.expressionChoices = {{}, {{"happy", 1.0}}, {{"sad", 1.0}}};
    sampling.poseChoices = {"rest", "a-pose"};
    const std::vector<ViewSample> samples = sampleViews(sampling, kModel);
    const double expected[3][3] = {
        {47.862973, -7.00786, 0.952946094}, {117.818677, 2.874432, 0.967998818}, {153.337869, 13.91881, 1.048868829}};
    const std::size_t expectedExpression[3] = {1, 1, 2};            // draws 0.3487, 0.4493, 0.8286 of 3
    const std::string expectedPose[3] = {"rest", "rest", "a-pose"}; // draws 0.1060, 0.0068, 0.6314 of 2
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(samples[i].azimuthDegrees, expected[i][0]) << i;
        EXPECT_EQ(samples[i].elevationDegrees, expected[i][1]) << i;
        EXPECT_EQ(samples[i].distanceScale, expected[i][2]) << i;
        EXPECT_EQ(*samples[i].expressions, sampling.expressionChoices[expectedExpression[i]]) << i;
        EXPECT_EQ(*samples[i].pose, expectedPose[i]) << i;
    }
}

TEST(ViewSamplingTest, SettingsOutOfRangeAreRefused) {
    const auto refusal = [](const ViewSampling& sampling, std::size_t index = 0) -> std::string {
        try {
            sampleView(sampling, kModel, index);
        } catch (const std::invalid_argument& error) {
            return error.what();
        }
        return "";
    };
    ViewSampling sampling;
    sampling.count = 2;
    EXPECT_NE(refusal(sampling, 2).find("view index 2 is not below the count 2"), std::string::npos);
    ViewSampling bad = sampling;
    bad.elevationLow = 30.0;
    bad.elevationHigh = 20.0;
    EXPECT_EQ(refusal(bad).rfind("sampleView(): the elevation's low", 0), 0u);
    bad = sampling;
    bad.distanceJitter = 0.95;
    EXPECT_NE(refusal(bad).find("'distanceJitter'"), std::string::npos);
    bad = sampling;
    bad.lightJitterDegrees = 10.0;
    EXPECT_NE(refusal(bad).find("needs the 'light'"), std::string::npos);
    bad = sampling;
    bad.count = 0;
    EXPECT_NE(refusal(bad).find("'count'"), std::string::npos);
}

} // namespace
} // namespace inkgraph
