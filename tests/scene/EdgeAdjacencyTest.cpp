// Edge adjacency (docs/lines.md): counts by kind on small meshes with known answers, normal angles by atan2,
// position welding across split normals and triangle soups, inconsistent orientation, degenerate faces, Lander 2000's
// Templist erratum, and the exact silhouette test with its tie rule.
#include "scene/mesh/EdgeAdjacency.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <utility>

namespace inkgraph::edge_adjacency_test {
namespace {

constexpr double kDegrees = glm::pi<double>() / 180.0;

/** The welded edges as sorted pairs of positions, so tests can name an edge by where it is. */
std::pair<glm::vec3, glm::vec3> endsOf(const Mesh& mesh, const MeshEdge& edge) {
    glm::vec3 a = mesh.positions[edge.vertices.x], b = mesh.positions[edge.vertices.y];
    if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
    return {a, b};
}

/** A regular tetrahedron, wound counter-clockwise from outside. */
Mesh tetrahedron() {
    Mesh mesh;
    mesh.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    return mesh;
}

TEST(EdgeAdjacency, TetrahedronHasSixManifoldEdgesAtTheRegularAngle) {
    const Mesh mesh = tetrahedron();
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
    const EdgeAdjacency adjacency = buildEdgeAdjacency(mesh.positions, mesh.triangles, 0.0);
    EXPECT_EQ(adjacency.counts.manifold, 6u);
    EXPECT_EQ(adjacency.counts.boundary, 0u);
    EXPECT_EQ(adjacency.counts.nonManifold, 0u);
    EXPECT_EQ(adjacency.counts.inconsistent, 0u);
    EXPECT_EQ(adjacency.counts.degenerateFaces, 0u);
    ASSERT_EQ(adjacency.edges.size(), 6u);
    // The interior dihedral angle is acos(1/3) = 70.5288 degrees; the outward normals meet at its supplement.
    const double interior = std::acos(1.0 / 3.0);
    EXPECT_NEAR(interior / kDegrees, 70.5288, 1e-4);
    for (const MeshEdge& edge : adjacency.edges) {
        EXPECT_EQ(edge.kind, EdgeKind::Manifold);
        EXPECT_EQ(edge.faceCount, 2u);
        EXPECT_NEAR(edge.normalAngle, glm::pi<double>() - interior, 1e-6);
        EXPECT_NEAR(180.0 - edge.normalAngle / kDegrees, 70.5288, 1e-4);
        // The two faces run the edge in opposite directions.
        const std::span<const EdgeFaceUse> faces = adjacency.facesOf(edge);
        EXPECT_NE(faces[0].againstKey, faces[1].againstKey);
    }
    for (const glm::vec3& normal : adjacency.faceNormals) EXPECT_NEAR(glm::length(normal), 1.0f, 1e-6f);
    // At an interior angle of 70.5 degrees every edge is a crease at 60 and none at 110 (normals at 109.47).
    EXPECT_EQ(selectCreaseEdges(adjacency, 60.0 * kDegrees).size(), 12u);
    EXPECT_EQ(selectCreaseEdges(adjacency, 110.0 * kDegrees).size(), 0u);
}

TEST(EdgeAdjacency, SingleTriangleAndOpenQuadAreBoundedByBorders) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const EdgeAdjacency triangle = buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 2}}, 0.0);
    EXPECT_EQ(triangle.counts.boundary, 3u);
    EXPECT_EQ(triangle.counts.manifold, 0u);
    EXPECT_EQ(selectBorderEdges(triangle), (std::vector<std::uint32_t>{0, 1, 1, 2, 2, 0}));
    EXPECT_EQ(triangle.faceNormals.at(0), glm::vec3(0, 0, 1));

    const EdgeAdjacency quad = buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}, 0.0);
    EXPECT_EQ(quad.counts.boundary, 4u);
    EXPECT_EQ(quad.counts.manifold, 1u);
    EXPECT_EQ(quad.counts.inconsistent, 0u);
    EXPECT_EQ(selectBorderEdges(quad).size(), 8u);
    // The diagonal is flat: no crease at any threshold, and no silhouette from either side.
    const MeshEdge& diagonal = quad.edges.at(2); // (2, 0): the first face's third edge
    EXPECT_EQ(diagonal.kind, EdgeKind::Manifold);
    EXPECT_EQ(diagonal.vertices, glm::uvec2(2, 0));
    EXPECT_EQ(diagonal.normalAngle, 0.0f);
    EXPECT_TRUE(selectCreaseEdges(quad, 0.0).empty());
    EXPECT_FALSE(isSilhouetteEdge(quad, diagonal, {0.3, 0.2, 2.0}));
    EXPECT_FALSE(isSilhouetteEdge(quad, diagonal, {0.3, 0.2, -2.0}));
    EXPECT_TRUE(selectSilhouetteEdges(quad, {5.0, -3.0, 0.5}).empty()); // boundary edges are never silhouettes
}

TEST(EdgeAdjacency, ThreeFacesOnOneEdgeMakeItNonManifold) {
    // A fin: three triangles hinged on the edge (0, 1), two of them running it one way and one the other.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, triangles, 0.0);
    EXPECT_EQ(adjacency.counts.nonManifold, 1u);
    EXPECT_EQ(adjacency.counts.boundary, 6u);
    EXPECT_EQ(adjacency.counts.manifold, 0u);
    const MeshEdge& hinge = adjacency.edges.at(0);
    EXPECT_EQ(hinge.kind, EdgeKind::NonManifold);
    ASSERT_EQ(hinge.faceCount, 3u);
    const std::span<const EdgeFaceUse> faces = adjacency.facesOf(hinge);
    EXPECT_EQ(faces[0].face, 0u);
    EXPECT_FALSE(faces[0].againstKey);
    EXPECT_EQ(faces[1].face, 1u);
    EXPECT_TRUE(faces[1].againstKey);
    EXPECT_EQ(faces[2].face, 2u);
    EXPECT_FALSE(faces[2].againstKey);
    EXPECT_EQ(hinge.normalAngle, 0.0f); // defined for manifold edges only
    // Borders take the rim and the hinge; creases and silhouettes never take a non-manifold edge.
    EXPECT_EQ(selectBorderEdges(adjacency).size(), 14u);
    EXPECT_TRUE(selectCreaseEdges(adjacency, 0.0).empty());
    EXPECT_FALSE(isSilhouetteEdge(adjacency, hinge, {0.5, 3.0, 0.2}));
}

TEST(EdgeAdjacency, CubeWithSplitNormalsKeysEdgesOnWeldedPositions) {
    const Mesh cube = makeCube({0.0f, 0.0f, 0.0f}, 1.0f);
    ASSERT_EQ(cube.positions.size(), 24u);
    // Keyed on the mesh's own ids, each face would be an island of 4 boundary edges and 1 diagonal.
    const double weldDistance = LoadOptions{}.weldTolerance * computeBoundingBox(cube.positions).diagonal();
    const EdgeAdjacency adjacency = buildEdgeAdjacency(cube.positions, cube.triangles, weldDistance);
    EXPECT_EQ(adjacency.counts.manifold, 18u);
    EXPECT_EQ(adjacency.counts.boundary, 0u);
    EXPECT_EQ(adjacency.counts.nonManifold, 0u);
    EXPECT_EQ(adjacency.counts.inconsistent, 0u);
    int right = 0, flat = 0;
    for (const MeshEdge& edge : adjacency.edges) {
        const auto [a, b] = endsOf(cube, edge);
        const int differingAxes = (a.x != b.x) + (a.y != b.y) + (a.z != b.z);
        if (differingAxes == 1) {
            EXPECT_NEAR(edge.normalAngle, glm::half_pi<double>(), 1e-6); // a cube edge
            ++right;
        } else {
            EXPECT_EQ(differingAxes, 2); // a face diagonal
            EXPECT_EQ(edge.normalAngle, 0.0f);
            ++flat;
        }
    }
    EXPECT_EQ(right, 12);
    EXPECT_EQ(flat, 6);
    EXPECT_EQ(selectCreaseEdges(adjacency, 30.0 * kDegrees).size(), 24u);
    EXPECT_EQ(selectCreaseEdges(adjacency, 0.0).size(), 24u); // the diagonals' 0 is exact, so never above 0
    EXPECT_EQ(selectCreaseEdges(adjacency, 89.9 * kDegrees).size(), 24u);
    EXPECT_EQ(selectCreaseEdges(adjacency, 90.1 * kDegrees).size(), 0u);
    EXPECT_TRUE(selectBorderEdges(adjacency).empty());
}

TEST(EdgeAdjacency, FlippedTriangleIsFlaggedAndItsAngleCorrected) {
    // The open quad with its second triangle wound the other way: both faces run the diagonal from 2 to 0.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 2}, {0, 3, 2}}, 0.0);
    EXPECT_EQ(adjacency.counts.inconsistent, 1u);
    EXPECT_EQ(adjacency.counts.manifold, 1u);
    const MeshEdge& diagonal = adjacency.edges.at(2);
    EXPECT_TRUE(diagonal.inconsistentOrientation);
    EXPECT_EQ(adjacency.faceNormals.at(1), glm::vec3(0, 0, -1));
    // Raw normals are opposite (180 degrees apart); re-oriented, the surface is flat.
    EXPECT_EQ(diagonal.normalAngle, 0.0f);
    EXPECT_TRUE(selectCreaseEdges(adjacency, 30.0 * kDegrees).empty());
    // s1 x s2 < 0 everywhere on the raw normals; re-oriented, a flat sheet has no silhouette from either side.
    EXPECT_FALSE(isSilhouetteEdge(adjacency, diagonal, {0.2, 0.7, 3.0}));
    EXPECT_FALSE(isSilhouetteEdge(adjacency, diagonal, {0.2, 0.7, -3.0}));
    EXPECT_TRUE(selectSilhouetteEdges(adjacency, {0.2, 0.7, 3.0}).empty());

    // Folded along the diagonal (vertex 3 lifted), the flipped pair gives the same silhouettes as the consistent one.
    const std::vector<glm::vec3> folded = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 1}};
    const EdgeAdjacency consistent = buildEdgeAdjacency(folded, std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}, 0.0);
    const EdgeAdjacency flipped = buildEdgeAdjacency(folded, std::vector<glm::uvec3>{{0, 1, 2}, {0, 3, 2}}, 0.0);
    EXPECT_NEAR(consistent.edges.at(2).normalAngle, flipped.edges.at(2).normalAngle, 1e-7);
    EXPECT_NEAR(consistent.edges.at(2).normalAngle / kDegrees, 54.7356, 1e-3); // normals (0,0,1) and (1,-1,1)/sqrt 3
    std::mt19937 random(11);
    std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
    int silhouettes = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const glm::dvec3 eye(coordinate(random), coordinate(random), coordinate(random));
        const bool expected = isSilhouetteEdge(consistent, consistent.edges.at(2), eye);
        EXPECT_EQ(isSilhouetteEdge(flipped, flipped.edges.at(2), eye), expected)
            << "eye " << eye.x << ' ' << eye.y << ' ' << eye.z;
        silhouettes += expected;
    }
    EXPECT_GT(silhouettes, 20); // both answers occur, so the comparison means something
    EXPECT_LT(silhouettes, 180);
}

TEST(EdgeAdjacency, EveryEdgeOfAFaceIsAddedAfterItsFirstMatches) {
    // An erratum of the comic-renderer write-up after Lander 2000: its Templist set `found` once per triangle, so a
    // triangle whose first edge matched never added its other two. In this fan every triangle after the first starts
    // with the edge it shares with the one before, and its second edge is what the next triangle shares.
    const std::vector<glm::vec3> fan = {{-1, -0.5f, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 1, 0}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {2, 1, 3}, {3, 1, 4}, {4, 1, 5}};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(fan, triangles, 0.0);
    EXPECT_EQ(adjacency.edges.size(), 9u);
    EXPECT_EQ(adjacency.counts.manifold, 3u); // 1-2, 1-3, 1-4
    EXPECT_EQ(adjacency.counts.boundary, 6u); // 0-1, 2-0, 3-2, 4-3, 5-4, 1-5
    EXPECT_EQ(adjacency.counts.inconsistent, 0u);
    std::set<std::pair<std::uint32_t, std::uint32_t>> manifold;
    for (const MeshEdge& edge : adjacency.edges)
        if (edge.kind == EdgeKind::Manifold)
            manifold.emplace(std::min(edge.vertices.x, edge.vertices.y), std::max(edge.vertices.x, edge.vertices.y));
    EXPECT_EQ(manifold, (std::set<std::pair<std::uint32_t, std::uint32_t>>{{1, 2}, {1, 3}, {1, 4}}));
}

TEST(EdgeAdjacency, TriangleSoupWeldsIntoAClosedCube) {
    // STL stores three private corners per face, and files written with rounding give the copies of one corner
    // slightly different coordinates: here the k-th copy is moved 4k float steps along x and y (at most 1.9e-5,
    // 5e-7 of the size; the weld distance is 1e-6 of the diagonal, 3.5e-5).
    std::vector<glm::vec3> soup = test::cubeTriangleSoup(10.0, {3.0, -2.0, 1.0});
    std::map<std::tuple<float, float, float>, int> copiesSoFar;
    for (glm::vec3& p : soup) {
        const int copy = copiesSoFar[{p.x, p.y, p.z}]++;
        for (int step = 0; step < 4 * copy; ++step) {
            p.x = std::nextafter(p.x, 100.0f);
            p.y = std::nextafter(p.y, 100.0f);
        }
    }
    std::vector<glm::uvec3> triangles;
    for (std::uint32_t i = 0; i < soup.size(); i += 3) triangles.emplace_back(i, i + 1, i + 2);
    const double diagonal = computeBoundingBox(soup).diagonal();

    const EdgeAdjacency welded = buildEdgeAdjacency(soup, triangles, LoadOptions{}.weldTolerance * diagonal);
    EXPECT_EQ(welded.counts.manifold, 18u);
    EXPECT_EQ(welded.counts.boundary, 0u);
    EXPECT_EQ(welded.counts.inconsistent, 0u);
    EXPECT_EQ(selectCreaseEdges(welded, 30.0 * kDegrees).size(), 24u);

    // Without welding every edge is a border (the reason to weld first).
    const EdgeAdjacency unwelded = buildEdgeAdjacency(soup, triangles, 0.0);
    EXPECT_EQ(unwelded.counts.boundary, 36u);
    EXPECT_EQ(unwelded.counts.manifold, 0u);
}

TEST(EdgeAdjacency, DegenerateFacesAreSkipped) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}, {1, 0, 1e-12f}};
    // A repeated index, three collinear points, two corners that weld together, and one good face.
    const std::vector<glm::uvec3> triangles = {{0, 1, 1}, {0, 1, 3}, {1, 4, 2}, {0, 1, 2}};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, triangles, 1e-9);
    EXPECT_EQ(adjacency.counts.degenerateFaces, 3u);
    EXPECT_EQ(adjacency.counts.boundary, 3u);
    EXPECT_EQ(adjacency.edges.size(), 3u);
    for (std::uint32_t face = 0; face < 3; ++face) {
        EXPECT_EQ(adjacency.faceNormals[face], glm::vec3(0.0f));
        EXPECT_EQ(eyeSideOfFace(adjacency, face, {3.0, 2.0, 1.0}), 0.0);
    }
    EXPECT_EQ(adjacency.faceNormals[3], glm::vec3(0, 0, 1));
}

TEST(EdgeAdjacency, EveryFaceDegenerateOnceWeldedGivesNoEdges) {
    // A far vertex makes the model large, so the weld distance (a share of its size) merges the small triangle's
    // corners: no face is left, and no edge entry to sort (the sort then did arithmetic on a null pointer, which the
    // sanitized build reports; fuzz_obj and fuzz_ply found it).
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e7f, 0, 0}};
    const std::vector<glm::uvec3> triangles = {{0, 1, 2}, {2, 1, 0}};
    const EdgeAdjacency adjacency = buildEdgeAdjacency(positions, triangles, 10.0);
    EXPECT_EQ(adjacency.counts.degenerateFaces, 2u);
    EXPECT_TRUE(adjacency.edges.empty());
    const EdgeAdjacency none = buildEdgeAdjacency(positions, std::vector<glm::uvec3>{}, 1e-6);
    EXPECT_TRUE(none.edges.empty());
}

TEST(EdgeAdjacency, BadInputThrowsNamingTheFunction) {
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    try {
        buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 3}}, 0.0);
        FAIL() << "an index past the positions must throw";
    } catch (const std::out_of_range& error) {
        EXPECT_NE(std::string(error.what()).find("buildEdgeAdjacency(): triangle 0"), std::string::npos);
    }
    EXPECT_THROW(buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 2}}, -1.0), std::invalid_argument);
    EXPECT_THROW(buildEdgeAdjacency(positions, std::vector<glm::uvec3>{{0, 1, 2}}, std::nan("")),
                 std::invalid_argument);
}

TEST(EdgeAdjacency, SilhouetteTieCountsTheEdgeOnFaceAsBack) {
    // The eye in the plane of the cube's top face (z = 1), in front of its +x face: the top is seen edge-on (s = 0).
    // Counted as back, the silhouette is the +x face's outline, 4 edges, with one line where front meets edge-on.
    // The write-up's "include ties" (s1 s2 <= 0) would add the top's three other edges, and its diagonal.
    const Mesh cube = makeCube({0.0f, 0.0f, 0.0f}, 1.0f);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(cube.positions, cube.triangles, 1e-6);
    const glm::dvec3 eye(5.0, 0.3, 1.0);
    const std::vector<std::uint32_t> silhouette = selectSilhouetteEdges(adjacency, eye);
    ASSERT_EQ(silhouette.size(), 8u);
    for (const std::uint32_t vertex : silhouette) EXPECT_EQ(cube.positions[vertex].x, 1.0f);
    int tiedFaces = 0, withTiesIncluded = 0;
    for (std::uint32_t face = 0; face < cube.triangles.size(); ++face)
        tiedFaces += eyeSideOfFace(adjacency, face, eye) == 0.0;
    EXPECT_EQ(tiedFaces, 2);
    for (const MeshEdge& edge : adjacency.edges) {
        const std::span<const EdgeFaceUse> faces = adjacency.facesOf(edge);
        withTiesIncluded +=
            eyeSideOfFace(adjacency, faces[0].face, eye) * eyeSideOfFace(adjacency, faces[1].face, eye) <= 0.0;
    }
    EXPECT_EQ(withTiesIncluded, 8); // the 4 + the top's 3 other edges + its diagonal
}

TEST(EdgeAdjacency, SilhouetteIsExactUnderPerspective) {
    // A sphere seen from 3 radii: the exact test picks edges where the surface turns away from the eye itself,
    // n . (E - x) ~ 0, on the small circle of tangency; a view-direction test picks the great circle n . d = 0.
    const Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 128, 64);
    const EdgeAdjacency adjacency = buildEdgeAdjacency(sphere.positions, sphere.triangles, 1e-7);
    const glm::dvec3 eye(0.3, -0.4, 3.0);
    const std::vector<std::uint32_t> silhouette = selectSilhouetteEdges(adjacency, eye);
    ASSERT_GE(silhouette.size(), 2u * 128u);
    double worstCosine = 0.0;
    for (std::size_t i = 0; i < silhouette.size(); i += 2) {
        const glm::dvec3 middle =
            (glm::dvec3(sphere.positions[silhouette[i]]) + glm::dvec3(sphere.positions[silhouette[i + 1]])) / 2.0;
        worstCosine = std::max(worstCosine, std::abs(glm::dot(glm::normalize(middle), glm::normalize(eye - middle))));
    }
    // Edges span about 2 pi / 128 = 0.049 rad; an edge's middle lies within that of the tangency circle.
    EXPECT_LT(worstCosine, 0.05);

    // The write-up's orthographic test, with the view direction d toward the centre: s = -n . d. Its edges lie on the
    // great circle perpendicular to d, where the eye sees the surface at cos = 1 / sqrt(10) = 0.316, not grazing.
    const glm::dvec3 towardEye = glm::normalize(eye);
    double bestOrthographicCosine = 1.0;
    int orthographicEdges = 0;
    for (const MeshEdge& edge : adjacency.edges) {
        const std::span<const EdgeFaceUse> faces = adjacency.facesOf(edge);
        const bool firstFront = glm::dot(glm::dvec3(adjacency.faceNormals[faces[0].face]), towardEye) > 0.0;
        const bool secondFront = glm::dot(glm::dvec3(adjacency.faceNormals[faces[1].face]), towardEye) > 0.0;
        if (firstFront == secondFront) continue;
        ++orthographicEdges;
        const glm::dvec3 middle =
            (glm::dvec3(sphere.positions[edge.vertices.x]) + glm::dvec3(sphere.positions[edge.vertices.y])) / 2.0;
        bestOrthographicCosine =
            std::min(bestOrthographicCosine, std::abs(glm::dot(glm::normalize(middle), glm::normalize(eye - middle))));
    }
    EXPECT_GE(orthographicEdges, 128);
    EXPECT_GT(bestOrthographicCosine, 0.25);
    RecordProperty("best_cosine_of_orthographic_edges", std::to_string(bestOrthographicCosine));
    RecordProperty("worst_cosine_at_silhouette_edge_middles", std::to_string(worstCosine));
}

} // namespace
} // namespace inkgraph::edge_adjacency_test
