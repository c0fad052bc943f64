// Lines that hold still (issue 39), as a test on generated shapes: every line type the comic and default looks draw
// on a torus and on a bumpy sphere keeps its skeleton F1 at 0.97 or more between 1024^2 and 2048^2 and between views
// 1 degree apart. The measure is bench/line-cleanliness.sh's (bench/LineCleanlinessMetrics.h: the drawn layer's
// skeleton, 1.5 px at the smaller size, views compared through depth both ways); the renders go through the public
// API with each look's defaults, at the default view (--orbit 0,14.04).
// Two cases render bundled models (Suzanne, Lucy) where the generated shapes did not show what they check.
#include <inkgraph/inkgraph.h>

#include "bench/LineCleanlinessMetrics.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace ig = inkgraph::api;

namespace inkgraph::bench {
namespace {

constexpr double kGoal = 0.97;       ///< the issue's floor for every type, size pair and turn
constexpr double kTolerance = 1.5;   ///< pixels of the smaller image (bench/line-cleanliness.sh)
constexpr double kElevation = 14.04; ///< the default view's elevation (the tool's view A)

struct MeshData {
    std::vector<float> vertices;
    std::vector<std::uint32_t> faces;
};

void addQuad(MeshData& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    mesh.faces.insert(mesh.faces.end(), {a, b, c, a, c, d});
}

/** A torus lying flat (its axis along y), ring radius 1 and tube radius 0.4, 160 x 80 quads: from 14 degrees above,
 *  its inner rim draws suggestive contours beside the contours. Normals are left to the loader, as for an OBJ. */
MeshData flatTorus() {
    constexpr int ring = 160, tube = 80;
    constexpr double R = 1.0, r = 0.4;
    MeshData mesh;
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) {
            const double u = 2.0 * std::numbers::pi * i / ring, v = 2.0 * std::numbers::pi * j / tube;
            const double spread = R + r * std::cos(v);
            mesh.vertices.insert(mesh.vertices.end(),
                                 {float(spread * std::cos(u)), float(r * std::sin(v)), float(-spread * std::sin(u))});
        }
    auto at = [&](int i, int j) { return std::uint32_t((i % ring) * tube + (j % tube)); };
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) addQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    return mesh;
}

/** A unit sphere with bumps, radius 1 + 0.08 sin(6 phi) sin(5 theta), 192 around and 96 rings: contours, the
 *  outline and suggestive contours in the valleys between the bumps. */
MeshData bumpySphere() {
    constexpr int around = 192, rings = 96;
    MeshData mesh;
    auto point = [&](double theta, double phi) {
        const double radius = 1.0 + 0.08 * std::sin(6.0 * phi) * std::sin(5.0 * theta);
        mesh.vertices.insert(mesh.vertices.end(),
                             {float(radius * std::sin(theta) * std::cos(phi)), float(radius * std::cos(theta)),
                              float(radius * std::sin(theta) * std::sin(phi))});
    };
    point(0.0, 0.0); // the north pole, vertex 0
    for (int k = 1; k < rings; ++k)
        for (int i = 0; i < around; ++i) point(std::numbers::pi * k / rings, 2.0 * std::numbers::pi * i / around);
    point(std::numbers::pi, 0.0);
    const std::uint32_t south = std::uint32_t(mesh.vertices.size() / 3 - 1);
    auto at = [&](int k, int i) { return std::uint32_t(1 + (k - 1) * around + (i % around)); };
    for (int i = 0; i < around; ++i) mesh.faces.insert(mesh.faces.end(), {0u, at(1, i + 1), at(1, i)});
    for (int k = 1; k + 1 < rings; ++k)
        for (int i = 0; i < around; ++i) addQuad(mesh, at(k, i), at(k, i + 1), at(k + 1, i + 1), at(k + 1, i));
    for (int i = 0; i < around; ++i)
        mesh.faces.insert(mesh.faces.end(), {at(rings - 1, i), at(rings - 1, i + 1), south});
    return mesh;
}

cv::Mat matOf(const ig::Image& image) {
    const int type = image.type() == ig::Image::Type::Float32 ? CV_32FC1 : CV_8UC1;
    return cv::Mat(image.height(), image.width(), type, const_cast<std::uint8_t*>(image.data()), image.rowBytes())
        .clone();
}

PinholeView viewOf(const ig::StillCamera& camera) {
    PinholeView view;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            view.view(row, col) = camera.view[std::size_t(row)][std::size_t(col)];
            view.projection(row, col) = camera.projection[std::size_t(row)][std::size_t(col)];
        }
    view.size = {camera.width, camera.height};
    return view;
}

/** One render's line skeletons (bench's skeletonPoints() of each drawn layer), depth and camera. */
struct Render {
    std::map<std::string, std::vector<cv::Point2d>> skeletons;
    cv::Mat depth;
    PinholeView view;
};

Render renderOnce(ig::Renderer& renderer, const ig::Scene& scene, const ig::Look& look, int size, double azimuth) {
    ig::Frame frame;
    frame.width = frame.height = size;
    frame.orbit = ig::Orbit{azimuth, kElevation};
    std::vector<std::string> buffers{"depth"};
    for (const ig::LineType type : look.lines()) buffers.push_back("lines." + ig::nameOf(type));
    const ig::Still still = renderer.render(scene, look, frame, buffers);
    Render result;
    for (const ig::LineType type : look.lines())
        result.skeletons[ig::nameOf(type)] = skeletonPoints(matOf(still.buffer("lines." + ig::nameOf(type))));
    result.depth = matOf(still.buffer("depth"));
    result.view = viewOf(still.camera());
    return result;
}

/** The one renderer of this binary (one GL context per process), shared by every test. */
ig::Renderer& sharedRenderer() {
    static ig::Renderer shared;
    return shared;
}

class LineStability : public ::testing::TestWithParam<const char*> {
protected:
    static ig::Renderer& renderer() { return sharedRenderer(); }

    /** Renders `mesh` with the look GetParam() names at 1024 and 2048 pixels and turned by +-1 degree, and checks
     *  every type it draws. */
    void expectStable(const MeshData& mesh, const char* meshName) {
        ig::MeshArrays arrays;
        arrays.vertices = mesh.vertices.data();
        arrays.vertexCount = mesh.vertices.size() / 3;
        arrays.faces = mesh.faces.data();
        arrays.faceCount = mesh.faces.size() / 3;
        const ig::Scene scene = ig::Scene::fromArrays(arrays, meshName);
        const ig::Look look = ig::Look::fromArguments(splitArguments(GetParam()));
        const Render a1024 = renderOnce(renderer(), scene, look, 1024, 0.0);
        const Render a2048 = renderOnce(renderer(), scene, look, 2048, 0.0);
        const Render turnedLeft = renderOnce(renderer(), scene, look, 1024, -1.0);
        const Render turnedRight = renderOnce(renderer(), scene, look, 1024, 1.0);
        for (const auto& [type, points] : a1024.skeletons) {
            SCOPED_TRACE(std::string(meshName) + ", " + GetParam() + ": " + type);
            // A type that draws nothing here (creases on smooth shapes) has nothing to hold still.
            if (points.empty() && a2048.skeletons.at(type).empty()) continue;
            ASSERT_GT(points.size(), 50u) << "too few skeleton points at 1024 to measure";
            const PointSetAgreement sizes = compareAcrossSizes(points, a2048.skeletons.at(type), 2.0, kTolerance);
            std::cout << meshName << " " << type << ": F1 1024/2048 " << sizes.f1;
            EXPECT_GE(sizes.f1, kGoal) << "1024/2048: precision " << sizes.precision << ", recall " << sizes.recall;
            for (const Render* turned : {&turnedLeft, &turnedRight}) {
                const ViewAgreement views =
                    compareAcrossViews(points, a1024.depth, a1024.view, turned->skeletons.at(type), turned->depth,
                                       turned->view, kTolerance);
                std::cout << (turned == &turnedLeft ? ", -1 degree " : ", +1 degree ") << views.agreement.f1;
                EXPECT_GE(views.agreement.f1, kGoal)
                    << "turned " << (turned == &turnedLeft ? "-1" : "+1") << " degree: precision "
                    << views.agreement.precision << ", recall " << views.agreement.recall;
            }
            std::cout << " (" << points.size() << " skeleton points at 1024)\n";
        }
    }

    static std::vector<std::string> splitArguments(const std::string& line) {
        std::vector<std::string> arguments;
        std::size_t start = 0;
        while (start < line.size()) {
            const std::size_t end = line.find(' ', start);
            arguments.push_back(line.substr(start, end == std::string::npos ? std::string::npos : end - start));
            if (end == std::string::npos) break;
            start = end + 1;
        }
        return arguments;
    }
};

TEST_P(LineStability, TorusHoldsStillAcrossSizesAndViews) { expectStable(flatTorus(), "torus"); }

TEST_P(LineStability, BumpySphereHoldsStillAcrossSizesAndViews) { expectStable(bumpySphere(), "bumpy sphere"); }

/** The default look's silhouette of bundled model `file` (under models/) at `smallerSize` and twice that, as the
 *  stability test compares them: F1 at least `floor`, with more than `minimumPoints` skeleton points at the smaller
 *  size to measure. */
void expectSilhouetteHoldsAcrossSizes(const std::string& file, int smallerSize, std::size_t minimumPoints,
                                      double floor) {
    const ig::Scene scene = ig::Scene::load(std::string(INKGRAPH_SOURCE_ROOT) + "/models/" + file);
    const ig::Look look = ig::Look::fromArguments({"--lines", "silhouette"});
    const Render smallerRender = renderOnce(sharedRenderer(), scene, look, smallerSize, 0.0);
    const Render largerRender = renderOnce(sharedRenderer(), scene, look, 2 * smallerSize, 0.0);
    const std::vector<cv::Point2d>& smaller = smallerRender.skeletons.at("silhouette");
    ASSERT_GT(smaller.size(), minimumPoints) << "too few skeleton points at " << smallerSize << " to measure";
    const PointSetAgreement sizes =
        compareAcrossSizes(smaller, largerRender.skeletons.at("silhouette"), 2.0, kTolerance);
    std::cout << file << " silhouette: F1 " << smallerSize << "/" << 2 * smallerSize << " " << sizes.f1 << " ("
              << smaller.size() << " skeleton points)\n";
    EXPECT_GE(sizes.f1, floor) << "precision " << sizes.precision << ", recall " << sizes.recall;
}

// Suzanne's ears, drawn by the default look's silhouette at 512^2 and 1024^2. The inner ear is seen at a grazing angle,
// where the inflated hull's back faces lie as good as on the visible surface: without the hull's polygon offset
// (passes/silhouette/SilhouettePass.cpp) they and the surface took turns pixel by pixel, and at 512^2 the ears drew
// strokes that 1024^2 did not (F1 0.968). With it: 0.992. A bundled model, not a generated shape: the thin shells
// tried (slabs, dishes, bent blades) hold at 1.000 with or without the offset.
TEST(LineStabilityOfBundledModels, SuzannesSilhouetteHoldsFrom512To1024) {
    expectSilhouetteHoldsAcrossSizes("suzanne_npm_4k.obj", 512, 500, 0.98);
}

// Lucy's wings, drawn by the default look's silhouette at 1024^2 and 2048^2. The inflated hull pokes through the
// thin wings as slivers: under a pixel at 1024^2, a pixel wide at 2048^2, where they were chained into strokes that
// 1024^2 did not draw (F1 0.948). The stroke stage now opens a band of one width by a pixel at 1024 rows, 2 x 2 at
// 2048^2 (openedBand(), passes/LineMaskTarget.h): 0.978.
TEST(LineStabilityOfBundledModels, LucysSilhouetteHoldsFrom1024To2048) {
    expectSilhouetteHoldsAcrossSizes("lucy_blendify_15k.obj", 1024, 1000, kGoal);
}

INSTANTIATE_TEST_SUITE_P(Looks, LineStability,
                         ::testing::Values("--shading comic --lines outline,contour,suggestive,crease",
                                           "--lines silhouette,contour"),
                         [](const ::testing::TestParamInfo<const char*>& look) {
                             return look.index == 0 ? std::string("Comic") : std::string("Default");
                         });

} // namespace
} // namespace inkgraph::bench
