// postfx/Composite on synthetic layers; no GL.
#include "postfx/Composite.h"

#include <gtest/gtest.h>

namespace inkgraph {
namespace {

TEST(Composite, PaperAloneWithoutShading) {
    CompositeInputs inputs;
    inputs.size = {5, 3};
    inputs.paper = {1.0f, 0.5f, 0.0f, 1.0f};
    const cv::Mat result = compositeFinal(inputs);
    ASSERT_EQ(result.type(), CV_8UC4);
    ASSERT_EQ(result.size(), cv::Size(5, 3));
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 5; ++col) EXPECT_EQ(result.at<cv::Vec4b>(row, col), cv::Vec4b(255, 128, 0, 255));
}

TEST(Composite, ShadingOverPaperByAlpha) {
    CompositeInputs inputs;
    inputs.size = {3, 1};
    inputs.paper = {1.0f, 1.0f, 1.0f, 1.0f};
    inputs.shading = cv::Mat(1, 3, CV_8UC4);
    inputs.shading.at<cv::Vec4b>(0, 0) = {10, 20, 30, 255}; // covered: the shading itself
    inputs.shading.at<cv::Vec4b>(0, 1) = {10, 20, 30, 0};   // background: paper
    inputs.shading.at<cv::Vec4b>(0, 2) = {0, 0, 0, 128};    // half: halfway to white
    const cv::Mat result = compositeFinal(inputs);
    EXPECT_EQ(result.at<cv::Vec4b>(0, 0), cv::Vec4b(10, 20, 30, 255));
    EXPECT_EQ(result.at<cv::Vec4b>(0, 1), cv::Vec4b(255, 255, 255, 255));
    EXPECT_EQ(result.at<cv::Vec4b>(0, 2), cv::Vec4b(127, 127, 127, 255));
}

TEST(Composite, RejectsWrongLayers) {
    CompositeInputs inputs;
    inputs.size = {4, 4};
    inputs.shading = cv::Mat(4, 4, CV_32FC4);
    EXPECT_THROW(compositeFinal(inputs), std::invalid_argument);
    inputs.shading = cv::Mat(2, 4, CV_8UC4);
    EXPECT_THROW(compositeFinal(inputs), std::invalid_argument);
    inputs.shading.release();
    inputs.paper = {2.0f, 0.0f, 0.0f, 1.0f};
    EXPECT_THROW(compositeFinal(inputs), std::invalid_argument);
    inputs.size = {0, 4};
    EXPECT_THROW(compositeFinal(inputs), std::invalid_argument);
}

TEST(Composite, LineLayersOverShadingInOrder) {
    CompositeInputs inputs;
    inputs.size = {4, 1};
    inputs.paper = {1.0f, 1.0f, 1.0f, 1.0f};
    inputs.shading = cv::Mat(1, 4, CV_8UC4, cv::Scalar(100, 100, 100, 255));
    cv::Mat first(1, 4, CV_8UC1, cv::Scalar(0));
    first.at<uchar>(0, 1) = 255; // full line: the line colour
    first.at<uchar>(0, 2) = 255;
    first.at<uchar>(0, 3) = 51; // partial coverage: 20% of the way from the shading to the line colour
    cv::Mat second(1, 4, CV_8UC1, cv::Scalar(0));
    second.at<uchar>(0, 2) = 255; // drawn after the first: on top
    inputs.lines.push_back({"first", first, {0.0f, 0.0f, 0.0f, 1.0f}});
    inputs.lines.push_back({"second", second, {1.0f, 0.0f, 0.0f, 1.0f}});
    const cv::Mat result = compositeFinal(inputs);
    EXPECT_EQ(result.at<cv::Vec4b>(0, 0), cv::Vec4b(100, 100, 100, 255)) << "no line: the shading";
    EXPECT_EQ(result.at<cv::Vec4b>(0, 1), cv::Vec4b(0, 0, 0, 255));
    EXPECT_EQ(result.at<cv::Vec4b>(0, 2), cv::Vec4b(255, 0, 0, 255)) << "the later layer wins";
    EXPECT_EQ(result.at<cv::Vec4b>(0, 3), cv::Vec4b(80, 80, 80, 255));
}

TEST(Composite, LineColourAlphaScalesTheMask) {
    CompositeInputs inputs;
    inputs.size = {1, 1};
    inputs.paper = {1.0f, 1.0f, 1.0f, 1.0f};
    inputs.lines.push_back({"half", cv::Mat(1, 1, CV_8UC1, cv::Scalar(255)), {0.0f, 0.0f, 0.0f, 0.5f}});
    EXPECT_EQ(compositeFinal(inputs).at<cv::Vec4b>(0, 0), cv::Vec4b(127, 127, 127, 255));
}

TEST(Composite, RejectsWrongLineLayersByName) {
    CompositeInputs inputs;
    inputs.size = {4, 4};
    inputs.lines.push_back({"outline", cv::Mat(4, 4, CV_8UC4), {0.0f, 0.0f, 0.0f, 1.0f}});
    try {
        compositeFinal(inputs);
        FAIL() << "a 4-channel mask was accepted";
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("'outline'"), std::string::npos) << error.what();
    }
    inputs.lines[0].mask = cv::Mat(4, 4, CV_8UC1, cv::Scalar(0));
    inputs.lines[0].color = {0.0f, 0.0f, 1.5f, 1.0f};
    EXPECT_THROW(compositeFinal(inputs), std::invalid_argument);
}

} // namespace
} // namespace inkgraph

namespace inkgraph {

TEST(Composite, PremultipliedShadingGoesOverThePaperOnce) {
    // A blended surface over nothing leaves colour x alpha: red at half alpha is (128, 0, 0, 128) in the shading,
    // and over white paper it is red 255 x 0.5 + 255 x 0.5 in red, 255 x 0.5 in green and blue.
    CompositeInputs inputs;
    inputs.size = {1, 1};
    inputs.paper = {1.0, 1.0, 1.0, 1.0};
    inputs.shading = cv::Mat(1, 1, CV_8UC4, cv::Scalar(128, 0, 0, 128));
    EXPECT_EQ(compositeFinal(inputs).at<cv::Vec4b>(0, 0), cv::Vec4b(255, 127, 127, 255));
}

TEST(Composite, StraightAlphaUndoesThePremultiplication) {
    cv::Mat shading(1, 4, CV_8UC4);
    shading.at<cv::Vec4b>(0, 0) = {64, 32, 0, 128};     // half covered
    shading.at<cv::Vec4b>(0, 1) = {10, 20, 30, 255};    // opaque: unchanged
    shading.at<cv::Vec4b>(0, 2) = {0, 0, 0, 0};         // empty: unchanged
    shading.at<cv::Vec4b>(0, 3) = {200, 200, 200, 100}; // more than alpha (not premultiplied): clamped
    const cv::Mat straight = straightAlphaOf(shading);
    EXPECT_EQ(straight.at<cv::Vec4b>(0, 0), cv::Vec4b(128, 64, 0, 128));
    EXPECT_EQ(straight.at<cv::Vec4b>(0, 1), cv::Vec4b(10, 20, 30, 255));
    EXPECT_EQ(straight.at<cv::Vec4b>(0, 2), cv::Vec4b(0, 0, 0, 0));
    EXPECT_EQ(straight.at<cv::Vec4b>(0, 3), cv::Vec4b(255, 255, 255, 100));
    EXPECT_EQ(shading.at<cv::Vec4b>(0, 0), cv::Vec4b(64, 32, 0, 128)) << "the input is not changed";
}

} // namespace inkgraph
