// Forward shading of analytic spheres against ray-cast expectations: cel band borders at the predicted angles, the
// specular highlight where the reflection vector meets the eye (phong and comic), shininess 0 and 1e6 without
// speckle, the GLSL specularTerm against double pow, flat faces, gouraud against lambert, and lambert against its
// formula. Needs a GL context (llvmpipe in CI).
#include "gl/GraphExecutor.h"
#include "gl/Readback.h"
#include "gl/ShaderLibrary.h"
#include "graph/GraphCompiler.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/SceneOrientation.h"
#include "passes/shade/ShadeMap.h"
#include "passes/shade/ShadePass.h"
#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/ImageCompare.h"
#include "tests/support/AnalyticSphere.h"
#include "tests/support/PassHarness.h"
#include "tests/support/Srgb.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph::shade_gl_test {
namespace {

constexpr int kSize = 256;
constexpr double kRadius = 1.0;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 35.0;

using test::decodeSrgb;
using test::encodeSrgb;
using test::linearOf;
using test::srgbCode;

const test::AnalyticSphereView kSphere{kSize, kRadius, kDistance, kFovDegrees};
const glm::dvec3 kCenter = kSphere.center();

/** The point of the sphere where r = reflect(-l, n) meets the eye: n = normalize(l + v), solved by fixed-point
 *  iteration (v depends on the point; with a constant v it is exact at once). */
glm::dvec3 highlightPoint(const glm::dvec3& towardLight, std::optional<glm::dvec3> constantTowardEye) {
    glm::dvec3 normal = glm::normalize(towardLight + glm::dvec3(0.0, 0.0, 1.0));
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 point = kCenter + kRadius * normal;
        const glm::dvec3 towardEye = constantTowardEye ? *constantTowardEye : glm::normalize(-point);
        normal = glm::normalize(towardLight + towardEye);
    }
    return kCenter + kRadius * normal;
}

/** max(r.v, 0)^n, gated by n.l > 0, in double. */
double specularReference(const glm::dvec3& normal, const glm::dvec3& towardLight, const glm::dvec3& towardEye,
                         double shininess) {
    if (glm::dot(normal, towardLight) <= 0.0) return 0.0;
    if (shininess == 0.0) return 1.0;
    const glm::dvec3 reflected = glm::reflect(-towardLight, normal);
    return std::pow(std::max(glm::dot(reflected, towardEye), 0.0), shininess);
}

cv::Vec4b pixelAt(const cv::Mat& image, int col, int row) { return image.at<cv::Vec4b>(row, col); }

class ShadeSphere : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** A UV sphere of radius 1 at the origin seen from (0, 0, kDistance): view space is world space shifted. */
    void useSphere(int segments, int rings, glm::vec4 baseColor) {
        Mesh mesh = makeUvSphere({0.0f, 0.0f, 0.0f}, float(kRadius), segments, rings);
        mesh.material.baseColorFactor = baseColor;
        scene = makeScene(std::move(mesh));
        frame.camera =
            test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    }

    void setLight(const glm::dvec3& towardLightWorld) { frame.towardLightWorld = glm::normalize(towardLightWorld); }
    /** The light in view space, in double (the camera only translates here, but go through its matrix anyway). */
    glm::dvec3 lightView() const {
        return glm::normalize(glm::dmat3(frame.camera.viewMatrix()) * frame.towardLightWorld);
    }

    /** Runs one ShadePass and returns its colour, row 0 at the top. */
    cv::Mat render(const ShadeSettings& settings, std::optional<ShadeMap> map = std::nullopt) {
        ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::move(map));
        const Plan plan = compile({&pass}, {"shade.color"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        cv::Mat image = executor.store().image("shade.color").clone();
        executor.store().clear();
        EXPECT_EQ(image.type(), CV_8UC4);
        return image;
    }

    static ShadeSettings settingsFor(ShadingModel model, double shininess = 32.0) {
        ShadeSettings settings;
        settings.model = model;
        settings.shininess = shininess;
        return settings;
    }
};

// ---------------------------------------------------------------------------------------------------------------
// Cel: band borders where n.l crosses the predicted values.

class ShadeCel : public ShadeSphere, public ::testing::WithParamInterface<int> {};

TEST_P(ShadeCel, BandBordersSitAtThePredictedAngles) {
    const int bands = GetParam();
    const glm::vec4 base(0.9f, 0.6f, 0.3f, 1.0f);
    useSphere(512, 256, base);
    // About 82 degrees off the view axis: n.l spans about [-0.92, 0.99] over the visible cap, so every border, down
    // to n.l = -0.6 (126.9 deg), lies well inside the disc.
    setLight({1.0, 0.3, 0.15});
    const glm::dvec3 l = lightView();
    const ShadeMap map = makeBandShadeMap(bands);
    // The colour each band must produce: decoded texel x base colour, encoded.
    std::vector<cv::Vec3i> bandColors;
    for (int i = 0; i < bands; ++i) {
        const cv::Vec4b texel = map.texels.at<cv::Vec4b>(0, i);
        cv::Vec3i color;
        for (int c = 0; c < 3; ++c) color[c] = srgbCode(linearOf(texel[c]) * double(base[c]));
        bandColors.push_back(color);
    }
    const cv::Mat image = render(settingsFor(ShadingModel::Cel), map);

    // Measured band of every pixel (the nearest band colour), -1 off the model or at the silhouette.
    cv::Mat measuredBand(kSize, kSize, CV_32S, cv::Scalar(-1));
    int compared = 0;
    int wrong = 0;
    int largestCodeError = 0;
    double widestWrongMargin = 0.0; // 0: no pixel off its band at all
    double closestToBorder = 1.0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            const cv::Vec4b pixel = pixelAt(image, col, row);
            const bool covered = pixel[3] == 255;
            if (kSphere.pixelsFromSilhouette(col, row) > 1.0) {
                ASSERT_EQ(covered, hit.has_value()) << "coverage at col " << col << ", row " << row;
            }
            if (!covered) {
                ASSERT_EQ(pixel, cv::Vec4b(0, 0, 0, 0)) << "background at col " << col << ", row " << row;
                continue;
            }
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5) continue;
            int nearest = 0;
            int nearestDistance = 256;
            for (int i = 0; i < bands; ++i) {
                int distance = 0;
                for (int c = 0; c < 3; ++c) distance = std::max(distance, std::abs(int(pixel[c]) - bandColors[i][c]));
                if (distance < nearestDistance) {
                    nearest = i;
                    nearestDistance = distance;
                }
            }
            measuredBand.at<int>(row, col) = nearest;
            const double q = 0.5 * glm::dot(hit->normal, l) + 0.5;
            double fromBorder = 1.0;
            for (int k = 1; k < bands; ++k) fromBorder = std::min(fromBorder, std::abs(q - double(k) / bands));
            const int predicted = std::min(int(std::floor(q * bands)), bands - 1);
            // How close to a border the shading is still exact: the farthest wrong pixel, margin or not.
            if (nearest != predicted) widestWrongMargin = std::max(widestWrongMargin, fromBorder);
            closestToBorder = std::min(closestToBorder, fromBorder);
            if (fromBorder <= 0.01) continue;
            ++compared;
            largestCodeError = std::max(largestCodeError, nearestDistance);
            if (nearest != predicted || nearestDistance > 1) {
                if (++wrong <= 5)
                    ADD_FAILURE() << "col " << col << ", row " << row << ": q " << q << " predicts band " << predicted
                                  << ", pixel shows band " << nearest << " (off by " << nearestDistance << " codes)";
            }
        }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(compared, 25000) << "most of the disc (about 34,000 pixels) must be compared";
    EXPECT_LE(largestCodeError, 1);
    RecordProperty("widest_wrong_q_margin", std::to_string(widestWrongMargin));
    std::printf("  bands %d: %d pixels compared beyond the margin; wrong band within %.2g of a border in q (0: none, "
                "the closest pixel being %.2g from one)\n",
                bands, compared, widestWrongMargin, closestToBorder);

    // Along every scanline, each change of band lies where n.l crosses a border: n.l = 2k/N - 1 between bands k - 1
    // and k. The shared edge of the two pixels is the measured border. The true border must lie between the two
    // pixel centres, and the edge must be unbiased: on average on the true border, in pixels and in degrees
    // (signed: positive when the measured border lies on the side of larger angles to the light).
    struct BorderStats {
        int transitions = 0;
        double signedDegrees = 0.0, signedPixels = 0.0, largestDegrees = 0.0, largestOutsideDegrees = 0.0;
    };
    std::vector<BorderStats> stats(bands);
    for (int row = 0; row < kSize; ++row) {
        const auto nDotLAt = [&](double x) {
            return std::clamp(glm::dot(kSphere.castPoint(x, row + 0.5)->normal, l), -1.0, 1.0);
        };
        for (int col = 0; col + 1 < kSize; ++col) {
            const int a = measuredBand.at<int>(row, col);
            const int b = measuredBand.at<int>(row, col + 1);
            if (a < 0 || b < 0 || a == b) continue;
            EXPECT_EQ(std::abs(a - b), 1) << "bands skipped at col " << col << ", row " << row;
            const int k = std::max(a, b);
            const double borderNDotL = 2.0 * k / bands - 1.0;
            const double borderDegrees = glm::degrees(std::acos(borderNDotL));
            const double left = glm::degrees(std::acos(nDotLAt(col + 0.5)));
            const double right = glm::degrees(std::acos(nDotLAt(col + 1.5)));
            const double edge = glm::degrees(std::acos(nDotLAt(col + 1.0)));
            BorderStats& border = stats[k];
            const double outside =
                std::max({0.0, std::min(left, right) - borderDegrees, borderDegrees - std::max(left, right)});
            border.largestOutsideDegrees = std::max(border.largestOutsideDegrees, outside);
            border.signedDegrees += edge - borderDegrees;
            border.largestDegrees = std::max(border.largestDegrees, std::abs(edge - borderDegrees));
            if (outside == 0.0) {
                // The analytic crossing between the centres, by bisection (n.l is monotonic over one pixel here).
                double low = col + 0.5, high = col + 1.5;
                const bool rising = nDotLAt(high) > nDotLAt(low);
                for (int i = 0; i < 60; ++i) {
                    const double middle = 0.5 * (low + high);
                    ((nDotLAt(middle) > borderNDotL) == rising ? high : low) = middle;
                }
                // Angles grow where n.l falls.
                border.signedPixels += (col + 1.0 - 0.5 * (low + high)) * (rising ? -1.0 : 1.0);
            }
            ++border.transitions;
        }
    }
    for (int k = 1; k < bands; ++k) {
        const BorderStats& border = stats[k];
        const double borderDegrees = glm::degrees(std::acos(2.0 * k / bands - 1.0));
        const int n = std::max(border.transitions, 1);
        EXPECT_GT(border.transitions, 50) << "border " << k << " at " << borderDegrees << " deg must be visible";
        // Interpolated normals are within 0.01 deg of the sphere's, so no border falls outside its pixel pair.
        EXPECT_LT(border.largestOutsideDegrees, 0.02) << "border at " << borderDegrees << " deg";
        // Each edge is within half a pixel of the true border; on average within a tenth of a pixel (a half-texel
        // or half-pixel shift would give 0.5).
        EXPECT_LT(std::abs(border.signedPixels / n), 0.1) << "border at " << borderDegrees << " deg, mean shift";
        const std::string key = "border_" + std::to_string(int(std::lround(borderDegrees * 10))) + "_decideg";
        RecordProperty(key + "_mean_shift_px", std::to_string(border.signedPixels / n));
        RecordProperty(key + "_mean_error_deg", std::to_string(border.signedDegrees / n));
        RecordProperty(key + "_max_error_deg", std::to_string(border.largestDegrees));
        std::printf("  bands %d, border %6.2f deg: %3d transitions, mean signed error %+.4f deg (%+.4f px), max "
                    "|error| %.3f deg, max outside the pixel pair %.4f deg\n",
                    bands, borderDegrees, border.transitions, border.signedDegrees / n, border.signedPixels / n,
                    border.largestDegrees, border.largestOutsideDegrees);
    }
}

INSTANTIATE_TEST_SUITE_P(Bands, ShadeCel, ::testing::Values(5, 3), [](const ::testing::TestParamInfo<int>& param) {
    return "Bands" + std::to_string(param.param);
});

// ---------------------------------------------------------------------------------------------------------------
// Specular highlights.

/** Centroid of the pixel centres where `select(col, row)` holds; the count in `count`. */
template <class Select>
glm::dvec2 centroid(Select select, int& count) {
    glm::dvec2 sum(0.0);
    count = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            if (!select(col, row)) continue;
            sum += glm::dvec2(col + 0.5, row + 0.5);
            ++count;
        }
    }
    return count > 0 ? sum / double(count) : glm::dvec2(-1.0);
}

const glm::dvec3 kHighlightLight(0.5, 0.4, 1.0);
const glm::vec4 kDarkBase(0.2f, 0.2f, 0.2f, 1.0f); // diffuse + 0.5 specular stays below 1: nothing clips

/** Specular of a phong render recovered against lambert with the same ambient: (phong - lambert) / strength. */
double specularOf(const cv::Mat& phong, const cv::Mat& lambert, int col, int row, float strength) {
    return (linearOf(pixelAt(phong, col, row)[1]) - linearOf(pixelAt(lambert, col, row)[1])) / strength;
}

TEST_F(ShadeSphere, PhongHighlightIsWhereTheReflectionMeetsTheEye) {
    useSphere(512, 256, kDarkBase);
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    ShadeSettings phongSettings = settingsFor(ShadingModel::Phong, 64.0);
    const cv::Mat phong = render(phongSettings);
    const cv::Mat lambert = render(settingsFor(ShadingModel::Lambert));
    const glm::dvec2 predicted = kSphere.project(highlightPoint(l, std::nullopt));

    double brightest = 0.0;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col)
            if (pixelAt(phong, col, row)[3] == 255)
                brightest = std::max(brightest, specularOf(phong, lambert, col, row, phongSettings.specularStrength));
    EXPECT_GT(brightest, 0.95) << "the peak of max(r.v, 0)^64 is 1";
    int count = 0;
    const glm::dvec2 measured = centroid(
        [&](int col, int row) {
            return pixelAt(phong, col, row)[3] == 255 &&
                   specularOf(phong, lambert, col, row, phongSettings.specularStrength) >= 0.5;
        },
        count);
    const double offset = glm::length(measured - predicted);
    EXPECT_GT(count, 50) << "the half-maximum highlight of shininess 64 covers a few hundred pixels";
    EXPECT_LT(offset, 1.0) << "measured (" << measured.x << ", " << measured.y << "), predicted (" << predicted.x
                           << ", " << predicted.y << ")";
    RecordProperty("phong_highlight_offset_px", std::to_string(offset));
    std::printf("  phong highlight: %d pixels at half maximum, centroid (%.3f, %.3f), predicted (%.3f, %.3f), "
                "offset %.3f px\n",
                count, measured.x, measured.y, predicted.x, predicted.y, offset);
}

/** Cel-style 2-D map for the comic tests: the top row (t >= 0.5) is white, the bottom row grey 100. */
ShadeMap highlightMap() {
    cv::Mat texels(2, 1, CV_8UC4);
    texels.at<cv::Vec4b>(0, 0) = cv::Vec4b(255, 255, 255, 255);
    texels.at<cv::Vec4b>(1, 0) = cv::Vec4b(100, 100, 100, 255);
    return shadeMapFromImage(texels, "test:highlight", false);
}

bool isHighlight(const cv::Mat& image, int col, int row) {
    const cv::Vec4b pixel = pixelAt(image, col, row);
    return pixel[3] == 255 && pixel[0] == 255;
}

/** Every covered pixel away from the silhouette whose analytic t is more than `margin` from 0.5 is classified as
 *  the map says; returns the number of pixels compared. */
int expectHighlightClassification(const cv::Mat& image, const glm::dvec3& l, double shininess,
                                  std::optional<glm::dvec3> constantTowardEye, double margin) {
    int compared = 0;
    int wrong = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5 || pixelAt(image, col, row)[3] != 255) continue;
            // The gate n.l > 0 decides t at the terminator: keep away from it too.
            if (std::abs(glm::dot(hit->normal, l)) < 0.01) continue;
            const glm::dvec3 towardEye = constantTowardEye ? *constantTowardEye : hit->towardEye;
            const double t = specularReference(hit->normal, l, towardEye, shininess);
            if (std::abs(t - 0.5) <= margin) continue;
            ++compared;
            if ((t > 0.5) != isHighlight(image, col, row) && ++wrong <= 5)
                ADD_FAILURE() << "col " << col << ", row " << row << ": t " << t << ", highlight "
                              << isHighlight(image, col, row);
        }
    }
    EXPECT_EQ(wrong, 0);
    return compared;
}

TEST_F(ShadeSphere, ComicHighlightIsWhereTheReflectionMeetsTheEye) {
    useSphere(512, 256, {1.0f, 1.0f, 1.0f, 1.0f});
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    const cv::Mat image = render(settingsFor(ShadingModel::Comic, 64.0), highlightMap());
    const glm::dvec2 predicted = kSphere.project(highlightPoint(l, std::nullopt));
    int count = 0;
    const glm::dvec2 measured = centroid([&](int col, int row) { return isHighlight(image, col, row); }, count);
    const double offset = glm::length(measured - predicted);
    EXPECT_GT(count, 50);
    EXPECT_LT(offset, 1.0) << "measured (" << measured.x << ", " << measured.y << "), predicted (" << predicted.x
                           << ", " << predicted.y << ")";
    EXPECT_GT(expectHighlightClassification(image, l, 64.0, std::nullopt, 0.02), 25000);
    // Everything else is the lower row of the map times the white base colour: grey 100, exactly.
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col)
            if (pixelAt(image, col, row)[3] == 255 && !isHighlight(image, col, row)) {
                ASSERT_EQ(pixelAt(image, col, row), cv::Vec4b(100, 100, 100, 255)) << col << ", " << row;
            }
    RecordProperty("comic_highlight_offset_px", std::to_string(offset));
    std::printf("  comic highlight: %d pixels with t >= 0.5, centroid (%.3f, %.3f), predicted (%.3f, %.3f), offset "
                "%.3f px\n",
                count, measured.x, measured.y, predicted.x, predicted.y, offset);
}

TEST_F(ShadeSphere, ComicMapWithManyRowBandsTakesTheGeneralPathAndAgrees) {
    // 20 rows: white above t = 0.5, alternating greys 100 and 101 below, so 10 row borders: more than the comparison
    // path takes, so the shader evaluates exp(n log(r.v)) instead. The highlight must be classified the same way.
    cv::Mat texels(20, 1, CV_8UC4);
    for (int row = 0; row < 20; ++row) {
        const uchar grey = row < 10 ? 255 : uchar(100 + row % 2);
        texels.at<cv::Vec4b>(row, 0) = cv::Vec4b(grey, grey, grey, 255);
    }
    const ShadeMap map = shadeMapFromImage(texels, "test:many-bands", false);
    ASSERT_GT(specularRowBands(map, 64.0).maxHalfSquaredDistance.size(), 8u);
    useSphere(512, 256, {1.0f, 1.0f, 1.0f, 1.0f});
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    const cv::Mat image = render(settingsFor(ShadingModel::Comic, 64.0), map);
    EXPECT_GT(expectHighlightClassification(image, l, 64.0, std::nullopt, 0.02), 25000);
}

TEST_F(ShadeSphere, ComicDefaultMapShowsItsThreeTonesWherePredicted) {
    const glm::vec4 base(0.9f, 0.6f, 0.3f, 1.0f);
    useSphere(512, 256, base);
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    const ShadeMap map = makeDefaultComicShadeMap();
    const cv::Mat image = render(settingsFor(ShadingModel::Comic, 32.0), map);
    // The map's tones (bottom-left shadow, bottom-right lit, top highlight) times the base colour.
    const auto colorOf = [&](int mapRow, int mapCol) {
        const cv::Vec4b texel = map.texels.at<cv::Vec4b>(mapRow, mapCol);
        cv::Vec3i color;
        for (int c = 0; c < 3; ++c) color[c] = srgbCode(linearOf(texel[c]) * double(base[c]));
        return color;
    };
    const int bottom = map.texels.rows - 1;
    const cv::Vec3i shadow = colorOf(bottom, 0), lit = colorOf(bottom, map.texels.cols - 1), highlight = colorOf(0, 0);
    int compared = 0;
    int wrong = 0;
    std::vector<int> counts(3, 0);
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5) continue;
            const double nDotL = glm::dot(hit->normal, l);
            const double s = std::max(nDotL, 0.0);
            const double t = specularReference(hit->normal, l, hit->towardEye, 32.0);
            if (std::abs(s - 0.25) < 0.01 || std::abs(t - 0.5) < 0.02 || std::abs(nDotL) < 0.01) continue;
            const int tone = t >= 0.5 ? 2 : (s < 0.25 ? 0 : 1);
            const cv::Vec3i expected = tone == 2 ? highlight : (tone == 1 ? lit : shadow);
            const cv::Vec4b pixel = pixelAt(image, col, row);
            int error = 0;
            for (int c = 0; c < 3; ++c) error = std::max(error, std::abs(int(pixel[c]) - expected[c]));
            ++compared;
            ++counts[tone];
            if (error > 1 && ++wrong <= 5)
                ADD_FAILURE() << "col " << col << ", row " << row << ": s " << s << ", t " << t << ", tone " << tone;
        }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(compared, 25000);
    for (int tone = 0; tone < 3; ++tone) EXPECT_GT(counts[tone], 100) << "tone " << tone << " must show";
    std::printf("  comic default map: %d pixels as predicted (shadow %d, lit %d, highlight %d)\n", compared, counts[0],
                counts[1], counts[2]);
}

TEST_F(ShadeSphere, ComicConstantViewVectorMovesTheHighlightAsPredicted) {
    useSphere(512, 256, {1.0f, 1.0f, 1.0f, 1.0f});
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    ShadeSettings settings = settingsFor(ShadingModel::Comic, 64.0);
    // V_c = (C - E)/|C - E|, eye -> centre, in world space; the surface -> eye vector is then +z in view space.
    settings.view.constant = true;
    settings.view.constantView = glm::dvec3(0.0, 0.0, -1.0);
    const cv::Mat image = render(settings, highlightMap());
    const glm::dvec3 constantTowardEye(0.0, 0.0, 1.0);
    const glm::dvec2 predicted = kSphere.project(highlightPoint(l, constantTowardEye));
    const glm::dvec2 exactPrediction = kSphere.project(highlightPoint(l, std::nullopt));
    int count = 0;
    const glm::dvec2 measured = centroid([&](int col, int row) { return isHighlight(image, col, row); }, count);
    const double offset = glm::length(measured - predicted);
    EXPECT_LT(offset, 1.0) << "measured (" << measured.x << ", " << measured.y << "), predicted (" << predicted.x
                           << ", " << predicted.y << ")";
    // The approximation is visible at this distance (r_b / |V_c| = 0.25): the two predictions are pixels apart.
    EXPECT_GT(glm::length(exactPrediction - predicted), 2.0);
    EXPECT_GT(expectHighlightClassification(image, l, 64.0, constantTowardEye, 0.02), 25000);
    RecordProperty("comic_constant_view_highlight_offset_px", std::to_string(offset));
    std::printf("  comic constant view: centroid (%.3f, %.3f), predicted (%.3f, %.3f), offset %.3f px; the exact-view "
                "prediction is %.3f px away\n",
                measured.x, measured.y, predicted.x, predicted.y, offset, glm::length(exactPrediction - predicted));
}

// ---------------------------------------------------------------------------------------------------------------
// Shininess at the extremes: 0 gives specular 1 wherever n.l > 0; 1e6 gives a sub-pixel highlight or none, and
// never speckle.

TEST_F(ShadeSphere, PhongShininessZeroAndHuge) {
    useSphere(512, 256, kDarkBase);
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();
    const cv::Mat lambert = render(settingsFor(ShadingModel::Lambert));

    // Shininess 0: base x (ambient + diffuse) + strength on the lit side, the formula at every pixel.
    const ShadeSettings zeroSettings = settingsFor(ShadingModel::Phong, 0.0);
    const cv::Mat zero = render(zeroSettings);
    int compared = 0;
    int largestError = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5) continue;
            const double nDotL = glm::dot(hit->normal, l);
            if (std::abs(nDotL) < 0.01) continue;
            const double diffuse =
                double(frame.ambientLight.g) + (1.0 - double(frame.ambientLight.g)) * std::max(nDotL, 0.0);
            const double expected = kDarkBase.g * diffuse + (nDotL > 0.0 ? zeroSettings.specularStrength : 0.0);
            largestError = std::max(largestError, std::abs(int(pixelAt(zero, col, row)[1]) - srgbCode(expected)));
            ++compared;
        }
    }
    EXPECT_GT(compared, 25000);
    EXPECT_LE(largestError, 1) << "shininess 0: specular must be exactly 1 on the lit side";

    // Shininess 1e6: the highlight's half-width is 0.001 rad in r, 0.06 px on screen, so at most a pixel or two
    // differ from lambert, all at the predicted centre; everything else equals lambert.
    const cv::Mat huge = render(settingsFor(ShadingModel::Phong, 1e6));
    const glm::dvec2 predicted = kSphere.project(highlightPoint(l, std::nullopt));
    int highlighted = 0;
    double farthest = 0.0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const cv::Vec4b pixel = pixelAt(huge, col, row);
            ASSERT_EQ(pixel[3], pixelAt(lambert, col, row)[3]) << "coverage at " << col << ", " << row;
            const int difference = int(pixel[1]) - int(pixelAt(lambert, col, row)[1]);
            if (difference == 0) continue;
            ++highlighted;
            farthest = std::max(farthest, glm::length(glm::dvec2(col + 0.5, row + 0.5) - predicted));
        }
    }
    EXPECT_LE(highlighted, 4);
    EXPECT_LE(farthest, 2.0) << "a lit pixel away from the predicted highlight is speckle";
    // And against the formula in double at every pixel: 1e6 is no different from any other shininess.
    int hugeError = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5) continue;
            const double nDotL = glm::dot(hit->normal, l);
            const double diffuse =
                double(frame.ambientLight.g) + (1.0 - double(frame.ambientLight.g)) * std::max(nDotL, 0.0);
            const double expected = kDarkBase.g * diffuse + zeroSettings.specularStrength *
                                                                specularReference(hit->normal, l, hit->towardEye, 1e6);
            hugeError = std::max(hugeError, std::abs(int(pixelAt(huge, col, row)[1]) - srgbCode(expected)));
        }
    }
    EXPECT_LE(hugeError, 1);
    RecordProperty("phong_1e6_highlight_pixels", std::to_string(highlighted));
    std::printf("  phong shininess 1e6: %d pixels differ from lambert, farthest %.3f px from the predicted centre\n",
                highlighted, farthest);
}

TEST_F(ShadeSphere, ComicShininessZeroAndHuge) {
    useSphere(512, 256, {1.0f, 1.0f, 1.0f, 1.0f});
    setLight(kHighlightLight);
    const glm::dvec3 l = lightView();

    // Shininess 0: t = 1 wherever n.l > 0, so the whole lit side is highlight and the rest is not.
    const cv::Mat zero = render(settingsFor(ShadingModel::Comic, 0.0), highlightMap());
    EXPECT_GT(expectHighlightClassification(zero, l, 0.0, std::nullopt, 0.02), 25000);

    // Shininess 1e4: a highlight of about a pixel, where the analytic t says.
    const cv::Mat sharp = render(settingsFor(ShadingModel::Comic, 1e4), highlightMap());
    EXPECT_GT(expectHighlightClassification(sharp, l, 1e4, std::nullopt, 0.02), 25000);
    int sharpCount = 0;
    centroid([&](int col, int row) { return isHighlight(sharp, col, row); }, sharpCount);
    EXPECT_GE(sharpCount, 1);

    // Shininess 1e6: t < 0.5 at every pixel centre of this view (the highlight's half-width is 0.06 px), so no
    // highlight pixel at all, or one or two next to the predicted centre: anything else is speckle.
    const cv::Mat huge = render(settingsFor(ShadingModel::Comic, 1e6), highlightMap());
    EXPECT_GT(expectHighlightClassification(huge, l, 1e6, std::nullopt, 0.02), 25000);
    const glm::dvec2 predicted = kSphere.project(highlightPoint(l, std::nullopt));
    int highlighted = 0;
    double farthest = 0.0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            if (!isHighlight(huge, col, row)) continue;
            ++highlighted;
            farthest = std::max(farthest, glm::length(glm::dvec2(col + 0.5, row + 0.5) - predicted));
        }
    }
    EXPECT_LE(highlighted, 4);
    EXPECT_LE(farthest, 2.0) << "a highlight pixel away from the predicted centre is speckle";
    RecordProperty("comic_1e6_highlight_pixels", std::to_string(highlighted));
    std::printf("  comic shininess 1e4: %d highlight pixels; 1e6: %d highlight pixels, farthest %.3f px from the "
                "predicted centre\n",
                sharpCount, highlighted, farthest);
}

// ---------------------------------------------------------------------------------------------------------------
// specularTerm itself, in float on the GPU, against double pow: 8-bit colour cannot show a NaN.

class SpecularTerm : public ::testing::Test {
protected:
    void SetUp() override { test::sharedGlContext(); }
};

std::string readFile(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

void writeFile(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

TEST_F(SpecularTerm, FiniteAndAccurateForShininessZeroToOneMillion) {
    // A probe program: the project's lighting.glsl plus a fragment shader that evaluates specularTerm for one input
    // per pixel. Built through ShaderLibrary from a scratch folder holding copies of the snippets it needs.
    const std::filesystem::path folder = test::testOutputDirectory("SpecularTermProbe") / "shaders";
    std::filesystem::remove_all(folder);
    for (const char* snippet : {"common/lighting.glsl", "common/fullscreen.glsl"})
        writeFile(folder / snippet, readFile(ShaderLibrary::defaultDirectory() / snippet));
    writeFile(folder / "probe/probe.vert", "void main() { emitFullscreenVertex(); }\n");
    // Inputs: GL row 0 holds r.xyz and the shininess, GL row 1 holds v.xyz (uploadImage() turns rows over).
    writeFile(folder / "probe/probe.frag", "layout(binding = 0) uniform sampler2D inputs;\n"
                                           "layout(location = 0) out vec4 outValue;\n"
                                           "void main() {\n"
                                           "    int i = int(gl_FragCoord.x);\n"
                                           "    vec4 r = texelFetch(inputs, ivec2(i, 0), 0);\n"
                                           "    vec3 v = texelFetch(inputs, ivec2(i, 1), 0).xyz;\n"
                                           "    float naive = pow(max(dot(r.xyz, v), 0.0), r.w);\n"
                                           "    outValue = vec4(specularTerm(r.xyz, v, r.w), naive, 0.0, 1.0);\n"
                                           "}\n");
    ShaderLibrary probeShaders(folder);
    const GlProgram program = probeShaders.build({"specular probe",
                                                  "probe/probe.vert",
                                                  "probe/probe.frag",
                                                  {},
                                                  {"common/fullscreen.glsl", "common/lighting.glsl"}});

    // Angles between r and v from 0 to pi, every shininess from 0 to 1e6, r on an axis and r in a general direction.
    const std::vector<double> angles = {0.0,
                                        1e-6,
                                        1e-5,
                                        1e-4,
                                        3e-4,
                                        1e-3,
                                        2e-3,
                                        3e-3,
                                        1e-2,
                                        3e-2,
                                        0.1,
                                        0.3,
                                        0.7,
                                        1.0,
                                        1.4,
                                        glm::half_pi<double>() - 1e-4,
                                        glm::half_pi<double>(),
                                        1.6,
                                        2.5,
                                        glm::pi<double>()};
    const std::vector<double> shininessValues = {0.0, 0.5, 1.0, 8.0, 32.0, 1e3, 1e5, 1e6};
    const std::vector<glm::dvec3> axes = {glm::dvec3(0.0, 0.0, 1.0), glm::normalize(glm::dvec3(0.3, -0.5, 0.8))};
    struct Case {
        glm::vec3 reflected;
        glm::vec3 towardEye;
        double shininess;
        double angle;
    };
    std::vector<Case> cases;
    for (const glm::dvec3& axis : axes) {
        // A unit vector perpendicular to the axis to rotate v away from r.
        const glm::dvec3 side = glm::normalize(glm::cross(axis, glm::dvec3(1.0, 0.0, 0.0)));
        for (double angle : angles)
            for (double shininess : shininessValues)
                cases.push_back(
                    {glm::vec3(axis), glm::vec3(std::cos(angle) * axis + std::sin(angle) * side), shininess, angle});
    }
    const int count = int(cases.size());
    cv::Mat inputs(2, count, CV_32FC4);
    for (int i = 0; i < count; ++i) {
        const Case& c = cases[i];
        // Image row 1 becomes GL row 0.
        inputs.at<cv::Vec4f>(1, i) = cv::Vec4f(c.reflected.x, c.reflected.y, c.reflected.z, float(c.shininess));
        inputs.at<cv::Vec4f>(0, i) = cv::Vec4f(c.towardEye.x, c.towardEye.y, c.towardEye.z, 0.0f);
    }
    GlTexture inputTexture(Format::RGBA32F, count, 2, "specular probe inputs");
    uploadImage(inputTexture, inputs);
    GlTexture output(Format::RGBA32F, count, 1, "specular probe output");
    GlFramebuffer framebuffer("specular probe");
    framebuffer.attachColor(0, output);
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, count, 1);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    program.use();
    glBindTextureUnit(0, inputTexture.id());
    GlVertexArray empty("specular probe fullscreen");
    empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glBindTextureUnit(0, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    const cv::Mat values = readTexture(output);

    double largestError = 0.0;
    double largestRelativeError = 0.0; // where the reference is above 1e-3
    double largestNaiveError = 0.0;
    for (int i = 0; i < count; ++i) {
        const Case& c = cases[i];
        const float value = values.at<cv::Vec4f>(0, i)[0];
        const float naive = values.at<cv::Vec4f>(0, i)[1];
        // The reference from the float inputs as given, in double: the angle between them by atan2 (exact for
        // tiny angles), then pow.
        const glm::dvec3 r(c.reflected), v(c.towardEye);
        const double angle = std::atan2(glm::length(glm::cross(r, v)), glm::dot(r, v));
        const double cosine = std::cos(angle);
        const double reference = c.shininess == 0.0 ? 1.0 : (cosine <= 0.0 ? 0.0 : std::pow(cosine, c.shininess));
        ASSERT_TRUE(std::isfinite(value)) << "angle " << c.angle << ", shininess " << c.shininess;
        EXPECT_GE(value, 0.0f);
        EXPECT_LE(value, 1.0f);
        // Float evaluation: exp(n log c) carries a relative error of about n |log c| x 1e-7 plus a few ulps, and
        // r.v itself an absolute one of a few 1e-8 (which pow(c, 0.5) near c = 1e-4 turns into 6e-7). 1e-5
        // relative plus 1e-6 absolute (1/300 of an 8-bit step at black) bounds both.
        const double error = std::abs(double(value) - reference);
        EXPECT_LE(error, 1e-5 * reference + 1e-6)
            << "angle " << c.angle << ", shininess " << c.shininess << ": " << value << " vs " << reference;
        largestError = std::max(largestError, error);
        if (reference > 1e-3) largestRelativeError = std::max(largestRelativeError, error / reference);
        if (std::isfinite(naive))
            largestNaiveError = std::max(largestNaiveError, std::abs(double(naive) - reference));
        else
            largestNaiveError = std::numeric_limits<double>::infinity();
    }
    RecordProperty("specular_term_max_abs_error", std::to_string(largestError));
    RecordProperty("specular_term_max_rel_error", std::to_string(largestRelativeError));
    RecordProperty("naive_pow_max_abs_error", std::to_string(largestNaiveError));
    std::printf("  specularTerm over %d inputs: max abs error %.3g, max relative error %.3g where above 1e-3, against "
                "double pow (naive float pow(max(r.v, 0), n): max abs error %.3g)\n",
                count, largestError, largestRelativeError, largestNaiveError);
}

// ---------------------------------------------------------------------------------------------------------------
// Flat, gouraud, lambert.

/** Nearest triangle of `mesh` (model space = world space here) under a pixel centre, by ray casting in double. */
struct MeshHit {
    int triangle = -1;
    double pixelsFromEdge = 0.0; ///< distance in the image to the nearest edge of that triangle
};

MeshHit castMesh(const Mesh& mesh, const glm::dmat4& viewFromModel, int col, int row) {
    const double tanHalf = std::tan(glm::radians(kFovDegrees) / 2.0);
    const glm::dvec3 direction = glm::normalize(
        glm::dvec3((2.0 * (col + 0.5) / kSize - 1.0) * tanHalf, (1.0 - 2.0 * (row + 0.5) / kSize) * tanHalf, -1.0));
    MeshHit best;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = glm::dvec3(viewFromModel * glm::dvec4(mesh.positions[mesh.triangles[t][k]], 1.0));
        // Moller-Trumbore, both sides.
        const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const glm::dvec3 h = glm::cross(direction, e2);
        const double det = glm::dot(e1, h);
        if (std::abs(det) < 1e-15) continue;
        const glm::dvec3 s = -p[0];
        const double u = glm::dot(s, h) / det;
        const glm::dvec3 qv = glm::cross(s, e1);
        const double v = glm::dot(direction, qv) / det;
        const double distance = glm::dot(e2, qv) / det;
        if (u < 0.0 || v < 0.0 || u + v > 1.0 || distance <= 0.0 || distance >= bestDistance) continue;
        bestDistance = distance;
        best.triangle = int(t);
        double nearestEdge = std::numeric_limits<double>::infinity();
        const glm::dvec2 pixel(col + 0.5, row + 0.5);
        for (int k = 0; k < 3; ++k) {
            const glm::dvec2 a = kSphere.project(p[k]), b = kSphere.project(p[(k + 1) % 3]);
            const double along = std::clamp(glm::dot(pixel - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            nearestEdge = std::min(nearestEdge, glm::length(pixel - (a + along * (b - a))));
        }
        best.pixelsFromEdge = nearestEdge;
    }
    return best;
}

TEST_F(ShadeSphere, FlatShadesEveryFaceWithOneColour) {
    const glm::vec4 base(0.8f, 0.8f, 0.8f, 1.0f);
    useSphere(8, 6, base);
    setLight({0.3, 0.5, 1.0});
    const glm::dvec3 l = lightView();
    const ShadeSettings settings = settingsFor(ShadingModel::Flat);
    const cv::Mat image = render(settings);
    const Mesh& mesh = scene.meshes.front();
    const glm::dmat4 viewFromModel = frame.camera.viewMatrix();

    std::map<int, std::set<int>> colorsByFace; // green codes of the pixels inside each face
    std::set<int> allColors;
    int compared = 0;
    int largestError = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const cv::Vec4b pixel = pixelAt(image, col, row);
            if (pixel[3] != 255) continue;
            EXPECT_EQ(pixel[0], pixel[1]);
            allColors.insert(pixel[1]);
            const MeshHit hit = castMesh(mesh, viewFromModel, col, row);
            if (hit.triangle < 0 || hit.pixelsFromEdge < 1.0) continue;
            colorsByFace[hit.triangle].insert(pixel[1]);
            // The face normal, turned toward the eye, lit like lambert.
            const glm::uvec3 t = mesh.triangles[hit.triangle];
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = glm::dvec3(viewFromModel * glm::dvec4(mesh.positions[t[k]], 1.0));
            glm::dvec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
            if (glm::dot(n, -p[0]) < 0.0) n = -n;
            const double expected = base.g * (double(frame.ambientLight.g) +
                                              (1.0 - double(frame.ambientLight.g)) * std::max(glm::dot(n, l), 0.0));
            largestError = std::max(largestError, std::abs(int(pixel[1]) - srgbCode(expected)));
            ++compared;
        }
    }
    EXPECT_GT(compared, 20000);
    EXPECT_LE(largestError, 1) << "flat colour against the face normal's lambert";
    // The face normal comes from screen derivatives of interpolated view positions (about 3 units from the eye,
    // 0.01 apart per pixel), so it carries float noise of about 1e-4 relative: a face whose colour lies within a
    // few hundredths of a code of a rounding boundary may show two neighbouring codes, never more.
    int spread = 0;
    int facesWithTwoCodes = 0;
    for (const auto& [face, colors] : colorsByFace) {
        spread = std::max(spread, *colors.rbegin() - *colors.begin());
        if (colors.size() > 1) ++facesWithTwoCodes;
    }
    EXPECT_LE(spread, 1) << "a face shows more than one colour";
    // 80 triangles, about 30 visible: one colour per face (symmetric faces may share one).
    EXPECT_LE(allColors.size(), colorsByFace.size() + facesWithTwoCodes) << "colours on the coarse sphere";
    EXPECT_GT(colorsByFace.size(), 20u);
    std::printf("  flat: %zu faces inside the image, %zu distinct colours, %d faces with two neighbouring codes, "
                "largest error against the face normal %d codes\n",
                colorsByFace.size(), allColors.size(), facesWithTwoCodes, largestError);
}

/** Largest difference of any colour channel between two renders, over pixels both cover. */
int largestDifference(const cv::Mat& a, const cv::Mat& b) {
    int largest = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const cv::Vec4b pa = pixelAt(a, col, row), pb = pixelAt(b, col, row);
            EXPECT_EQ(pa[3], pb[3]) << "coverage at " << col << ", " << row;
            if (pa[3] != 255 || pb[3] != 255) continue;
            for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(int(pa[c]) - int(pb[c])));
        }
    }
    return largest;
}

TEST_F(ShadeSphere, GouraudDiffersFromLambertOnACoarseSphereOnly) {
    const glm::vec4 base(0.7f, 0.5f, 0.9f, 1.0f);
    setLight({0.3, 0.5, 1.0});
    useSphere(8, 6, base);
    const int coarse =
        largestDifference(render(settingsFor(ShadingModel::Gouraud)), render(settingsFor(ShadingModel::Lambert)));
    useSphere(512, 256, base);
    const int fine =
        largestDifference(render(settingsFor(ShadingModel::Gouraud)), render(settingsFor(ShadingModel::Lambert)));
    // Linear interpolation of colours instead of normals: large on 8 x 6 segments, a rounding step on 512 x 256.
    EXPECT_GE(coarse, 20) << "gouraud and lambert must differ on a coarse sphere";
    EXPECT_LE(fine, 2) << "gouraud and lambert must agree on a fine sphere";
    RecordProperty("gouraud_lambert_coarse_codes", std::to_string(coarse));
    RecordProperty("gouraud_lambert_fine_codes", std::to_string(fine));
    std::printf("  gouraud vs lambert: largest difference %d codes on 8 x 6 segments, %d on 512 x 256\n", coarse, fine);
}

TEST_F(ShadeSphere, LambertMatchesItsFormulaPerChannelOfTheAmbientLight) {
    const glm::vec4 base(0.9f, 0.6f, 0.3f, 1.0f);
    useSphere(512, 256, base);
    setLight({-0.4, 0.6, 0.7});
    frame.ambientLight = glm::vec3(0.3f, 0.15f, 0.05f); // --ambient: each channel its own ambient term
    const glm::dvec3 l = lightView();
    const ShadeSettings settings = settingsFor(ShadingModel::Lambert);
    const cv::Mat image = render(settings);
    int compared = 0;
    int largestError = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> hit = kSphere.castPixel(col, row);
            const cv::Vec4b pixel = pixelAt(image, col, row);
            if (kSphere.pixelsFromSilhouette(col, row) > 1.0) {
                ASSERT_EQ(pixel[3] == 255, hit.has_value()) << "coverage at " << col << ", " << row;
            }
            if (pixel[3] != 255) {
                ASSERT_EQ(pixel, cv::Vec4b(0, 0, 0, 0)) << "background at " << col << ", " << row;
                continue;
            }
            if (!hit || kSphere.pixelsFromSilhouette(col, row) <= 1.5) continue;
            for (int c = 0; c < 3; ++c) {
                const double ambient = frame.ambientLight[c];
                const double diffuse = ambient + (1.0 - ambient) * std::max(glm::dot(hit->normal, l), 0.0);
                largestError = std::max(largestError, std::abs(int(pixel[c]) - srgbCode(double(base[c]) * diffuse)));
            }
            ++compared;
        }
    }
    EXPECT_GT(compared, 25000);
    EXPECT_LE(largestError, 1);
    std::printf("  lambert: %d pixels, largest error against the formula %d codes\n", compared, largestError);
}

TEST_F(ShadeSphere, RejectsMissingOrWrongShadeMapsAndBadSettings) {
    useSphere(8, 6, {0.8f, 0.8f, 0.8f, 1.0f});
    const auto message = [&](ShadeSettings settings, std::optional<ShadeMap> map) -> std::string {
        try {
            ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::move(map));
        } catch (const std::invalid_argument& error) {
            return error.what();
        }
        return "";
    };
    EXPECT_EQ(message(settingsFor(ShadingModel::Cel), std::nullopt), "ShadePass(): the 'cel' model needs a shade map");
    EXPECT_EQ(message(settingsFor(ShadingModel::Comic), std::nullopt),
              "ShadePass(): the 'comic' model needs a shade map");
    EXPECT_EQ(message(settingsFor(ShadingModel::Cel), makeDefaultComicShadeMap()),
              "ShadePass(): the 'cel' model needs a one-row shade map, 'builtin:comic' has 32 rows");
    EXPECT_EQ(message(settingsFor(ShadingModel::Phong, -1.0), std::nullopt),
              "ShadePass(): shininess must be finite and >= 0, got -1.000000");
    EXPECT_EQ(message(settingsFor(ShadingModel::Lambert), std::nullopt), "");
    // A one-row map is a valid comic map (t is then ignored).
    EXPECT_EQ(message(settingsFor(ShadingModel::Comic), makeBandShadeMap(4)), "");
}

// ---------------------------------------------------------------------------------------------------------------
// Per-mesh shade maps: two spheres side by side, each drawn with its own map.

/** A map of `rows` x `cols` texels of one colour. */
ShadeMap flatMap(cv::Vec4b color, int rows, int cols, const std::string& source) {
    return shadeMapFromImage(cv::Mat(rows, cols, CV_8UC4, cv::Scalar(color[0], color[1], color[2], color[3])), source,
                             false);
}

/** A comic map 8 wide: the lower half-map's rows are `shadow` left of column 2 and `lit` from there; above them come
 *  the specular bands, `rowsPerBand` rows each, the last of `highlights` at the top (t = 1). Row bands: one per
 *  highlight colour, plus the diffuse one. */
ShadeMap comicMap(cv::Vec4b shadow, cv::Vec4b lit, const std::vector<cv::Vec4b>& highlights, int rowsPerBand,
                  const std::string& source) {
    const int rows = 2 * rowsPerBand * int(highlights.size());
    cv::Mat texels(rows, 8, CV_8UC4);
    for (int row = 0; row < rows; ++row) {
        const int band = (rows - 1 - row) / rowsPerBand; // from the bottom
        const int highlight = band - int(highlights.size());
        for (int col = 0; col < 8; ++col)
            texels.at<cv::Vec4b>(row, col) =
                highlight >= 0 ? highlights[std::size_t(highlight)] : (col < 2 ? shadow : lit);
    }
    return shadeMapFromImage(texels, source, false);
}

/** The 8-bit colour a texel gives on a base colour: decoded, multiplied, encoded. */
cv::Vec3i shadedColor(cv::Vec4b texel, glm::vec4 base) {
    cv::Vec3i color;
    for (int c = 0; c < 3; ++c) color[c] = srgbCode(linearOf(texel[c]) * double(base[c]));
    return color;
}

bool near(cv::Vec4b pixel, cv::Vec3i color, int tolerance = 1) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(pixel[c]) - color[c]) > tolerance) return false;
    return true;
}

/** Pixels of `a` and `b` that differ in the left (`left`) or right half of the image. */
int differingPixels(const cv::Mat& a, const cv::Mat& b, bool left) {
    int count = 0;
    for (int row = 0; row < kSize; ++row)
        for (int col = left ? 0 : kSize / 2; col < (left ? kSize / 2 : kSize); ++col)
            if (pixelAt(a, col, row) != pixelAt(b, col, row)) ++count;
    return count;
}

class ShadeTwoSpheres : public ShadeSphere {
protected:
    /** Mesh 0 ("left") and mesh 1 ("right"): unit spheres at x = -1.25 and x = +1.25, seen from (0, 0, 6) with a 45
     *  degree field of view, so each lies wholly in its half of the image (the gap between them straddles the
     *  middle column). */
    void useTwoSpheres(glm::vec4 leftBase, glm::vec4 rightBase) {
        Mesh left = makeUvSphere({-1.25f, 0.0f, 0.0f}, 1.0f, 128, 64);
        left.name = "left";
        left.material.baseColorFactor = leftBase;
        Mesh right = makeUvSphere({1.25f, 0.0f, 0.0f}, 1.0f, 128, 64);
        right.name = "right";
        right.material.baseColorFactor = rightBase;
        scene = makeScene(std::move(left));
        scene.meshes.push_back(std::move(right));
        frame.camera = test::lookingAt(scene, glm::dvec3(0.0, 0.0, 6.0), glm::dvec3(0.0), 45.0, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        setLight(kHighlightLight);
    }

    /** render() with the face orientation set on the GpuScene (GpuScene::setOrientation()), if any. */
    cv::Mat renderWith(const ShadeSettings& settings, ShadeMap map) {
        ShadePass pass("shade", shaders, *gpuScene, frame, settings, std::move(map));
        const Plan plan = compile({&pass}, {"shade.color"});
        executor.run(plan, {&pass}, {kSize, kSize, false});
        cv::Mat image = executor.store().image("shade.color").clone();
        executor.store().clear();
        return image;
    }

    /** Covered pixels in each half; fails if a half holds no sphere or a sphere crosses the middle. */
    void expectEachSphereInItsHalf(const cv::Mat& image) {
        int covered[2] = {0, 0};
        for (int row = 0; row < kSize; ++row)
            for (int col = 0; col < kSize; ++col)
                if (pixelAt(image, col, row)[3] == 255) ++covered[col < kSize / 2 ? 0 : 1];
        EXPECT_GT(covered[0], 5000);
        EXPECT_GT(covered[1], 5000);
        for (int row = 0; row < kSize; ++row)
            for (int col : {kSize / 2 - 1, kSize / 2})
                ASSERT_EQ(pixelAt(image, col, row)[3], 0) << "the spheres must not reach the middle, row " << row;
    }

    static ShadeSettings withMeshMaps(ShadingModel model, double shininess,
                                      std::vector<std::optional<ShadeMap>> meshMaps) {
        ShadeSettings settings = settingsFor(model, shininess);
        settings.meshShadeMaps = std::move(meshMaps);
        return settings;
    }
};

TEST_F(ShadeTwoSpheres, CelMeshesTakeTheColourOfTheirOwnMap) {
    // One-texel maps: every pixel of a sphere is its map's colour times its base colour, whatever the lighting. The
    // default (five grey bands) is used by neither mesh.
    const glm::vec4 leftBase(0.9f, 0.6f, 0.3f, 1.0f);
    const glm::vec4 rightBase(0.4f, 0.7f, 1.0f, 1.0f);
    useTwoSpheres(leftBase, rightBase);
    const cv::Vec4b orange(240, 160, 40, 255);
    const cv::Vec4b teal(30, 200, 180, 255);
    const cv::Mat image = render(
        withMeshMaps(ShadingModel::Cel, 32.0, {flatMap(orange, 1, 1, "test:orange"), flatMap(teal, 1, 1, "test:teal")}),
        makeBandShadeMap(5));
    expectEachSphereInItsHalf(image);
    const cv::Vec3i expected[2] = {shadedColor(orange, leftBase), shadedColor(teal, rightBase)};
    int compared = 0;
    int wrong = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const cv::Vec4b pixel = pixelAt(image, col, row);
            if (pixel[3] != 255) continue;
            ++compared;
            // The shader encodes in float: one code off at most.
            if (!near(pixel, expected[col < kSize / 2 ? 0 : 1]) && ++wrong <= 5)
                ADD_FAILURE() << "col " << col << ", row " << row << ": " << pixel;
        }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(compared, 10000);
    std::printf("  cel per-mesh maps: %d pixels, each its own map's colour x base colour\n", compared);
}

TEST_F(ShadeTwoSpheres, PerMeshMapEqualToTheDefaultGivesTheSamePicture) {
    useTwoSpheres({0.9f, 0.6f, 0.3f, 1.0f}, {0.4f, 0.7f, 1.0f, 1.0f});
    // Cel: mesh 0 names a map equal to the default (a fresh copy), mesh 1 none.
    const cv::Mat celDefault = render(settingsFor(ShadingModel::Cel), makeBandShadeMap(5));
    const cv::Mat celPerMesh =
        render(withMeshMaps(ShadingModel::Cel, 32.0, {makeBandShadeMap(5), std::nullopt}), makeBandShadeMap(5));
    expectEachSphereInItsHalf(celDefault);
    EXPECT_EQ(cv::norm(celDefault, celPerMesh, cv::NORM_INF), 0.0);

    // Comic: both meshes name the same map while the default, which no mesh then uses, has more row bands. The
    // program must be the single-map pass's (SPECULAR_ROW_BANDS from the maps in use), so the picture is the same.
    const ShadeMap shared = comicMap({60, 60, 60, 255}, {170, 170, 170, 255}, {{255, 255, 255, 255}}, 4, "test:shared");
    const ShadeMap unused = comicMap({0, 0, 0, 255}, {90, 90, 90, 255},
                                     {{120, 0, 0, 255}, {0, 120, 0, 255}, {0, 0, 120, 255}}, 2, "test:unused");
    const cv::Mat comicDefault = render(settingsFor(ShadingModel::Comic, 16.0), shared);
    const cv::Mat comicPerMesh = render(withMeshMaps(ShadingModel::Comic, 16.0, {shared, shared}), unused);
    EXPECT_EQ(cv::norm(comicDefault, comicPerMesh, cv::NORM_INF), 0.0);
}

TEST_F(ShadeTwoSpheres, ComicMeshesUseTheirOwnTwoDimensionalMaps) {
    // Map A has one row border, map B two: the pass pads A's borders to B's count. Each half of the picture must be
    // bit for bit the picture of that map alone (the row is an integer found by the same comparisons).
    const glm::vec4 white(1.0f, 1.0f, 1.0f, 1.0f);
    useTwoSpheres(white, white);
    const cv::Vec4b aShadow(90, 30, 30, 255), aLit(200, 90, 80, 255), aHighlight(255, 230, 200, 255);
    const cv::Vec4b bShadow(20, 40, 90, 255), bLit(70, 140, 220, 255), bLow(160, 220, 255, 255),
        bHigh(250, 255, 255, 255);
    const ShadeMap a = comicMap(aShadow, aLit, {aHighlight}, 6, "test:a");
    const ShadeMap b = comicMap(bShadow, bLit, {bLow, bHigh}, 3, "test:b");
    ASSERT_EQ(specularRowBands(a, 16.0).maxHalfSquaredDistance.size(), 1u);
    ASSERT_EQ(specularRowBands(b, 16.0).maxHalfSquaredDistance.size(), 2u);

    const cv::Mat perMesh = render(withMeshMaps(ShadingModel::Comic, 16.0, {a, b}), makeDefaultComicShadeMap());
    const cv::Mat onlyA = render(settingsFor(ShadingModel::Comic, 16.0), a);
    const cv::Mat onlyB = render(settingsFor(ShadingModel::Comic, 16.0), b);
    expectEachSphereInItsHalf(perMesh);
    EXPECT_EQ(differingPixels(perMesh, onlyA, true), 0);
    EXPECT_EQ(differingPixels(perMesh, onlyB, false), 0);

    // Every tone of each map shows on its own sphere, and none of the other map's.
    const std::vector<cv::Vec4b> tones[2] = {{aShadow, aLit, aHighlight}, {bShadow, bLit, bLow, bHigh}};
    for (int half = 0; half < 2; ++half) {
        std::vector<int> counts(tones[half].size(), 0);
        int other = 0;
        for (int row = 0; row < kSize; ++row) {
            for (int col = half * kSize / 2; col < (half + 1) * kSize / 2; ++col) {
                const cv::Vec4b pixel = pixelAt(perMesh, col, row);
                if (pixel[3] != 255) continue;
                bool known = false;
                for (std::size_t k = 0; k < tones[half].size(); ++k)
                    if (near(pixel, shadedColor(tones[half][k], white))) {
                        ++counts[k];
                        known = true;
                    }
                if (!known) ++other;
            }
        }
        EXPECT_EQ(other, 0) << "half " << half << ": pixels of no tone of its map";
        for (std::size_t k = 0; k < counts.size(); ++k)
            EXPECT_GT(counts[k], 20) << "half " << half << ", tone " << k << " must show";
    }
}

TEST_F(ShadeTwoSpheres, ComicFaceOrientationSetsDrawWithEachMeshsMap) {
    // Winnemöller & Bangay's CPU marking: the pass draws the front sets with the per-vertex (s, t), one map per mesh.
    useTwoSpheres({1.0f, 1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    const ShadeMap a = comicMap({90, 30, 30, 255}, {200, 90, 80, 255}, {{255, 230, 200, 255}}, 6, "test:a");
    const ShadeMap b = comicMap({20, 40, 90, 255}, {70, 140, 220, 255}, {{160, 220, 255, 255}}, 3, "test:b");
    OrientationSettings orientationSettings;
    orientationSettings.method = FaceOrientationMethod::AfterVertices;
    orientationSettings.shininess = 16.0;
    gpuScene->setOrientation(frame, orientationSettings);
    ASSERT_NE(gpuScene->cpuOrientation(), nullptr);
    const cv::Mat perMesh = renderWith(withMeshMaps(ShadingModel::Comic, 16.0, {a, b}), makeDefaultComicShadeMap());
    const cv::Mat onlyA = renderWith(settingsFor(ShadingModel::Comic, 16.0), a);
    const cv::Mat onlyB = renderWith(settingsFor(ShadingModel::Comic, 16.0), b);
    expectEachSphereInItsHalf(perMesh);
    EXPECT_EQ(differingPixels(perMesh, onlyA, true), 0);
    EXPECT_EQ(differingPixels(perMesh, onlyB, false), 0);
    EXPECT_GT(cv::norm(onlyA, onlyB, cv::NORM_INF), 0.0); // the maps differ where it shows
}

TEST_F(ShadeTwoSpheres, ComicMapWithTooManyRowBandsTakesEveryMeshToTheGenericPath) {
    // Map M has 10 row borders, more than the comparison path takes, so the pass's one program evaluates
    // exp(n log(r.v)) for both meshes. M's half is exactly M alone (generic both times); A's half may differ from A
    // alone (comparisons) only where t lies within float rounding of A's border.
    useTwoSpheres({1.0f, 1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f});
    cv::Mat texels(20, 1, CV_8UC4);
    for (int row = 0; row < 20; ++row) {
        const uchar grey = row < 10 ? 255 : uchar(100 + row % 2);
        texels.at<cv::Vec4b>(row, 0) = cv::Vec4b(grey, grey, grey, 255);
    }
    const ShadeMap many = shadeMapFromImage(texels, "test:many-bands", false);
    const ShadeMap a = comicMap({90, 30, 30, 255}, {200, 90, 80, 255}, {{255, 230, 200, 255}}, 6, "test:a");
    const cv::Mat perMesh = render(withMeshMaps(ShadingModel::Comic, 16.0, {many, a}), makeDefaultComicShadeMap());
    const cv::Mat onlyMany = render(settingsFor(ShadingModel::Comic, 16.0), many);
    const cv::Mat onlyA = render(settingsFor(ShadingModel::Comic, 16.0), a);
    EXPECT_EQ(differingPixels(perMesh, onlyMany, true), 0);
    const int differing = differingPixels(perMesh, onlyA, false);
    EXPECT_LE(differing, 3);
    std::printf("  comic generic fall-back: %d pixels of the one-border map differ from its comparison path\n",
                differing);
}

TEST_F(ShadeTwoSpheres, DistinctMapsAreUploadedOnceAndWrongOnesRefused) {
    useTwoSpheres({0.8f, 0.8f, 0.8f, 1.0f}, {0.8f, 0.8f, 0.8f, 1.0f});
    const ShadeMap red = flatMap({255, 0, 0, 255}, 1, 4, "test:red");
    const ShadeMap blue = flatMap({0, 0, 255, 255}, 1, 4, "test:blue");
    const auto distinct = [&](ShadingModel model, std::vector<std::optional<ShadeMap>> meshMaps) {
        ShadePass pass("shade", shaders, *gpuScene, frame, withMeshMaps(model, 32.0, std::move(meshMaps)),
                       makeBandShadeMap(5));
        return pass.distinctShadeMapCount();
    };
    EXPECT_EQ(distinct(ShadingModel::Cel, {}), 1u);
    EXPECT_EQ(distinct(ShadingModel::Cel, {red, std::nullopt}), 2u);
    EXPECT_EQ(distinct(ShadingModel::Cel, {red, blue}), 2u); // the default is used by neither
    // Equal texels are one map, whatever their source says.
    ShadeMap redAgain = flatMap({255, 0, 0, 255}, 1, 4, "test:red-again");
    EXPECT_EQ(distinct(ShadingModel::Cel, {red, redAgain}), 1u);
    EXPECT_EQ(distinct(ShadingModel::Cel, {makeBandShadeMap(5), std::nullopt}), 1u);
    EXPECT_EQ(distinct(ShadingModel::Lambert, {red, blue}), 0u); // models without a map ignore them

    const auto message = [&](ShadingModel model, std::vector<std::optional<ShadeMap>> meshMaps) -> std::string {
        try {
            ShadePass pass("shade", shaders, *gpuScene, frame, withMeshMaps(model, 32.0, std::move(meshMaps)),
                           makeBandShadeMap(5));
        } catch (const std::invalid_argument& error) {
            return error.what();
        }
        return "";
    };
    EXPECT_EQ(message(ShadingModel::Cel, {std::nullopt, makeDefaultComicShadeMap()}),
              "ShadePass(): the 'cel' model needs a one-row shade map, 'builtin:comic' (mesh 1) has 32 rows");
    ShadeMap rgb{cv::Mat(1, 4, CV_8UC3, cv::Scalar(1, 2, 3)), "test:rgb"};
    EXPECT_EQ(message(ShadingModel::Comic, {rgb}),
              "ShadePass(): shade map 'test:rgb' (mesh 0) must be a non-empty CV_8UC4 image (see shadeMapFromImage())");
    EXPECT_EQ(message(ShadingModel::Cel, {red, blue, red}),
              "ShadePass(): 3 per-mesh shade maps for a scene of 2 meshes");
    EXPECT_EQ(message(ShadingModel::Comic, {makeDefaultComicShadeMap(), red}), ""); // one-row maps are comic maps too
}

} // namespace
} // namespace inkgraph::shade_gl_test
