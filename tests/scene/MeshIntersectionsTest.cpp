// scene/mesh/MeshIntersections: two interpenetrating spheres against their exact intersection circle (within the
// faceting error, computed from the meshes), the touching rule (boxes face to face, a sphere resting on a plane at a
// vertex: none), the self-intersection rule (two quads of one mesh crossing: the exact segment; triangles of one mesh
// sharing a vertex by position: skipped), and a closed sphere alone: none.
#include "scene/mesh/MeshIntersections.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace inkgraph {
namespace {

constexpr double kRadius = 0.8;
constexpr double kOffset = 0.45;

/** A mesh of separate triangles, each with its own three vertices (as an STL file gives them). */
Mesh soup(const std::vector<std::array<glm::vec3, 3>>& triangles) {
    Mesh mesh;
    mesh.name = "soup";
    for (const auto& triangle : triangles) {
        const auto first = std::uint32_t(mesh.positions.size());
        for (const glm::vec3& corner : triangle) {
            mesh.positions.push_back(corner);
            mesh.normals.push_back({0.0f, 0.0f, 1.0f});
        }
        mesh.triangles.push_back({first, first + 1, first + 2});
    }
    return mesh;
}

/** A quad (a, b, c, d counter-clockwise) as two triangles. */
std::vector<std::array<glm::vec3, 3>> quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    return {{a, b, c}, {a, c, d}};
}

/** How far inside its sphere a faceted sphere's surface reaches: the radius less the nearest triangle plane's
 *  distance from the centre (every point of a triangle is at least that far from the centre, at most R). */
double facetingDepth(const Mesh& sphere, glm::dvec3 centre) {
    double nearest = kRadius;
    for (const glm::uvec3& t : sphere.triangles) {
        const glm::dvec3 a(sphere.positions[t.x]), b(sphere.positions[t.y]), c(sphere.positions[t.z]);
        const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
        nearest = std::min(nearest, std::abs(glm::dot(normal, a - centre)));
    }
    return kRadius - nearest;
}

MeshIntersections search(const std::vector<Mesh>& meshes) { return findMeshIntersections(meshes, 1e-6); }

TEST(MeshIntersections, TwoSpheresCrossOnTheirExactCircleWithinTheFacetingError) {
    const glm::dvec3 right(kOffset, 0.0, 0.0), left(-kOffset, 0.0, 0.0);
    // Different tessellations, so nothing lines up by symmetry.
    const std::vector<Mesh> meshes = {makeUvSphere(glm::vec3(right), float(kRadius), 64, 32),
                                      makeUvSphere(glm::vec3(left), float(kRadius), 56, 28)};
    const MeshIntersections found = search(meshes);
    ASSERT_GT(found.segments.size(), 100u);
    EXPECT_EQ(found.report.segments, found.segments.size());
    EXPECT_EQ(found.report.selfSegments, 0u);
    EXPECT_EQ(found.report.triangles, meshes[0].triangles.size() + meshes[1].triangles.size());

    const double depth = std::max(facetingDepth(meshes[0], right), facetingDepth(meshes[1], left));
    // A point on both faceted surfaces is between R - depth and R from both centres; as d_right^2 - d_left^2 =
    // -4 offset x, |x| <= (R^2 - (R - depth)^2) / (4 offset), and its distance from the x axis follows.
    const double slack = 1e-6; // float positions
    const double xBound = (kRadius * kRadius - (kRadius - depth) * (kRadius - depth)) / (4.0 * kOffset) + slack;
    const double rhoLow = std::sqrt(std::pow(kRadius - depth, 2) - std::pow(kOffset + xBound, 2)) - slack;
    const double rhoHigh = std::sqrt(kRadius * kRadius - std::pow(kOffset - xBound, 2)) + slack;
    const double exact = std::sqrt(kRadius * kRadius - kOffset * kOffset);
    ASSERT_LT(rhoLow, exact);
    ASSERT_GT(rhoHigh, exact);
    EXPECT_LT(xBound, 0.01) << "the meshes are too coarse for the test to mean much";

    double length = 0.0, worstX = 0.0, worstRadius = 0.0;
    std::vector<glm::dvec3> ends;
    for (const IntersectionSegment& segment : found.segments) {
        EXPECT_EQ(segment.meshes[0], 0u);
        EXPECT_EQ(segment.meshes[1], 1u);
        length += glm::length(segment.ends[1] - segment.ends[0]);
        for (const glm::dvec3& end : segment.ends) {
            EXPECT_LE(glm::length(end - right), kRadius + slack);
            EXPECT_GE(glm::length(end - right), kRadius - depth - slack);
            EXPECT_LE(glm::length(end - left), kRadius + slack);
            EXPECT_GE(glm::length(end - left), kRadius - depth - slack);
            const double rho = std::hypot(end.y, end.z);
            EXPECT_LE(std::abs(end.x), xBound);
            EXPECT_GE(rho, rhoLow);
            EXPECT_LE(rho, rhoHigh);
            worstX = std::max(worstX, std::abs(end.x));
            worstRadius = std::max(worstRadius, std::abs(rho - exact));
            ends.push_back(end);
        }
    }
    // One closed curve: every end meets another segment's end (bitwise where the curve leaves a triangle through an
    // edge: both triangles beside it compute the point alike; within rounding where it passes where edges of both
    // meshes cross, as on the spheres' common equator), so no crossing pair was missed.
    for (std::size_t i = 0; i < ends.size(); ++i) {
        double nearest = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < ends.size(); ++j)
            if (j / 2 != i / 2) nearest = std::min(nearest, glm::length(ends[j] - ends[i]));
        EXPECT_LE(nearest, 1e-12) << "a gap at end " << i;
    }
    // Its chords are as long as the circle within the faceting error.
    const double circle = 2.0 * glm::pi<double>() * exact;
    EXPECT_NEAR(length, circle, 0.01 * circle);
    RecordProperty("faceting_depth", std::to_string(depth));
    RecordProperty("worst_off_plane", std::to_string(worstX));
    RecordProperty("worst_off_radius", std::to_string(worstRadius));
    RecordProperty("length_over_circle", std::to_string(length / circle));
}

TEST(MeshIntersections, BoxesTouchingFaceToFaceGiveNone) {
    // Equal boxes face to face, and a smaller one touching the right box's face off its centre (so faces overlap in
    // part and edges lie across the other's faces).
    for (const auto& [centre, half] :
         {std::pair{glm::vec3(-0.5f, 0.0f, 0.0f), 0.5f}, std::pair{glm::vec3(-0.25f, 0.3f, -0.2f), 0.25f}}) {
        const std::vector<Mesh> meshes = {makeCube({0.5f, 0.0f, 0.0f}, 0.5f), makeCube(centre, half)};
        ASSERT_EQ(centre.x + half, 0.0f);
        const MeshIntersections found = search(meshes);
        EXPECT_TRUE(found.segments.empty());
        EXPECT_GT(found.report.pairsTested, 0u) << "the touching faces were never tested";
    }
}

TEST(MeshIntersections, ASphereRestingOnAPlaneAtAVertexGivesNone) {
    // The sphere's south pole is at z = 0.8f - 0.8f = 0 exactly, on the plane.
    Mesh sphere = makeUvSphere({0.1f, -0.2f, float(kRadius)}, float(kRadius), 32, 16);
    ASSERT_EQ(sphere.positions.back().z, 0.0f);
    const Mesh plane = soup(quad({-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}));
    const MeshIntersections found = search({sphere, plane});
    EXPECT_TRUE(found.segments.empty());
    EXPECT_GT(found.report.pairsTested, 0u);
    // Lowered by a little, it crosses: the test sees the contact.
    for (glm::vec3& position : sphere.positions) position.z -= 0.01f;
    EXPECT_FALSE(search({sphere, plane}).segments.empty());
}

TEST(MeshIntersections, TwoQuadsOfOneMeshCrossingGiveTheExactSegment) {
    // In the plane z = 0, and in the plane x = 0.25 spanning y in [-0.5, 0.5]: they cross on x = 0.25, z = 0,
    // y in [-0.5, 0.5], cut into pieces by the quads' diagonals.
    std::vector<std::array<glm::vec3, 3>> triangles = quad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
    for (const auto& t : quad({0.25f, -0.5f, -1}, {0.25f, 0.5f, -1}, {0.25f, 0.5f, 1}, {0.25f, -0.5f, 1}))
        triangles.push_back(t);
    const MeshIntersections found = search({soup(triangles)});
    ASSERT_FALSE(found.segments.empty());
    EXPECT_EQ(found.report.selfSegments, found.segments.size());
    double length = 0.0, low = 1.0, high = -1.0;
    for (const IntersectionSegment& segment : found.segments) {
        EXPECT_EQ(segment.meshes[0], 0u);
        EXPECT_EQ(segment.meshes[1], 0u);
        for (const glm::dvec3& end : segment.ends) {
            EXPECT_NEAR(end.x, 0.25, 1e-12);
            EXPECT_NEAR(end.z, 0.0, 1e-12);
            low = std::min(low, end.y);
            high = std::max(high, end.y);
        }
        length += glm::length(segment.ends[1] - segment.ends[0]);
    }
    EXPECT_NEAR(low, -0.5, 1e-12);
    EXPECT_NEAR(high, 0.5, 1e-12);
    EXPECT_NEAR(length, 1.0, 1e-12) << "pieces overlap or leave a gap";
}

TEST(MeshIntersections, TrianglesOfOneMeshSharingAVertexByPositionAreSkipped) {
    // They properly cross (each straddles the other's plane; their cuts overlap from the shared point to (1, 0, 0)),
    // but share the point (0, 0, 0), each with its own copy of it: as one mesh they are neighbours, as two meshes
    // they cross.
    const std::array<glm::vec3, 3> first = {glm::vec3(0, 0, 0), glm::vec3(2, 0, -1), glm::vec3(2, 0, 1)};
    const std::array<glm::vec3, 3> second = {glm::vec3(0, 0, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0)};
    const MeshIntersections one = search({soup({first, second})});
    EXPECT_TRUE(one.segments.empty());
    EXPECT_EQ(one.report.sharedVertexPairs, 1u);
    const MeshIntersections two = search({soup({first}), soup({second})});
    ASSERT_EQ(two.segments.size(), 1u);
    const auto& ends = two.segments[0].ends;
    const glm::dvec3 lowEnd = ends[0].x < ends[1].x ? ends[0] : ends[1];
    const glm::dvec3 highEnd = ends[0].x < ends[1].x ? ends[1] : ends[0];
    EXPECT_EQ(lowEnd, glm::dvec3(0.0));
    EXPECT_EQ(highEnd, glm::dvec3(1.0, 0.0, 0.0));
}

TEST(MeshIntersections, AClosedSphereAloneGivesNone) {
    const MeshIntersections found = search({makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 48, 24)});
    EXPECT_TRUE(found.segments.empty());
    EXPECT_GT(found.report.sharedVertexPairs, 0u);
    EXPECT_GT(found.report.indexNodes, 1u);
}

TEST(MeshIntersections, TouchingEdgesAndCoplanarTrianglesGiveNone) {
    using T = std::array<glm::dvec3, 3>;
    // Coplanar, overlapping.
    EXPECT_FALSE(triangleIntersectionSegment(T{glm::dvec3(0, 0, 0), {1, 0, 0}, {0, 1, 0}},
                                             T{glm::dvec3(0.2, 0.2, 0), {1, 0.2, 0}, {0.2, 1, 0}}));
    // An edge of one lying across the other's face (a T that does not go through).
    EXPECT_FALSE(triangleIntersectionSegment(T{glm::dvec3(-1, -1, 0), {1, -1, 0}, {0, 1, 0}},
                                             T{glm::dvec3(-0.5, 0, 0), {0.5, 0, 0}, {0, 0, 1}}));
    // Straddling each other's planes, but the cuts only meet at a point: edges touching crosswise.
    EXPECT_FALSE(triangleIntersectionSegment(T{glm::dvec3(0, 0, -1), {0, 0, 1}, {-1, 0, 0}},
                                             T{glm::dvec3(0, -1, 0), {0, 1, 0}, {1, 0, 0}}));
    // Through: the exact segment.
    const auto through = triangleIntersectionSegment(T{glm::dvec3(-1, -1, 0), {1, -1, 0}, {0, 1, 0}},
                                                     T{glm::dvec3(-0.5, 0, -1), {0.5, 0, -1}, {0, 0, 1}});
    ASSERT_TRUE(through);
    for (const glm::dvec3& end : *through) {
        EXPECT_EQ(end.y, 0.0);
        EXPECT_EQ(end.z, 0.0);
    }
    EXPECT_NEAR(std::abs((*through)[1].x - (*through)[0].x), 0.5, 1e-15);
}

TEST(MeshIntersections, WeldsMustMatchTheMeshes) {
    const std::vector<Mesh> meshes = {makeCube({0.0f, 0.0f, 0.0f}, 1.0f)};
    try {
        findMeshIntersections(meshes, std::vector<const WeldMap*>{});
        FAIL() << "no throw";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()).rfind("findMeshIntersections(): ", 0), 0u) << error.what();
    }
    const WeldMap empty;
    EXPECT_THROW(findMeshIntersections(meshes, std::vector<const WeldMap*>{&empty}), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
