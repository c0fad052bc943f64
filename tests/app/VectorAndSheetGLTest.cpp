// --svg and --contact-sheet from the real `inkgraph` executable: the SVG parses back (tests/support/SvgPaths.h) into
// one group per line type whose paths lie on that type's line mask, and the contact sheet holds exactly the buffers
// the plan computed, laid out as postfx/ContactSheet.h says. Needs a GL context (llvmpipe in CI).
#include "render/ImageFiles.h"
#include "CliTestSupport.h"
#include "postfx/ContactSheet.h"
#include "tests/support/SvgPaths.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>

namespace inkgraph {
namespace {

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

/** Distance (output pixels) from each pixel centre to the nearest pixel the mask draws on at all. */
cv::Mat distanceToMask(const cv::Mat& mask) {
    cv::Mat off = mask == 0; // 255 where nothing is drawn
    cv::Mat distance;
    cv::distanceTransform(off, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    return distance;
}

/** Samples every path of `group` each 0.25 output pixels; SVG user units are output pixels with pixel (col, row)
 *  covering [col, col + 1) x [row, row + 1). */
std::vector<cv::Point2d> samplesOf(const test::SvgPathGroup& group) {
    std::vector<cv::Point2d> samples;
    for (std::size_t p = 0; p < group.paths.size(); ++p) {
        std::vector<cv::Point2d> path = group.paths[p];
        if (group.closed[p] && path.size() > 1) path.push_back(path.front());
        for (std::size_t i = 0; i + 1 < path.size(); ++i) {
            const double length = cv::norm(path[i + 1] - path[i]);
            const int steps = std::max(1, int(std::ceil(length / 0.25)));
            for (int s = 0; s < steps; ++s) samples.push_back(path[i] + (path[i + 1] - path[i]) * (double(s) / steps));
        }
        samples.push_back(path.back());
    }
    return samples;
}

/** Checks `group`'s paths against `mask` (the type's dumped line layer, frame-sized): every sample lies within
 *  `onTolerance` of a drawn pixel, and every fully drawn pixel lies within `reach` of a sample, so the SVG neither
 *  invents nor loses lines. */
void expectPathsOnMask(const test::SvgPathGroup& group, const cv::Mat& mask, double onTolerance, double reach) {
    ASSERT_FALSE(group.paths.empty()) << group.id;
    const cv::Mat distance = distanceToMask(mask);
    const std::vector<cv::Point2d> samples = samplesOf(group);
    double worst = 0.0;
    for (const cv::Point2d& sample : samples) {
        const int col = std::clamp(int(std::floor(sample.x)), 0, mask.cols - 1);
        const int row = std::clamp(int(std::floor(sample.y)), 0, mask.rows - 1);
        worst = std::max(worst, double(distance.at<float>(row, col)));
    }
    EXPECT_LE(worst, onTolerance) << group.id << ": a path leaves the mask by " << worst << " px";

    cv::Mat sampled = cv::Mat::zeros(mask.size(), CV_8UC1);
    for (const cv::Point2d& sample : samples) {
        const int col = std::clamp(int(std::floor(sample.x)), 0, mask.cols - 1);
        const int row = std::clamp(int(std::floor(sample.y)), 0, mask.rows - 1);
        sampled.at<uchar>(row, col) = 255;
    }
    const cv::Mat toPath = distanceToMask(sampled);
    double farthest = 0.0;
    for (int row = 0; row < mask.rows; ++row)
        for (int col = 0; col < mask.cols; ++col)
            if (mask.at<uchar>(row, col) == 255) farthest = std::max(farthest, double(toPath.at<float>(row, col)));
    EXPECT_LE(farthest, reach) << group.id << ": a drawn pixel is " << farthest << " px from every path";
}

TEST_F(Cli, SvgHasOneGroupPerLineTypeWhosePathsLieOnItsMask) {
    for (const int supersample : {1, 2}) {
        SCOPED_TRACE("supersample " + std::to_string(supersample));
        const CliRun result =
            run("render " + model("suzanne_npm_4k.obj") +
                " --size 160x120 --lines outline,crease,border,contour --border-color 0.8,0.1,0.1,0.5 " +
                "--outline-width 4 --supersample " + std::to_string(supersample) + " --svg lines.svg --dump dump -q");
        ASSERT_EQ(result.exitCode, 0) << result.err;
        const test::SvgPathDocument document = test::parseSvgPathDocument(readText(directory / "lines.svg"));
        EXPECT_EQ(document.width, 160);
        EXPECT_EQ(document.height, 120);
        EXPECT_NE(document.title.find("suzanne_npm_4k.obj"), std::string::npos) << document.title;
        // The composite's order (later on top), whatever the order of --lines.
        ASSERT_EQ(document.groups.size(), 4u);
        EXPECT_EQ(document.groups[0].id, "lines-outline");
        EXPECT_EQ(document.groups[1].id, "lines-crease");
        EXPECT_EQ(document.groups[2].id, "lines-border");
        EXPECT_EQ(document.groups[3].id, "lines-contour");
        EXPECT_EQ(document.groups[0].strokeWidth, 4.0);
        EXPECT_EQ(document.groups[3].strokeWidth, 2.0);
        EXPECT_EQ(document.groups[2].stroke, "#cc1a1a");
        EXPECT_DOUBLE_EQ(document.groups[2].opacity, 0.5);
        for (const test::SvgPathGroup& group : document.groups) {
            const cv::Mat mask = readImage(directory / "dump" / ("lines-" + group.label + ".png"));
            ASSERT_EQ(mask.type(), CV_8UC1) << group.label;
            if (group.label != "outline") {
                // One-pixel skeletons stroked at their width: the traced centre lines (sub-pixel, simplified within
                // 0.5 px) stay inside the stroke, and the stroke reaches half its width (+ the pixel grid) past them.
                expectPathsOnMask(group, mask, 0.0, group.strokeWidth / 2.0 + 1.5);
            } else {
                // A band GL drew, thinned to its medial line on pixel centres: simplifying within 0.5 px may cut a
                // corner into the next pixel, and where bands merge into a blob its pixels are as far from the
                // medial line as the blob's widest inscribed circle, not half the stroke.
                cv::Mat insideDistance;
                cv::distanceTransform(mask > 0, insideDistance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
                double inscribed = 0.0;
                cv::minMaxLoc(insideDistance, nullptr, &inscribed);
                expectPathsOnMask(group, mask, 1.0, inscribed + 1.0);
            }
        }
    }
}

TEST_F(Cli, SvgAloneRendersAndWritesNothingElse) {
    const CliRun result = run("render " + model("spot_c3d.obj") + " --size 64x64 --lines contour --svg only.svg -q");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>({"only.svg"}));
    const auto groups = test::parseSvgPathGroups(readText(directory / "only.svg"));
    ASSERT_EQ(groups.size(), 1u);
    EXPECT_FALSE(groups[0].paths.empty());
}

TEST_F(Cli, ContactSheetShowsEveryBufferThePlanComputed) {
    const CliRun result = run("render " + model("spot_c3d.obj") + " --size 96x64 --lines contour,outline " +
                              "--request 'gbuffer.*' --dump dump --contact-sheet sheet.png -o final.png -q");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto manifest = nlohmann::json::parse(readText(directory / "dump" / "manifest.json"));
    const std::size_t buffers = manifest["files"].size();
    EXPECT_GE(buffers, 12u); // eight G-buffer fields, shading, two line layers, final

    const cv::Mat sheet = readImage(directory / "sheet.png");
    ASSERT_EQ(sheet.type(), CV_8UC4);
    ContactSheetLayout layout;
    layout.title = "title"; // the CLI always writes one
    EXPECT_EQ(sheet.size(), contactSheetSize(int(buffers), {96, 64}, layout))
        << "one tile per dumped buffer, no more, no fewer";

    // The cell of the final picture holds the final picture as tileImage() shows it (8-bit PNG: exact).
    std::size_t finalIndex = buffers;
    for (std::size_t i = 0; i < buffers; ++i)
        if (manifest["files"][i]["resource"] == "composite.final") finalIndex = i;
    ASSERT_LT(finalIndex, buffers);
    const int columns = int(std::ceil(std::sqrt(double(buffers))));
    const int tileHeight = int(std::lround(layout.tileWidth * 64.0 / 96.0));
    const int x =
        ContactSheetLayout::kSpacing + int(finalIndex % columns) * (layout.tileWidth + ContactSheetLayout::kSpacing);
    const int y =
        ContactSheetLayout::kTitleBarHeight + ContactSheetLayout::kSpacing +
        int(finalIndex / columns) * (tileHeight + ContactSheetLayout::kCaptionHeight + ContactSheetLayout::kSpacing);
    const cv::Mat expected =
        tileImage(readImage(directory / "final.png"), TileContent::Color, {layout.tileWidth, tileHeight});
    const cv::Mat cell = sheet(cv::Rect(x, y, layout.tileWidth, tileHeight));
    EXPECT_EQ(cv::norm(cell, expected, cv::NORM_INF), 0.0);
}

TEST_F(Cli, ContactSheetOfALinesOnlyPlanHasNoGBuffer) {
    // Outline with cel shading needs no G-buffer: the sheet shows what ran, nothing more.
    const CliRun result = run("render " + model("spot_c3d.obj") +
                              " --size 64x64 --lines outline --contact-sheet sheet.png --stats stats.json -q");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const cv::Mat sheet = readImage(directory / "sheet.png");
    ContactSheetLayout layout;
    layout.title = "title";
    EXPECT_EQ(sheet.size(), contactSheetSize(3, {64, 64}, layout)) << "shade.color, outline.lines, composite.final";
    const auto stats = nlohmann::json::parse(readText(directory / "stats.json"));
    bool gbufferCulled = false;
    for (const auto& culled : stats["culled"]) gbufferCulled |= culled["name"] == "gbuffer";
    EXPECT_TRUE(gbufferCulled);
}

} // namespace
} // namespace inkgraph
