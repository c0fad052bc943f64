// G-buffer of an analytic sphere against ray-cast ground truth: normals (angular error in degrees), n.v, |w|,
// linear depth and coverage, plus optional-output culling. Needs a GL context (llvmpipe in CI).
#include "gl/GraphExecutor.h"
#include "gl/ShaderLibrary.h"
#include "graph/GraphCompiler.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPass.h"
#include "scene/Camera.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/AnalyticSphere.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

namespace inkgraph {
namespace {

constexpr int kSize = 256;
constexpr double kRadius = 1.0;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 35.0;

const test::AnalyticSphereView kSphere{kSize, kRadius, kDistance, kFovDegrees};

class GBufferSphere : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override {
        test::sharedGlContext();
        scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, float(kRadius), 512, 256));
        frame.camera =
            test::lookingAt(scene, glm::dvec3(0.0, 0.0, kDistance), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
    }

    /** Compiles the single G-buffer pass for `requested` and runs it; returns the plan. */
    Plan render(const std::vector<std::string>& requested, int supersample = 1,
                GBufferPrecision precision = GBufferPrecision::Float32) {
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        pass = std::make_unique<GBufferPass>("gbuffer", shaders, *gpuScene, frame, supersample, precision);
        Plan plan = compile({pass.get()}, requested);
        executor.run(plan, {pass.get()}, {kSize, kSize, false});
        return plan;
    }

    std::unique_ptr<GBufferPass> pass;
};

TEST_F(GBufferSphere, MatchesRayCastSphere) {
    render({"gbuffer.normal", "gbuffer.view", "gbuffer.wVec", "gbuffer.nDotV", "gbuffer.depth", "gbuffer.coverage"});
    ResourceStore& store = executor.store();
    const cv::Mat& normal = store.image("gbuffer.normal");
    const cv::Mat& view = store.image("gbuffer.view");
    const cv::Mat& wVec = store.image("gbuffer.wVec");
    const cv::Mat& nDotV = store.image("gbuffer.nDotV");
    const cv::Mat& depth = store.image("gbuffer.depth");
    const cv::Mat& coverage = store.image("gbuffer.coverage");
    ASSERT_EQ(normal.type(), CV_32FC4);
    ASSERT_EQ(nDotV.type(), CV_32FC1);
    ASSERT_EQ(coverage.type(), CV_8UC1);

    std::vector<double> angleErrors;
    double maxNDotVError = 0.0, maxViewError = 0.0, maxDepthError = 0.0, maxWError = 0.0;
    int comparedPixels = 0;
    for (int row = 0; row < kSize; ++row) {
        for (int col = 0; col < kSize; ++col) {
            const std::optional<test::SphereHit> truth = kSphere.castPixel(col, row);
            const bool covered = coverage.at<uchar>(row, col) == 255;
            // Pixels within a pixel of the silhouette may go either way (the mesh is a polygon); elsewhere coverage
            // must match the analytic disc exactly.
            if (kSphere.pixelsFromSilhouette(col, row) > 1.0) {
                ASSERT_EQ(covered, truth.has_value()) << "coverage at col " << col << ", row " << row;
            }
            if (!covered) {
                ASSERT_EQ(depth.at<float>(row, col), 0.0f) << "background depth at " << col << "," << row;
                continue;
            }
            if (!truth || kSphere.pixelsFromSilhouette(col, row) <= 2.0) continue;
            const cv::Vec4f n = normal.at<cv::Vec4f>(row, col);
            const glm::dvec3 measured(n[0], n[1], n[2]);
            EXPECT_EQ(n[3], 1.0f);
            const double cosine = std::clamp(glm::dot(glm::normalize(measured), truth->normal), -1.0, 1.0);
            angleErrors.push_back(glm::degrees(std::acos(cosine)));
            const cv::Vec4f v = view.at<cv::Vec4f>(row, col);
            maxViewError = std::max(maxViewError, glm::length(glm::dvec3(v[0], v[1], v[2]) - truth->towardEye));
            const double trueNDotV = glm::dot(truth->normal, truth->towardEye);
            maxNDotVError = std::max(maxNDotVError, std::abs(double(nDotV.at<float>(row, col)) - trueNDotV));
            maxDepthError = std::max(maxDepthError, std::abs(double(depth.at<float>(row, col)) - truth->depth));
            // |w| = sin(theta) and w is tangent: |w|^2 + (n.v)^2 = 1.
            const cv::Vec4f w = wVec.at<cv::Vec4f>(row, col);
            const double wLengthSquared = double(w[0]) * w[0] + double(w[1]) * w[1] + double(w[2]) * w[2];
            const double measuredNDotV = nDotV.at<float>(row, col);
            maxWError = std::max(maxWError, std::abs(wLengthSquared + measuredNDotV * measuredNDotV - 1.0));
            ++comparedPixels;
        }
    }
    // The disc covers about pi * 66^2 pixels at this size; most of them must be compared.
    ASSERT_GT(comparedPixels, 12000);
    std::sort(angleErrors.begin(), angleErrors.end());
    const double medianAngle = angleErrors[angleErrors.size() / 2];
    const double maxAngle = angleErrors.back();
    // 512 x 256 segments: the faceted surface deviates by R(1 - cos(pi/512)) ~ 2e-5 and interpolated normals by
    // under 0.01 degree (measured on llvmpipe: median 0.0009, max 0.0096); a wrong matrix, a flip or a half-pixel
    // shift gives errors of degrees.
    EXPECT_LT(medianAngle, 0.005) << "median normal error in degrees";
    EXPECT_LT(maxAngle, 0.05) << "max normal error in degrees";
    EXPECT_LT(maxViewError, 1e-3);
    EXPECT_LT(maxNDotVError, 5e-3);
    EXPECT_LT(maxDepthError, 1e-3) << "linear depth error in world units (depth about 3)";
    EXPECT_LT(maxWError, 1e-5);
    RecordProperty("median_normal_error_degrees", std::to_string(medianAngle));
    RecordProperty("max_normal_error_degrees", std::to_string(maxAngle));
}

TEST_F(GBufferSphere, ComputesOnlyRequestedOptionalOutputs) {
    const Plan plan = render({"gbuffer.nDotV"});
    const PlannedPass* planned = plan.findPass("gbuffer");
    ASSERT_NE(planned, nullptr);
    EXPECT_EQ(planned->liveWrites, std::vector<std::string>{"gbuffer.nDotV"});
    // Every field but n.v is left out, and so is the z-buffer.
    EXPECT_EQ(planned->deadOptionalWrites.size(), GBufferPass::fields().size());
    EXPECT_EQ(executor.store().names(), std::vector<std::string>{"gbuffer.nDotV"});
    // n.v at the centre of a frontal sphere is 1 (the eye looks straight at the surface).
    const cv::Mat& nDotV = executor.store().image("gbuffer.nDotV");
    EXPECT_NEAR(nDotV.at<float>(kSize / 2, kSize / 2), 1.0f, 1e-3f);
}

/** The published z-buffer is the window depth the projection gives the linear depth: reversed-Z, z_w = (P[2][2] z_v +
 *  P[3][2]) / -z_v with z_v = -depth, and the far plane's 0 off the model. Alone, it is drawn depth only. */
TEST_F(GBufferSphere, ZBufferIsTheWindowDepthOfTheLinearDepth) {
    const Plan alone = render({"gbuffer.zBuffer"});
    EXPECT_EQ(alone.findPass("gbuffer")->liveWrites, std::vector<std::string>{"gbuffer.zBuffer"});
    const cv::Mat depthOnly = executor.store().image("gbuffer.zBuffer").clone();
    render({"gbuffer.zBuffer", "gbuffer.depth"});
    const cv::Mat zBuffer = executor.store().image("gbuffer.zBuffer");
    const cv::Mat depth = executor.store().image("gbuffer.depth");
    ASSERT_EQ(zBuffer.type(), CV_32FC1);
    EXPECT_EQ(cv::countNonZero(depthOnly != zBuffer), 0) << "drawing depth only changes the depth";
    const glm::dmat4 clipFromView(frame.clipFromView());
    int covered = 0;
    double maxRelativeError = 0.0;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) {
            const double linear = depth.at<float>(row, col);
            const double window = zBuffer.at<float>(row, col);
            if (linear == 0.0) {
                EXPECT_EQ(window, 0.0) << "off the model at " << col << "," << row;
                continue;
            }
            ++covered;
            const double expected = (clipFromView[2][2] * -linear + clipFromView[3][2]) / linear;
            maxRelativeError = std::max(maxRelativeError, std::abs(window - expected) / expected);
        }
    EXPECT_GT(covered, 12000);
    // Window depth is interpolated linearly on screen, the linear depth perspective-correctly, both in float32:
    // measured 2.2e-5 on llvmpipe. A standard (not reversed) depth or a wrong projection is off by over 10%.
    EXPECT_LT(maxRelativeError, 1e-4);
    RecordProperty("max_relative_error", std::to_string(maxRelativeError));
}

TEST_F(GBufferSphere, RadialFieldIsDeCarlosUnnormalisedFormWithImageSpaceW) {
    render({"gbuffer.radial", "gbuffer.depth"});
    const cv::Mat& radial = executor.store().image("gbuffer.radial");
    ASSERT_EQ(radial.type(), CV_32FC4);
    double maxFacingError = 0.0, maxDirectionDegrees = 0.0, maxLengthError = 0.0, maxWError = 0.0;
    int compared = 0;
    // Every 7th pixel of the disc away from the rim, against the ray-cast surface and a numerical image Jacobian.
    for (int row = 3; row < kSize; row += 7) {
        for (int col = 3; col < kSize; col += 7) {
            const std::optional<test::SphereHit> truth = kSphere.castPixel(col, row);
            if (!truth || kSphere.pixelsFromSilhouette(col, row) <= 3.0) continue;
            const cv::Vec4f value = radial.at<cv::Vec4f>(row, col);
            const glm::dvec3 towardEye = -truth->point; // unnormalised: c - p
            const double facing = glm::dot(truth->normal, towardEye);
            const glm::dvec3 w = towardEye - facing * truth->normal;
            // J w by central differences of the projection (x right, y down, pixels).
            const double step = 1e-4;
            const glm::dvec2 jw =
                (kSphere.project(truth->point + step * w) - kSphere.project(truth->point - step * w)) / (2.0 * step);
            maxFacingError = std::max(maxFacingError, std::abs(value[0] - facing));
            maxLengthError =
                std::max(maxLengthError, std::abs(std::hypot(value[1], value[2]) - glm::length(jw)) / glm::length(jw));
            if (glm::length(jw) > 1.0) {
                const double cosine = glm::dot(glm::normalize(glm::dvec2(value[1], value[2])), glm::normalize(jw));
                maxDirectionDegrees = std::max(maxDirectionDegrees, glm::degrees(std::acos(std::min(1.0, cosine))));
            }
            maxWError = std::max(maxWError, std::abs(value[3] - glm::dot(w, w)));
            ++compared;
        }
    }
    ASSERT_GT(compared, 200);
    // The interpolated normal is within 0.01 degree of the true one (see MatchesRayCastSphere): n.(c - p) is about
    // 3 units, so 1e-3 is the normal error times the distance, with room; a unit v or w.xy would miss by far more.
    EXPECT_LT(maxFacingError, 2e-3);
    EXPECT_LT(maxDirectionDegrees, 0.5);
    EXPECT_LT(maxLengthError, 0.01);
    EXPECT_LT(maxWError, 2e-3);
}

TEST_F(GBufferSphere, OffAxisViewKeepsTheWholeFrontOfTheSphere) {
    // The eye 4 from the centre looking 0.8 beside it: the sphere's front lies nearer along the view axis than its
    // centre's distance less the radius, so a near plane fitted to that distance clipped a cap off the front (a hole
    // showing the inside). Every pixel whose ray, and its neighbours' rays, hit the sphere must be covered at the
    // ray-cast depth.
    const glm::dvec3 eye(0.0, 0.0, kDistance), target(0.8, 0.0, 0.0);
    frame.camera = test::lookingAt(scene, eye, target, kFovDegrees, kSize, kSize);
    render({"gbuffer.depth", "gbuffer.coverage"});
    const cv::Mat& depth = executor.store().image("gbuffer.depth");
    const cv::Mat& coverage = executor.store().image("gbuffer.coverage");
    const glm::dvec3 forward = glm::normalize(target - eye);
    const glm::dmat3 worldFromView = glm::transpose(glm::dmat3(frame.camera.viewMatrix()));
    const double tanHalf = std::tan(glm::radians(kFovDegrees) / 2.0);
    // Linear depth of the sphere along a pixel's ray through (x, y) in pixels, or nothing when the ray misses.
    auto castDepth = [&](double x, double y) -> std::optional<double> {
        const double ndcX = (x + 0.5) / kSize * 2.0 - 1.0, ndcY = 1.0 - (y + 0.5) / kSize * 2.0;
        const glm::dvec3 ray = glm::normalize(worldFromView * glm::dvec3(ndcX * tanHalf, ndcY * tanHalf, -1.0));
        const glm::dvec3 toEye = eye; // the sphere's centre is the origin
        const double b = glm::dot(ray, toEye);
        const double discriminant = b * b - (glm::dot(toEye, toEye) - kRadius * kRadius);
        if (discriminant <= 0.0) return std::nullopt;
        const double t = -b - std::sqrt(discriminant);
        return glm::dot(t * ray, forward);
    };
    int checked = 0, wrong = 0;
    double worstDepth = 0.0;
    for (int row = 1; row + 1 < kSize; ++row)
        for (int col = 1; col + 1 < kSize; ++col) {
            bool inside = true;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1 && inside; ++dx) inside = castDepth(col + dx, row + dy).has_value();
            if (!inside) continue;
            ++checked;
            const double truth = *castDepth(col, row);
            const double error = std::abs(double(depth.at<float>(row, col)) - truth);
            worstDepth = std::max(worstDepth, error);
            if (coverage.at<uchar>(row, col) != 255 || error > 2e-3 * truth) ++wrong;
        }
    EXPECT_GT(checked, 5000);
    EXPECT_EQ(wrong, 0) << "pixels of the sphere's front missing or at the wrong depth; worst depth error "
                        << worstDepth;
    EXPECT_LT(frame.camera.zNear, glm::dot(-eye, forward) - kRadius);
}

TEST_F(GBufferSphere, SupersampleScalesEveryField) {
    const Plan plan = render({"gbuffer.depth", "gbuffer.radial"}, 2);
    const cv::Mat& depth = executor.store().image("gbuffer.depth");
    ASSERT_EQ(depth.size(), cv::Size(2 * kSize, 2 * kSize));
    EXPECT_EQ(plan.findResource("gbuffer.radial")->desc.scale, 2);
    // The sphere covers the same fraction of the frame: its centre row crosses it at the same relative place.
    int coveredInRow = 0;
    for (int col = 0; col < 2 * kSize; ++col) coveredInRow += depth.at<float>(kSize, col) > 0.0f;
    const double diameter =
        2.0 * kSphere.focalPixels() * kRadius / std::sqrt(kDistance * kDistance - kRadius * kRadius);
    EXPECT_NEAR(coveredInRow, 2.0 * diameter, 2.0);
}

TEST_F(GBufferSphere, ImageRowZeroIsTheTop) {
    // Light the top of the sphere only through geometry: the view-space normal's y is positive in the upper half.
    render({"gbuffer.normal"});
    const cv::Mat& normal = executor.store().image("gbuffer.normal");
    const int center = kSize / 2;
    EXPECT_GT(normal.at<cv::Vec4f>(center - 40, center)[1], 0.2f) << "upper half must face up (+y)";
    EXPECT_LT(normal.at<cv::Vec4f>(center + 40, center)[1], -0.2f);
    EXPECT_LT(normal.at<cv::Vec4f>(center, center - 40)[0], -0.2f) << "left half must face left (-x)";
}

TEST_F(GBufferSphere, HalfPrecisionStoresTheDirectionFieldsAsFloat16AndDepthAsFloat32) {
    const std::vector<std::string> fields = {"gbuffer.normal", "gbuffer.nDotV", "gbuffer.radial", "gbuffer.depth"};
    render(fields);
    std::map<std::string, cv::Mat> full;
    for (const std::string& field : fields) full[field] = executor.store().image(field).clone();
    const Plan plan = render(fields, 1, GBufferPrecision::Float16);
    EXPECT_EQ(plan.findResource("gbuffer.normal")->desc.format, Format::RGBA16F);
    EXPECT_EQ(plan.findResource("gbuffer.radial")->desc.format, Format::RGBA16F);
    EXPECT_EQ(plan.findResource("gbuffer.nDotV")->desc.format, Format::R16F);
    EXPECT_EQ(plan.findResource("gbuffer.depth")->desc.format, Format::R32F);
    for (const std::string& field : fields) {
        const cv::Mat& half = executor.store().image(field);
        ASSERT_EQ(half.type(), full[field].type()) << field << " is read back as float32";
        // Every value is a float16 (it survives a round trip through CV_16F), within half's relative step of the
        // float32 value; depth is float32 itself.
        cv::Mat asHalf, roundTrip;
        half.convertTo(asHalf, CV_16F);
        asHalf.convertTo(roundTrip, CV_32F);
        const double notHalf = cv::norm(half, roundTrip, cv::NORM_INF);
        const double difference = cv::norm(half, full[field], cv::NORM_INF);
        double largest = 0.0;
        cv::minMaxLoc(cv::Mat(cv::abs(full[field])).reshape(1), nullptr, &largest);
        if (field == "gbuffer.depth") {
            EXPECT_EQ(difference, 0.0) << field;
        } else {
            EXPECT_EQ(notHalf, 0.0) << field;
            EXPECT_GT(difference, 0.0) << field << ": float16 must round something";
            EXPECT_LE(difference, largest * 1e-3) << field; // 2^-11 relative rounding, of the largest value at most
        }
    }
}

TEST_F(GBufferSphere, RadialFieldIsMeasuredInTheLengthUnit) {
    // As if the model were scaled by 1/L: n.(c - p) shrinks by L, |w|^2 by L^2, and J w (pixels) stays.
    render({"gbuffer.radial"});
    const cv::Mat unitLength = executor.store().image("gbuffer.radial").clone();
    constexpr double kLengthUnit = 4.0;
    frame.radialLengthUnit = kLengthUnit;
    render({"gbuffer.radial"});
    const cv::Mat& scaled = executor.store().image("gbuffer.radial");
    int compared = 0;
    for (int row = 0; row < kSize; row += 3) {
        for (int col = 0; col < kSize; col += 3) {
            const cv::Vec4f a = unitLength.at<cv::Vec4f>(row, col);
            const cv::Vec4f b = scaled.at<cv::Vec4f>(row, col);
            if (a[0] == 0.0f) continue;
            ++compared;
            EXPECT_NEAR(b[0], a[0] / kLengthUnit, 1e-6 * std::abs(a[0]));
            EXPECT_NEAR(b[1], a[1], 1e-6 * std::abs(a[1]) + 1e-7);
            EXPECT_NEAR(b[2], a[2], 1e-6 * std::abs(a[2]) + 1e-7);
            EXPECT_NEAR(b[3], a[3] / (kLengthUnit * kLengthUnit), 1e-6 * std::abs(a[3]) + 1e-9);
        }
    }
    EXPECT_GT(compared, 1000);
}

// --- material ids ----------------------------------------------------------------------------------------------

/** Two cubes side by side, left and right of the centre, seen from the front; `right`'s material is set by the test. */
class GBufferMaterials : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override { test::sharedGlContext(); }

    /** Renders gbuffer.materialId (and coverage) of the two cubes at `precision`. */
    cv::Mat render(const Mesh& left, const Mesh& right, GBufferPrecision precision = GBufferPrecision::Float32) {
        scene = makeScene(left);
        scene.meshes.push_back(right);
        frame.camera = test::lookingAt(scene, glm::dvec3(0.0, 0.0, 8.0), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        GBufferPass pass("gbuffer", shaders, *gpuScene, frame, 1, precision);
        const Plan plan = compile({&pass}, {"gbuffer.materialId", "gbuffer.coverage"});
        EXPECT_EQ(plan.findResource("gbuffer.materialId")->desc.format, Format::R32F) << "ids must stay exact";
        executor.run(plan, {&pass}, {kSize, kSize, false});
        return executor.store().image("gbuffer.materialId").clone();
    }

    static Mesh cube(float x, std::string material, glm::vec4 color) {
        Mesh mesh = makeCube({x, 0.0f, 0.0f}, 0.8f);
        mesh.material.name = std::move(material);
        mesh.material.baseColorFactor = color;
        return mesh;
    }

    /** The distinct values of `ids` where `mask` is set (where it is not, with `outside`), ascending. */
    static std::vector<float> valuesIn(const cv::Mat& ids, const cv::Mat& mask, bool outside = false) {
        std::vector<float> values;
        for (int row = 0; row < ids.rows; ++row)
            for (int col = 0; col < ids.cols; ++col) {
                if ((mask.at<uchar>(row, col) != 0) == outside) continue;
                const float value = ids.at<float>(row, col);
                if (std::find(values.begin(), values.end(), value) == values.end()) values.push_back(value);
            }
        std::sort(values.begin(), values.end());
        return values;
    }

    static cv::Mat halfOf(const cv::Mat& coverage, bool leftHalf) {
        cv::Mat mask = coverage.clone();
        const int half = coverage.cols / 2;
        const cv::Rect otherHalf =
            leftHalf ? cv::Rect(half, 0, coverage.cols - half, coverage.rows) : cv::Rect(0, 0, half, coverage.rows);
        mask(otherHalf).setTo(0);
        return mask;
    }

    const glm::vec4 kRed{0.8f, 0.1f, 0.1f, 1.0f};
    const glm::vec4 kBlue{0.1f, 0.1f, 0.8f, 1.0f};
};

TEST_F(GBufferMaterials, TwoMaterialsGiveIdsOneAndTwoAndTheBackgroundZero) {
    const cv::Mat ids = render(cube(-1.2f, "paint", kRed), cube(1.2f, "metal", kBlue));
    ASSERT_EQ(ids.type(), CV_32FC1);
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    EXPECT_GT(cv::countNonZero(halfOf(coverage, true)), 1000);
    EXPECT_GT(cv::countNonZero(halfOf(coverage, false)), 1000);
    EXPECT_EQ(valuesIn(ids, halfOf(coverage, true)), std::vector<float>{1.0f}) << "the left cube, material 0";
    EXPECT_EQ(valuesIn(ids, halfOf(coverage, false)), std::vector<float>{2.0f}) << "the right cube, material 1";
    EXPECT_EQ(valuesIn(ids, coverage, true), std::vector<float>{0.0f}) << "off the model";
}

TEST_F(GBufferMaterials, EqualMaterialsShareOneId) {
    const cv::Mat ids = render(cube(-1.2f, "paint", kRed), cube(1.2f, "paint", kRed));
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    EXPECT_EQ(valuesIn(ids, coverage), std::vector<float>{1.0f});
    EXPECT_EQ(valuesIn(ids, coverage, true), std::vector<float>{0.0f});
}

TEST_F(GBufferMaterials, HalfPrecisionKeepsIdsFloat32) {
    const cv::Mat ids = render(cube(-1.2f, "", kRed), cube(1.2f, "", kBlue), GBufferPrecision::Float16);
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    EXPECT_EQ(valuesIn(ids, halfOf(coverage, true)), std::vector<float>{1.0f});
    EXPECT_EQ(valuesIn(ids, halfOf(coverage, false)), std::vector<float>{2.0f});
}

TEST_F(GBufferMaterials, AllFieldsTakeTwoDrawsThatCoverTheSamePixels) {
    // Thirteen live fields: barycentric has a draw of its own (with a geometry stage), and the other twelve exceed the
    // 8 draw buffers GL guarantees, so materialId, objectId, meshId and triangleId come from a third draw with its own
    // program; the vertex stage is invariant, so all three draws rasterise the same fragments, silhouettes included.
    Mesh left = makeUvSphere({-1.0f, 0.0f, 0.0f}, 1.1f, 48, 24);
    Mesh right = makeUvSphere({1.0f, 0.2f, -0.5f}, 1.1f, 48, 24);
    left.material.baseColorFactor = kRed;
    right.material.baseColorFactor = kBlue;
    scene = makeScene(left);
    scene.meshes.push_back(right);
    frame.camera = test::lookingAt(scene, glm::dvec3(0.3, 0.4, 7.0), glm::dvec3(0.0), kFovDegrees, kSize, kSize);
    frame.worldOrigin = glm::dvec3(0.0);
    gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
    GBufferPass pass("gbuffer", shaders, *gpuScene, frame);
    std::vector<std::string> every;
    for (const GBufferPass::Field& field : GBufferPass::fields()) every.push_back(std::string("gbuffer.") + field.name);
    ASSERT_EQ(every.size(), 13u);
    const Plan plan = compile({&pass}, every);
    EXPECT_EQ(plan.findResource("gbuffer.objectId")->desc.format, Format::R32F) << "ids must stay exact";
    executor.run(plan, {&pass}, {kSize, kSize, false});
    const cv::Mat ids = executor.store().image("gbuffer.materialId");
    const cv::Mat objects = executor.store().image("gbuffer.objectId");
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    const cv::Mat depth = executor.store().image("gbuffer.depth");
    const cv::Mat meshIds = executor.store().image("gbuffer.meshId");
    const cv::Mat triangleIds = executor.store().image("gbuffer.triangleId");
    const cv::Mat barycentric = executor.store().image("gbuffer.barycentric");
    int covered = 0, mismatched = 0;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) {
            const bool onModel = coverage.at<uchar>(row, col) != 0;
            covered += onModel;
            if (onModel != (ids.at<float>(row, col) > 0.0f) || onModel != (depth.at<float>(row, col) > 0.0f) ||
                onModel != (objects.at<float>(row, col) > 0.0f) || onModel != (meshIds.at<float>(row, col) > 0.0f) ||
                onModel != (triangleIds.at<float>(row, col) > 0.0f) ||
                onModel != (barycentric.at<cv::Vec4f>(row, col)[3] > 0.0f))
                ++mismatched;
        }
    EXPECT_GT(covered, 1000);
    EXPECT_EQ(mismatched, 0) << "the two draws covered different pixels";
    EXPECT_EQ(valuesIn(ids, coverage), (std::vector<float>{1.0f, 2.0f}));
    // Meshes without node paths (a file without nodes) are one object.
    EXPECT_EQ(valuesIn(objects, coverage), std::vector<float>{1.0f});
    EXPECT_EQ(valuesIn(objects, coverage, true), std::vector<float>{0.0f});
    EXPECT_EQ(valuesIn(meshIds, coverage), (std::vector<float>{1.0f, 2.0f}));
}

} // namespace
} // namespace inkgraph
