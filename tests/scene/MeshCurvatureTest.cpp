// scene/mesh/MeshCurvature against analytic surfaces: a sphere (kappa = 1/R, C = 0), a torus (kappa_v = 1/r along the
// tube, kappa_u = cos v / (R + r cos v) around it, and C's one non-zero component d kappa_u / ds_v), degenerate input,
// and welding (a cube with split normals, a triangle soup).
#include "scene/mesh/MeshCurvature.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph {
namespace {

MeshCurvature curvatureOf(const Mesh& mesh) { return computeMeshCurvature(mesh.positions, mesh.triangles, 1e-6); }

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void expectAllFinite(const MeshCurvature& curvature) {
    for (std::size_t vertex = 0; vertex < curvature.positions.size(); ++vertex) {
        ASSERT_TRUE(isFinite(curvature.normals[vertex])) << "vertex " << vertex;
        ASSERT_TRUE(std::isfinite(curvature.curvature1[vertex]) && std::isfinite(curvature.curvature2[vertex]))
            << "vertex " << vertex;
        ASSERT_TRUE(isFinite(curvature.direction1[vertex]) && isFinite(curvature.direction2[vertex]))
            << "vertex " << vertex;
        const glm::dvec4& c = curvature.derivative[vertex];
        ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w))
            << "vertex " << vertex;
        ASSERT_TRUE(std::isfinite(curvature.pointAreas[vertex]));
    }
}

TEST(MeshCurvature, SphereHasCurvatureOneOverRadiusEverywhere) {
    const double radius = 2.0;
    const Mesh sphere = makeUvSphere({0.5f, -1.0f, 0.25f}, float(radius), 128, 64);
    const MeshCurvature curvature = curvatureOf(sphere);
    ASSERT_EQ(curvature.positions.size(), sphere.positions.size());
    EXPECT_EQ(curvature.counts.degenerateFaces, 0u);
    EXPECT_EQ(curvature.counts.singularCurvatureFits, 0u);
    EXPECT_EQ(curvature.counts.isolatedVertices, 0u);
    expectAllFinite(curvature);
    const glm::dvec3 center(0.5, -1.0, 0.25);
    double worstCurvature = 0.0, sumCurvature = 0.0, worstNormal = 0.0, worstDerivative = 0.0, area = 0.0;
    for (std::size_t vertex = 0; vertex < curvature.positions.size(); ++vertex) {
        const glm::dvec3 exactNormal = glm::normalize(curvature.positions[vertex] - center);
        worstNormal = std::max(worstNormal, glm::length(curvature.normals[vertex] - exactNormal));
        for (double kappa : {curvature.curvature1[vertex], curvature.curvature2[vertex]}) {
            const double error = std::abs(kappa * radius - 1.0);
            worstCurvature = std::max(worstCurvature, error);
            sumCurvature += error;
        }
        const glm::dvec4 c = curvature.derivative[vertex] * radius * radius; // dimensionless
        worstDerivative = std::max({worstDerivative, std::abs(c.x), std::abs(c.y), std::abs(c.z), std::abs(c.w)});
        EXPECT_NEAR(glm::dot(curvature.direction1[vertex], curvature.normals[vertex]), 0.0, 1e-9);
        EXPECT_NEAR(glm::dot(curvature.direction2[vertex], curvature.normals[vertex]), 0.0, 1e-9);
        EXPECT_NEAR(glm::dot(curvature.direction1[vertex], curvature.direction2[vertex]), 0.0, 1e-9);
        area += curvature.pointAreas[vertex];
    }
    const double meanCurvature = sumCurvature / double(2 * curvature.positions.size());
    // Max's weights give the exact normal at a vertex on a sphere; what is left is the float positions' rounding
    // (measured 1.5e-6).
    EXPECT_LT(worstNormal, 1e-5);
    // Measured (128 x 64): worst relative error of kappa 1.3e-4, mean 5e-6.
    EXPECT_LT(worstCurvature, 1e-3);
    EXPECT_LT(meanCurvature, 2e-5);
    // C = 0 on a sphere. Measured: worst |C| R^2 = 0.040 (a difference of curvatures over one edge, divided by the
    // edge, so it amplifies their error by 1 / (edge kappa) ~ 20 here); tolerance twice that.
    EXPECT_LT(worstDerivative, 0.08);
    // Point areas tile the polyhedron, whose area is within 0.1% of the sphere's.
    EXPECT_NEAR(area, 4.0 * glm::pi<double>() * radius * radius, 1e-3 * 4.0 * glm::pi<double>() * radius * radius);
    RecordProperty("worst_relative_curvature_error", std::to_string(worstCurvature));
    RecordProperty("mean_relative_curvature_error", std::to_string(meanCurvature));
    RecordProperty("worst_derivative_R2", std::to_string(worstDerivative));
}

/** The torus of makeTorus(): P(u, v) = ((R + r cos v) cos u, (R + r cos v) sin u, r sin v). */
struct Torus {
    double ring = 1.0;
    double tube = 0.35;
    glm::dvec2 parameters(const glm::dvec3& p) const {
        return {std::atan2(p.y, p.x), std::atan2(p.z, std::hypot(p.x, p.y) - ring)};
    }
    glm::dvec3 tangentU(double u) const { return {-std::sin(u), std::cos(u), 0.0}; }
    glm::dvec3 tangentV(double u, double v) const {
        return {-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v)};
    }
    double curvatureU(double v) const { return std::cos(v) / (ring + tube * std::cos(v)); }
    double curvatureV() const { return 1.0 / tube; }
    /** d kappa_u / ds_v with s_v = r v: C(e_v, e_u, e_u), the only component of C not zero by symmetry. */
    double curvatureUAlongTube(double v) const {
        const double radius = ring + tube * std::cos(v);
        return -ring * std::sin(v) / (tube * radius * radius);
    }
};

TEST(MeshCurvature, TorusMatchesTheAnalyticPrincipalCurvaturesDirectionsAndDerivative) {
    const Torus torus;
    const Mesh mesh = makeTorus(float(torus.ring), float(torus.tube), 256, 96);
    const MeshCurvature curvature = curvatureOf(mesh);
    ASSERT_EQ(curvature.positions.size(), 256u * 96u);
    EXPECT_EQ(curvature.counts.singularCurvatureFits + curvature.counts.singularDerivativeFits, 0u);
    expectAllFinite(curvature);
    double worstTube = 0.0, worstAround = 0.0, worstDirection = 0.0, worstDerivative = 0.0, worstOther = 0.0;
    for (std::size_t vertex = 0; vertex < curvature.positions.size(); ++vertex) {
        const glm::dvec2 uv = torus.parameters(curvature.positions[vertex]);
        // |kappa_v| = 2.86 > |kappa_u| <= 1.54 everywhere: kappa1 runs along the tube.
        worstTube = std::max(worstTube, std::abs(curvature.curvature1[vertex] - torus.curvatureV()));
        worstAround = std::max(worstAround, std::abs(curvature.curvature2[vertex] - torus.curvatureU(uv.y)));
        const double alongTube = glm::dot(curvature.direction1[vertex], torus.tangentV(uv.x, uv.y));
        worstDirection = std::max(worstDirection, 1.0 - std::abs(alongTube));
        // C(e1, e2, e2) = C122 flips with e1's sign; C111, C112 and C222 vanish.
        const glm::dvec4& c = curvature.derivative[vertex];
        const double sign = alongTube < 0.0 ? -1.0 : 1.0;
        worstDerivative = std::max(worstDerivative, std::abs(sign * c.z - torus.curvatureUAlongTube(uv.y)));
        worstOther = std::max({worstOther, std::abs(c.x), std::abs(c.y), std::abs(c.w)});
    }
    // Measured (256 x 96 vertices): worst |kappa1 - 1/r| = 4.6e-4 (0.016% of 2.86), worst |kappa2 - kappa_u| =
    // 1.5e-3 (0.1% of its peak 1.54), directions exact to 1 - |cos| < 1e-6, worst C122 error 0.016 against a peak
    // of 3.6 (0.45%), other components at most 0.0092. Tolerances are about twice the measurements.
    EXPECT_LT(worstTube, 1e-3);
    EXPECT_LT(worstAround, 3e-3);
    EXPECT_LT(worstDirection, 1e-6);
    EXPECT_LT(worstDerivative, 0.03);
    EXPECT_LT(worstOther, 0.02);
    RecordProperty("worst_kappa_v_error", std::to_string(worstTube));
    RecordProperty("worst_kappa_u_error", std::to_string(worstAround));
    RecordProperty("worst_direction_error", std::to_string(worstDirection));
    RecordProperty("worst_c122_error", std::to_string(worstDerivative));
    RecordProperty("worst_other_c", std::to_string(worstOther));
}

TEST(MeshCurvature, DegenerateFacesGiveFiniteResults) {
    // A fan around vertex 0 on a bumpy cap, plus: a zero-area face (collinear), a face with a repeated vertex, a
    // needle (area just above the degenerate limit, so its fits are singular), and an isolated vertex.
    std::vector<glm::vec3> positions = {{0.0f, 0.0f, 0.2f}};
    for (int i = 0; i < 6; ++i) {
        const float angle = float(i) * glm::pi<float>() / 3.0f;
        positions.push_back({std::cos(angle), std::sin(angle), 0.05f * float(i % 2)});
    }
    std::vector<glm::uvec3> triangles;
    for (std::uint32_t i = 0; i < 6; ++i) triangles.push_back({0u, 1u + i, 1u + (i + 1) % 6});
    positions.push_back({2.0f, 0.0f, 0.0f});  // 7: collinear with 1 and 8
    positions.push_back({3.0f, 0.0f, 0.0f});  // 8
    triangles.push_back({1u, 7u, 8u});        // zero area
    triangles.push_back({1u, 1u, 2u});        // repeated vertex
    positions.push_back({3.0f, 1e-5f, 0.0f}); // 9: a needle with 7 and 8
    triangles.push_back({7u, 8u, 9u});
    positions.push_back({5.0f, 5.0f, 5.0f}); // 10: used by no face
    const MeshCurvature curvature = computeMeshCurvature(positions, triangles, 0.0);
    expectAllFinite(curvature);
    EXPECT_EQ(curvature.counts.degenerateFaces, 2u);
    EXPECT_EQ(curvature.triangles.size(), 7u);
    EXPECT_GE(curvature.counts.isolatedVertices, 1u);
    EXPECT_EQ(curvature.curvature1[10], 0.0);
    EXPECT_EQ(curvature.normals[10], glm::dvec3(0.0, 0.0, 1.0));
    // The cap's centre bends away from its upward normal: positive mean curvature.
    EXPECT_GT(curvature.normals[0].z, 0.9);
    EXPECT_GT(curvature.curvature1[0] + curvature.curvature2[0], 0.0);

    // Every face degenerate: nothing usable, still finite.
    const std::vector<glm::vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    const std::vector<glm::uvec3> flat = {{0u, 1u, 2u}};
    const MeshCurvature none = computeMeshCurvature(line, flat, 0.0);
    expectAllFinite(none);
    EXPECT_EQ(none.triangles.size(), 0u);
    EXPECT_EQ(none.counts.isolatedVertices, 3u);
}

TEST(MeshCurvature, SplitNormalsAndSoupsAreWelded) {
    const Mesh cube = makeCube({0.0f, 0.0f, 0.0f}, 1.0f);
    ASSERT_EQ(cube.positions.size(), 24u);
    const MeshCurvature welded = curvatureOf(cube);
    EXPECT_EQ(welded.counts.weldedVertices, 8u);
    ASSERT_EQ(welded.weldedOf.size(), 24u);
    expectAllFinite(welded);
    for (std::size_t vertex = 0; vertex < 8; ++vertex) {
        // Each corner's normal points out along its diagonal (within the triangulation's asymmetry), and the corner
        // is convex: unwelded, each face's copy would see a flat square and zero curvature.
        const glm::dvec3 diagonal = glm::normalize(welded.positions[vertex]);
        EXPECT_GT(glm::dot(welded.normals[vertex], diagonal), 0.9) << "vertex " << vertex;
        EXPECT_GT(welded.curvature1[vertex], 0.3) << "vertex " << vertex;
    }
    const MeshCurvature unwelded = computeMeshCurvature(cube.positions, cube.triangles, 0.0);
    EXPECT_EQ(unwelded.counts.weldedVertices, 8u) << "copies at exactly one position weld even at distance 0";

    // A soup (every triangle its own three vertices) of a sphere gives the same curvature as the indexed sphere.
    const Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 32, 16);
    std::vector<glm::vec3> soup;
    std::vector<glm::uvec3> soupTriangles;
    for (const glm::uvec3& triangle : sphere.triangles) {
        const auto first = std::uint32_t(soup.size());
        for (int corner = 0; corner < 3; ++corner) soup.push_back(sphere.positions[triangle[corner]]);
        soupTriangles.push_back({first, first + 1, first + 2});
    }
    const MeshCurvature indexed = curvatureOf(sphere);
    const MeshCurvature fromSoup = computeMeshCurvature(soup, soupTriangles, 1e-6);
    ASSERT_EQ(fromSoup.counts.weldedVertices, indexed.counts.weldedVertices);
    for (std::size_t input = 0; input < soup.size(); ++input) {
        const std::uint32_t a = fromSoup.weldedOf[input];
        const std::uint32_t b = indexed.weldedOf[sphere.triangles[input / 3][int(input % 3)]];
        EXPECT_NEAR(fromSoup.curvature1[a], indexed.curvature1[b], 1e-9);
        EXPECT_NEAR(fromSoup.curvature2[a], indexed.curvature2[b], 1e-9);
    }
}

TEST(MeshCurvature, ASmoothingTooCostlyIsRefusedBeforeItIsSpent) {
    // A sphere of 33,000 vertices smoothed over its whole radius: every window floods the whole mesh, about 1.1e9
    // visits a smoothing (minutes), refused at once with the largest smoothing not refused; a hundredth of the
    // radius is a few hundred visits a vertex and runs.
    const Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    try {
        (void)computeMeshCurvature(sphere.positions, sphere.triangles, 1e-6, 1.0);
        FAIL() << "a smoothing of the whole sphere was not refused";
    } catch (const SmoothingTooCostlyError& costly) {
        EXPECT_GT(costly.estimatedVisits(), kMaxSmoothingVisits);
        EXPECT_EQ(costly.smoothing(), 1.0);
        EXPECT_GT(costly.vertexCount(), 32000u);
        // Windows of area pi (3 s)^2 on a surface of 4 pi hold 9 s^2 / 4 of the mesh: within the limit while
        // N^2 x 9 s^2 / 4 <= 5e8 (s <= 0.45 on a flat patch; the sphere's curve holds a little more).
        EXPECT_GT(costly.smoothingWithinLimit(), 0.3);
        EXPECT_LT(costly.smoothingWithinLimit(), 0.5);
        EXPECT_NE(
            std::string(costly.what()).find("computeMeshCurvature(): a 'smoothing' of 1 model units floods about"),
            std::string::npos)
            << costly.what();
    }
    EXPECT_NO_THROW((void)computeMeshCurvature(sphere.positions, sphere.triangles, 1e-6, 0.01));
}

TEST(MeshCurvature, AFineMeshAtANarrowSmoothingIsSlowNotRefused) {
    // A flat grid of a million vertices at a hundredth of its half-diagonal (the object-space lines' default): about
    // 1e3 vertices a window, 1e9 visits, over kMaxSmoothingVisits, but each window a thousandth of the mesh: a fine
    // mesh, not a wide smoothing, so it is not refused. Ten times wider, each window holds a tenth: refused.
    constexpr int kSide = 1000;
    std::vector<glm::vec3> positions;
    positions.reserve(std::size_t(kSide) * kSide);
    for (int row = 0; row < kSide; ++row)
        for (int column = 0; column < kSide; ++column) positions.emplace_back(float(column), float(row), 0.0f);
    std::vector<glm::uvec3> triangles;
    for (int row = 0; row + 1 < kSide; ++row)
        for (int column = 0; column + 1 < kSide; ++column) {
            const unsigned corner = unsigned(row * kSide + column);
            triangles.emplace_back(corner, corner + 1, corner + kSide);
            triangles.emplace_back(corner + 1, corner + kSide + 1, corner + kSide);
        }
    const WeldMap weld = weldVertices(positions, {}, 1e-6);
    const double halfDiagonal = 0.5 * std::sqrt(2.0) * (kSide - 1);
    EXPECT_NO_THROW(requireAffordableSmoothing(positions, triangles, weld, 0.01 * halfDiagonal));
    EXPECT_THROW(requireAffordableSmoothing(positions, triangles, weld, 0.1 * halfDiagonal), SmoothingTooCostlyError);
}

TEST(MeshCurvature, ASmoothingIsJudgedOverEveryMeshOfTheModel) {
    // One sphere of 33,000 vertices at a smoothing of 0.35 of its radius: windows of 9 x 0.35^2 / 4 = 28% of it,
    // about 3e8 visits, within the limit. Three such meshes make 9e8 in all: refused, though each alone is not.
    const Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 256, 128);
    const WeldMap weld = weldVertices(sphere.positions, {}, 1e-6);
    const MeshToSmooth one{sphere.positions, sphere.triangles, &weld};
    const std::vector<MeshToSmooth> three(3, one);
    EXPECT_NO_THROW(requireAffordableSmoothing(std::span<const MeshToSmooth>(&one, 1), 0.35));
    try {
        requireAffordableSmoothing(three, 0.35);
        FAIL() << "three meshes of 3e8 visits each were not refused";
    } catch (const SmoothingTooCostlyError& costly) {
        EXPECT_GT(costly.estimatedVisits(), kMaxSmoothingVisits);
        EXPECT_EQ(costly.vertexCount(), 3 * weld.kept.size());
        EXPECT_GT(costly.smoothingWithinLimit(), 0.1);
        EXPECT_LT(costly.smoothingWithinLimit(), 0.35);
    }
}

TEST(MeshCurvature, BadInputIsAClearError) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<glm::uvec3> outOfRange = {{0u, 1u, 3u}};
    try {
        computeMeshCurvature(positions, outOfRange, 0.0);
        FAIL() << "expected std::out_of_range";
    } catch (const std::out_of_range& error) {
        EXPECT_NE(std::string(error.what()).find("computeMeshCurvature(): 'triangles'"), std::string::npos)
            << error.what();
    }
    const std::vector<glm::uvec3> good = {{0u, 1u, 2u}};
    EXPECT_THROW(computeMeshCurvature(positions, good, -1.0), std::invalid_argument);
    EXPECT_THROW(computeMeshCurvature(positions, good, std::nan("")), std::invalid_argument);
    const std::vector<glm::vec3> infinite = {{0, 0, 0}, {1, 0, 0}, {0, INFINITY, 0}};
    EXPECT_THROW(computeMeshCurvature(infinite, good, 0.0), std::invalid_argument);
}

} // namespace
} // namespace inkgraph

namespace inkgraph {
namespace {

TEST(MeshCurvature, SmoothingBringsANoisySphereBackToOneOverRadius) {
    // A scan-like sphere: every vertex moved along its radius by up to +-0.3% of R (deterministic), a fifth of an
    // edge. Unsmoothed, the fits turn that into curvature noise; smoothed over sigma = 3% of R (rtsc's diffusion), the
    // curvature is close to 1/R again and C to 0.
    Mesh sphere = makeUvSphere(glm::vec3(0.0f), 1.0f, 256, 128);
    std::uint32_t state = 12345u;
    for (glm::vec3& p : sphere.positions) {
        state = state * 1664525u + 1013904223u;
        const float offset = 0.003f * (float(state >> 8) / float(1u << 24) * 2.0f - 1.0f);
        p *= 1.0f + offset;
    }
    auto errors = [&](double smoothing) {
        const MeshCurvature curvature = computeMeshCurvature(sphere.positions, sphere.triangles, 1e-6, smoothing);
        double curvatureError = 0.0, derivative = 0.0;
        for (std::size_t vertex = 0; vertex < curvature.positions.size(); ++vertex) {
            curvatureError +=
                std::abs(curvature.curvature1[vertex] - 1.0) + std::abs(curvature.curvature2[vertex] - 1.0);
            derivative += glm::length(curvature.derivative[vertex]);
        }
        const double count = double(curvature.positions.size());
        return std::pair<double, double>(curvatureError / (2.0 * count), derivative / count);
    };
    const auto [rawCurvature, rawDerivative] = errors(0.0);
    const auto [smoothCurvature, smoothDerivative] = errors(0.03);
    std::cout << "noisy sphere: mean |kappa - 1/R| R " << rawCurvature << " -> " << smoothCurvature << ", mean |C| R^2 "
              << rawDerivative << " -> " << smoothDerivative << "\n";
    EXPECT_LT(smoothCurvature, 0.25 * rawCurvature);
    EXPECT_LT(smoothDerivative, 0.25 * rawDerivative);
    EXPECT_THROW(computeMeshCurvature(sphere.positions, sphere.triangles, 1e-6, -1.0), std::invalid_argument);
    EXPECT_THROW(computeMeshCurvature(sphere.positions, sphere.triangles, 1e-6, std::nan("")), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
