// Winnemöller & Bangay's CPU face orientation against the exact per-face test: no holes for any method, rule or view
// vector at any distance (with the corrected cut-off), holes with the paper's cut-off, front shares against the
// analytic sphere, and the per-vertex (s, t) against the textbook form of the specular term.
#include "scene/mesh/FaceOrientation.h"

#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

struct MethodRule {
    FaceOrientationMethod method;
    int frontRule;
};

/** Every CPU method with every rule that matters (during-triangles ignores the rule). */
const std::vector<MethodRule>& allMethodsAndRules() {
    static const std::vector<MethodRule> list = {
        {FaceOrientationMethod::DuringTriangles, 3}, {FaceOrientationMethod::DuringVertices, 1},
        {FaceOrientationMethod::DuringVertices, 2},  {FaceOrientationMethod::DuringVertices, 3},
        {FaceOrientationMethod::AfterVertices, 1},   {FaceOrientationMethod::AfterVertices, 2},
        {FaceOrientationMethod::AfterVertices, 3}};
    return list;
}

OrientationRequest makeRequest(MethodRule methodRule, const ViewVectorChoice& view, const glm::dvec3& eye) {
    OrientationRequest request;
    request.method = methodRule.method;
    request.frontRule = methodRule.frontRule;
    request.view = view;
    request.eye = eye;
    request.towardLight = glm::normalize(glm::dvec3(0.3, 0.4, 0.85));
    return request;
}

std::string describe(MethodRule methodRule, const ViewVectorChoice& view) {
    return faceOrientationMethodName(methodRule.method) + " rule " + std::to_string(methodRule.frontRule) + ", " +
           (view.constant   ? "constant"
            : view.fellBack ? "exact (fell back)"
                            : "exact");
}

/** The cube [-1,1]^3 as 12 triangles with the symmetric corner normals (+-1,+-1,+-1)/sqrt(3). */
Mesh makeCube() {
    Mesh mesh;
    mesh.name = "cube";
    for (const glm::vec3& corner : test::cubeCorners()) {
        mesh.positions.push_back(corner);
        mesh.normals.push_back(glm::normalize(corner));
    }
    for (const glm::uvec4& quad : test::cubeQuads()) {
        const glm::uvec4 q = quad - glm::uvec4(1);
        mesh.triangles.emplace_back(q.x, q.y, q.z);
        mesh.triangles.emplace_back(q.x, q.z, q.w);
    }
    return mesh;
}

bool isExactFrontInTest(const Mesh& mesh, const glm::uvec3& triangle, const glm::dvec3& eye) {
    return glm::dot(test::triangleCross(mesh, triangle), glm::dvec3(mesh.positions[triangle.x]) - eye) < 0.0;
}

// ---- chooseViewVector --------------------------------------------------------------------------------------------

TEST(ChooseViewVector, ExactRequestIsNeverConstant) {
    const ViewVectorChoice choice = chooseViewVector(ViewVectorMode::Exact, {0, 0, 100}, {0, 0, 0}, 1.0);
    EXPECT_FALSE(choice.constant);
    EXPECT_FALSE(choice.fellBack);
    EXPECT_TRUE(choice.reason.empty());
}

TEST(ChooseViewVector, EyeInsideTheSphereFallsBack) {
    const ViewVectorChoice choice = chooseViewVector(ViewVectorMode::Constant, {0.5, 0, 0}, {0, 0, 0}, 1.0);
    EXPECT_FALSE(choice.constant);
    EXPECT_TRUE(choice.fellBack);
    EXPECT_EQ(choice.reason, "eye inside the bounding sphere");
    // On the sphere, and within the 1e-3 margin outside it, counts as inside too.
    EXPECT_TRUE(chooseViewVector(ViewVectorMode::Constant, {1.0, 0, 0}, {0, 0, 0}, 1.0).fellBack);
    EXPECT_TRUE(chooseViewVector(ViewVectorMode::Constant, {1.0009, 0, 0}, {0, 0, 0}, 1.0).fellBack);
}

TEST(ChooseViewVector, EyeAtTheCentreGivesNoNaN) {
    const glm::dvec3 center(1.0, -2.0, 3.0);
    for (const double radius : {0.0, 1.0}) {
        const ViewVectorChoice choice = chooseViewVector(ViewVectorMode::Constant, center, center, radius);
        EXPECT_FALSE(choice.constant);
        EXPECT_TRUE(choice.fellBack);
        EXPECT_TRUE(std::isfinite(choice.sinAlpha));
        EXPECT_TRUE(std::isfinite(choice.constantView.x) && std::isfinite(choice.constantView.y) &&
                    std::isfinite(choice.constantView.z));
    }
}

TEST(ChooseViewVector, EyeWithinTwoRadiiFallsBackAndSaysWhy) {
    const ViewVectorChoice choice = chooseViewVector(ViewVectorMode::Constant, {0, 0, 1.59}, {0, 0, 0}, 1.0);
    EXPECT_FALSE(choice.constant);
    EXPECT_TRUE(choice.fellBack);
    EXPECT_EQ(choice.reason, "eye within 2 radii of the bounding-sphere centre (sin alpha = 0.63 > 0.5)");
    // Exactly 2 radii is sin(alpha) = 0.5, still accepted.
    EXPECT_TRUE(chooseViewVector(ViewVectorMode::Constant, {0, 0, 2.0}, {0, 0, 0}, 1.0).constant);
}

TEST(ChooseViewVector, FarEyeGivesRadiusOverDistance) {
    const glm::dvec3 center(1.0, 2.0, 3.0);
    const double radius = 2.0;
    const glm::dvec3 eye = center + glm::dvec3(3.0, -4.0, 12.0); // 13 away
    const ViewVectorChoice choice = chooseViewVector(ViewVectorMode::Constant, eye, center, radius);
    ASSERT_TRUE(choice.constant);
    EXPECT_FALSE(choice.fellBack);
    EXPECT_EQ(choice.sinAlpha, radius / glm::length(center - eye));
    EXPECT_NEAR(choice.sinAlpha, 2.0 / 13.0, 1e-15);
    EXPECT_NEAR(choice.constantView.x, -3.0 / 13.0, 1e-15);
    EXPECT_NEAR(choice.constantView.y, 4.0 / 13.0, 1e-15);
    EXPECT_NEAR(choice.constantView.z, -12.0 / 13.0, 1e-15);
}

TEST(ChooseViewVector, RejectsBadInput) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(chooseViewVector(ViewVectorMode::Constant, {0, 0, 5}, {0, 0, 0}, -1.0), std::invalid_argument);
    EXPECT_THROW(chooseViewVector(ViewVectorMode::Constant, {0, 0, 5}, {0, 0, 0}, nan), std::invalid_argument);
    EXPECT_THROW(chooseViewVector(ViewVectorMode::Constant, {nan, 0, 5}, {0, 0, 0}, 1.0), std::invalid_argument);
}

// ---- derived data and exact counts ------------------------------------------------------------------------------

TEST(DeriveOrientationData, CubeFaceNormalsBetaMaxAndAdjacency) {
    const Mesh cube = makeCube();
    const OrientationMeshData data = deriveOrientationData(cube, true);
    ASSERT_EQ(data.faceNormals.size(), 12u);
    for (std::size_t i = 0; i < cube.triangles.size(); ++i) {
        const glm::dvec3 expected = glm::normalize(test::triangleCross(cube, cube.triangles[i]));
        EXPECT_NEAR(glm::length(glm::dvec3(data.faceNormals[i]) - expected), 0.0, 1e-7);
    }
    // A corner normal (1,1,1)/sqrt(3) against an axis: acos(1/sqrt(3)) = atan2(sqrt(2), 1) = 54.7356 degrees.
    EXPECT_NEAR(data.betaMaxRadians, std::atan2(std::sqrt(2.0), 1.0), 1e-7);

    ASSERT_EQ(data.vertexTriangleStart.size(), cube.positions.size() + 1);
    ASSERT_EQ(data.vertexTriangles.size(), 36u);
    EXPECT_EQ(data.vertexTriangleStart.front(), 0u);
    EXPECT_EQ(data.vertexTriangleStart.back(), 36u);
    for (std::uint32_t v = 0; v < cube.positions.size(); ++v) {
        for (std::uint32_t k = data.vertexTriangleStart[v]; k < data.vertexTriangleStart[v + 1]; ++k) {
            const glm::uvec3& triangle = cube.triangles.at(data.vertexTriangles[k]);
            EXPECT_TRUE(triangle.x == v || triangle.y == v || triangle.z == v);
        }
    }
    EXPECT_TRUE(deriveOrientationData(cube, false).vertexTriangles.empty());
}

TEST(DeriveOrientationData, SphereBetaMaxIsBelowOneRingStep) {
    const int rings = 32;
    const OrientationMeshData data = deriveOrientationData(makeUvSphere({0, 0, 0}, 1.0f, 64, rings), false);
    EXPECT_GT(data.betaMaxRadians, 0.0);
    EXPECT_LT(data.betaMaxRadians, glm::pi<double>() / rings);
}

TEST(DeriveOrientationData, RejectsMissingNormals) {
    Mesh cube = makeCube();
    cube.normals.pop_back();
    try {
        deriveOrientationData(cube, false);
        FAIL() << "no exception";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()).rfind("deriveOrientationData(): mesh 'cube'", 0), 0u) << error.what();
    }
}

TEST(CountExactFront, CubeAndTriangleByHand) {
    const Mesh cube = makeCube();
    EXPECT_EQ(countExactFrontTriangles(cube, {0, 0, 5}), 2u);   // the +z face
    EXPECT_EQ(countExactFrontTriangles(cube, {5, 5, 5}), 6u);   // three faces
    EXPECT_EQ(countExactFrontTriangles(cube, {5, 0, 0.5}), 2u); // +x only: z = 0.5 is inside the z slab
    EXPECT_EQ(countExactFrontTriangles(cube, {0, 0, 0}), 0u);   // inside a closed mesh nothing faces the eye
    EXPECT_EQ(countExactFrontTriangles(cube, {0, 0, 1}), 0u);   // on the +z plane: grazing is not front
    EXPECT_EQ(countExactFrontVertices(cube, {0, 0, 5}), 4u);
    EXPECT_EQ(countExactFrontVertices(cube, {5, 5, 5}), 7u); // all but the far corner
    EXPECT_EQ(countExactFrontVertices(cube, {0, 0, 0}), 0u);

    Mesh triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}; // counter-clockwise seen from +z
    triangle.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    triangle.triangles = {{0, 1, 2}};
    EXPECT_EQ(countExactFrontTriangles(triangle, {0.2, 0.2, 1}), 1u);
    EXPECT_EQ(countExactFrontTriangles(triangle, {5, -3, 0.001}), 1u);
    EXPECT_EQ(countExactFrontTriangles(triangle, {0.2, 0.2, -1}), 0u);
}

TEST(CountMissedTriangles, MergeWalkOverMeshOrder) {
    const Mesh cube = makeCube();
    const glm::dvec3 eye(5, 5, 5);
    std::vector<glm::uvec3> exactFront;
    for (const glm::uvec3& triangle : cube.triangles) {
        if (isExactFrontInTest(cube, triangle, eye)) exactFront.push_back(triangle);
    }
    ASSERT_EQ(exactFront.size(), 6u);
    EXPECT_EQ(countMissedTriangles(cube, eye, exactFront), 0u);
    EXPECT_EQ(countMissedTriangles(cube, eye, cube.triangles), 0u);
    std::vector<glm::uvec3> oneShort(exactFront.begin() + 1, exactFront.end());
    EXPECT_EQ(countMissedTriangles(cube, eye, oneShort), 1u);
    EXPECT_EQ(countMissedTriangles(cube, eye, {}), 6u);
    std::vector<glm::uvec3> reversed(exactFront.rbegin(), exactFront.rend());
    EXPECT_THROW(countMissedTriangles(cube, eye, reversed), std::invalid_argument);
}

// ---- holes -------------------------------------------------------------------------------------------------------

/** Every method, rule and view mode from eyes at 0.2 to 50 radii in five directions: no exact front triangle may be
 *  missed. Also checks that both view modes were really exercised (constant accepted and fallen back). */
void expectNoHoles(const Scene& scene, const std::string& label) {
    const BoundingSphere sphere = computeBoundingSphere(scene);
    std::vector<OrientationMeshData> data;
    for (const Mesh& mesh : scene.meshes) data.push_back(deriveOrientationData(mesh, true));

    const std::vector<double> distances = {0.2, 0.5, 0.9, 1.0, 1.0005, 1.1, 1.5, 1.99, 2.0, 2.5, 3.0, 5.0, 10.0, 50.0};
    const std::vector<glm::dvec3> directions = {{0, 0, 1},
                                                {1, 0, 0},
                                                glm::normalize(glm::dvec3(1, 2, 3)),
                                                glm::normalize(glm::dvec3(-0.3, -1, 0.2)),
                                                glm::normalize(glm::dvec3(0.7, -0.2, -0.9))};
    int constantRuns = 0;
    int fallBackRuns = 0;
    for (const double distance : distances) {
        for (const glm::dvec3& direction : directions) {
            const glm::dvec3 eye = sphere.center + distance * sphere.radius * direction;
            for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
                const ViewVectorChoice view = chooseViewVector(mode, eye, sphere.center, sphere.radius);
                for (const MethodRule& methodRule : allMethodsAndRules()) {
                    std::size_t missed = 0;
                    std::size_t exactFront = 0;
                    std::size_t front = 0;
                    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
                        const MeshOrientation result =
                            orientMesh(scene.meshes[m], data[m], makeRequest(methodRule, view, eye));
                        missed += result.missedTriangles;
                        exactFront += countExactFrontTriangles(scene.meshes[m], eye);
                        front += result.frontTriangles.size();
                    }
                    EXPECT_EQ(missed, 0u) << label << " at " << distance << " radii, direction (" << direction.x << ", "
                                          << direction.y << ", " << direction.z << "), " << describe(methodRule, view);
                    EXPECT_GE(front, exactFront)
                        << label << " at " << distance << " radii, " << describe(methodRule, view);
                    constantRuns += view.constant ? 1 : 0;
                    fallBackRuns += view.fellBack ? 1 : 0;
                }
            }
        }
    }
    EXPECT_GT(constantRuns, 0) << label;
    EXPECT_GT(fallBackRuns, 0) << label;
}

TEST(FaceOrientationHoles, NoneOnASphere) { expectNoHoles(makeScene(makeUvSphere({1, 2, 3}, 2.0f, 96, 48)), "sphere"); }

TEST(FaceOrientationHoles, NoneOnATorus) { expectNoHoles(makeScene(makeTorus(3.0f, 1.0f, 96, 48)), "torus"); }

TEST(FaceOrientationHoles, NoneOnTheBunny) {
    expectNoHoles(loadScene(test::sourcePath("models/bunny_c3d_70k.obj")), "bunny");
}

TEST(FaceOrientationHoles, NoneOnTheFandisk) {
    // Sharp creases: betaMax is large, the vertex cut-off wide.
    expectNoHoles(loadScene(test::sourcePath("models/fandisk_c3d.obj")), "fandisk");
}

TEST(FaceOrientationHoles, PaperCutoffOpensHolesWithRuleOne) {
    // Negative control: the paper's -sin(alpha) without betaMax. On a sphere the vertex test then matches the exact
    // visible cap, but chord faces straddling its rim are front with a vertex outside it, so rule 1 drops them.
    const Scene scene = makeScene(makeUvSphere({0, 0, 0}, 1.0f, 96, 48));
    const Mesh& mesh = scene.meshes[0];
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 direction = glm::normalize(glm::dvec3(1, 2, 3));
    for (const double distance : {1.5, 2.0, 3.0}) {
        const glm::dvec3 eye = distance * direction;
        // Built by hand at 1.5 radii, where chooseViewVector() would fall back.
        ViewVectorChoice view;
        view.constant = true;
        view.constantView = -direction;
        view.sinAlpha = 1.0 / distance;
        for (const FaceOrientationMethod method :
             {FaceOrientationMethod::AfterVertices, FaceOrientationMethod::DuringVertices}) {
            OrientationRequest request = makeRequest({method, 1}, view, eye);
            request.paperCutoff = true;
            const MeshOrientation paper = orientMesh(mesh, data, request);
            EXPECT_GT(paper.missedTriangles, 0u) << distance << " radii, " << faceOrientationMethodName(method);
            EXPECT_NEAR(paper.cutoff, -1.0 / distance, 1e-15);
            request.paperCutoff = false;
            EXPECT_EQ(orientMesh(mesh, data, request).missedTriangles, 0u) << distance << " radii, corrected";
        }
    }
}

// ---- front shares ------------------------------------------------------------------------------------------------

TEST(FaceOrientationShares, SphereMatchesTheVisibleCap) {
    const int rings = 128;
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 2 * rings, rings);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 direction(1.0, 0.0, 0.0);
    for (const double distance : {2.0, 5.0, 50.0}) {
        const glm::dvec3 eye = distance * direction;
        // Visible fraction of a sphere's area from distance d: the cap n.e > r/d, area (1 - r/d)/2.
        double frontArea = 0.0;
        double totalArea = 0.0;
        std::size_t exactCount = 0;
        for (const glm::uvec3& triangle : mesh.triangles) {
            const double area = glm::length(test::triangleCross(mesh, triangle)) / 2.0;
            totalArea += area;
            if (isExactFrontInTest(mesh, triangle, eye)) {
                frontArea += area;
                ++exactCount;
            }
        }
        EXPECT_EQ(countExactFrontTriangles(mesh, eye), exactCount);
        EXPECT_NEAR(frontArea / totalArea, (1.0 - 1.0 / distance) / 2.0, 0.003) << distance << " radii";

        // Seen along its axis, a UV sphere's rings are equal bands in polar angle with equal triangle counts, so the
        // triangle share is the cap's polar angle over pi, within one ring.
        const double axisShare = double(countExactFrontTriangles(mesh, {0.0, 0.0, distance})) / mesh.triangleCount();
        EXPECT_NEAR(axisShare, std::acos(1.0 / distance) / glm::pi<double>(), 1.0 / rings) << distance << " radii";
        if (distance == 50.0) {
            EXPECT_NEAR(axisShare, 0.5, 0.01);
        }

        for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
            const ViewVectorChoice view = chooseViewVector(mode, eye, {0, 0, 0}, 1.0);
            ASSERT_EQ(view.constant, mode == ViewVectorMode::Constant);
            std::size_t previousRuleCount[2] = {0, 0};
            for (const MethodRule& methodRule : allMethodsAndRules()) {
                const MeshOrientation result = orientMesh(mesh, data, makeRequest(methodRule, view, eye));
                const std::string context = std::to_string(distance) + " radii, " + describe(methodRule, view);
                EXPECT_GE(result.frontTriangles.size(), exactCount) << context;
                // Every triangle is drawn by the fill, the outline, or both.
                EXPECT_GE(result.frontTriangles.size() + result.backTriangles.size(), mesh.triangleCount()) << context;
                if (methodRule.method == FaceOrientationMethod::DuringTriangles) {
                    if (!view.constant) {
                        // Exact face test: the exact set, and no intermediates.
                        EXPECT_EQ(result.frontTriangles.size(), exactCount) << context;
                        EXPECT_EQ(result.frontTriangles.size() + result.backTriangles.size(), mesh.triangleCount());
                    }
                    continue;
                }
                // Rules 1 <= 2 <= 3, per vertex method.
                std::size_t& previous =
                    previousRuleCount[methodRule.method == FaceOrientationMethod::DuringVertices ? 0 : 1];
                EXPECT_GE(result.frontTriangles.size(), previous) << context;
                previous = result.frontTriangles.size();
            }
        }
    }
}

TEST(FaceOrientationShares, VertexMethodsAgreeExactly) {
    // During-vertices and after-vertices differ in traversal, not in outcome.
    const Mesh mesh = makeTorus(3.0f, 1.0f, 64, 32);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 eye(4.0, -9.0, 6.0);
    for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
        const ViewVectorChoice view = chooseViewVector(mode, eye, {0, 0, 0}, 4.0);
        for (int rule = 1; rule <= 3; ++rule) {
            const MeshOrientation during =
                orientMesh(mesh, data, makeRequest({FaceOrientationMethod::DuringVertices, rule}, view, eye));
            const MeshOrientation after =
                orientMesh(mesh, data, makeRequest({FaceOrientationMethod::AfterVertices, rule}, view, eye));
            EXPECT_EQ(during.frontTriangles, after.frontTriangles) << "rule " << rule;
            EXPECT_EQ(during.backTriangles, after.backTriangles) << "rule " << rule;
            EXPECT_EQ(during.shadeCoords, after.shadeCoords) << "rule " << rule;
            EXPECT_EQ(during.frontVertexCount, after.frontVertexCount);
            EXPECT_EQ(during.cutoff, after.cutoff);
        }
    }
}

TEST(FaceOrientationShares, ReusedResultMatchesAFreshOne) {
    const Mesh mesh = makeTorus(3.0f, 1.0f, 48, 24);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    MeshOrientation reused;
    // Far then close, so the second call must shrink what the first left behind.
    for (const glm::dvec3& eye : {glm::dvec3(0.0, -40.0, 10.0), glm::dvec3(0.5, -4.5, 1.0), glm::dvec3(20, 0, 0)}) {
        const ViewVectorChoice view = chooseViewVector(ViewVectorMode::Constant, eye, {0, 0, 0}, 4.0);
        for (const MethodRule& methodRule : allMethodsAndRules()) {
            const OrientationRequest request = makeRequest(methodRule, view, eye);
            const MeshOrientation fresh = orientMesh(mesh, data, request);
            orientMesh(mesh, data, request, reused);
            EXPECT_EQ(reused.frontTriangles, fresh.frontTriangles) << describe(methodRule, view);
            EXPECT_EQ(reused.backTriangles, fresh.backTriangles) << describe(methodRule, view);
            EXPECT_EQ(reused.shadeCoords, fresh.shadeCoords) << describe(methodRule, view);
            EXPECT_EQ(reused.frontVertexCount, fresh.frontVertexCount);
            EXPECT_EQ(reused.missedTriangles, fresh.missedTriangles);
            EXPECT_EQ(reused.cutoff, fresh.cutoff);
        }
    }
}

TEST(FaceOrientationShares, CutoffsFollowTheFormulas) {
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 64, 32);
    const OrientationMeshData data = deriveOrientationData(mesh, false);
    const glm::dvec3 eye(0.0, 0.0, 4.0);
    const ViewVectorChoice constant = chooseViewVector(ViewVectorMode::Constant, eye, {0, 0, 0}, 1.0);
    const ViewVectorChoice exact = chooseViewVector(ViewVectorMode::Exact, eye, {0, 0, 0}, 1.0);
    const double beta = data.betaMaxRadians;
    const auto cutoffOf = [&](FaceOrientationMethod method, const ViewVectorChoice& view) {
        return orientMesh(mesh, data, makeRequest({method, 3}, view, eye)).cutoff;
    };
    EXPECT_DOUBLE_EQ(cutoffOf(FaceOrientationMethod::DuringTriangles, constant), 0.25);
    EXPECT_DOUBLE_EQ(cutoffOf(FaceOrientationMethod::DuringTriangles, exact), 0.0);
    EXPECT_DOUBLE_EQ(cutoffOf(FaceOrientationMethod::AfterVertices, constant), std::sin(std::asin(0.25) + beta));
    EXPECT_DOUBLE_EQ(cutoffOf(FaceOrientationMethod::AfterVertices, exact), std::sin(beta));

    // A cube's corner normals are 54.7 degrees off its faces; with alpha = 41.8 degrees (1.5 radii, by hand) the sum
    // passes pi/2, the cut-off is 1 and every vertex, even the far corner whose normal points straight along V, is
    // front.
    const Mesh cube = makeCube();
    const OrientationMeshData cubeData = deriveOrientationData(cube, false);
    const glm::dvec3 closeEye(1.5, 1.5, 1.5); // 1.5 bounding radii (sqrt 3) from the centre
    ViewVectorChoice close;
    close.constant = true;
    close.constantView = -glm::normalize(closeEye);
    close.sinAlpha = 1.0 / 1.5;
    const MeshOrientation all =
        orientMesh(cube, cubeData, makeRequest({FaceOrientationMethod::AfterVertices, 1}, close, closeEye));
    EXPECT_EQ(all.cutoff, 1.0);
    EXPECT_EQ(all.frontVertexCount, 8u);
    EXPECT_EQ(all.frontTriangles.size(), 12u);
}

// ---- lighting ----------------------------------------------------------------------------------------------------

TEST(FaceOrientationLighting, NormalAlongTheLightSeenFromAboveIsFullyLit) {
    // The sphere's north pole has N = L = (0,0,1); with the eye straight above, V = (0,0,-1) and the paper form gives
    // R.V = L.V - 2 (N.L)(N.V) = -1 + 2 = 1.
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 64, 32);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 eye(0.0, 0.0, 5.0);
    for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
        const ViewVectorChoice view = chooseViewVector(mode, eye, {0, 0, 0}, 1.0);
        for (const MethodRule& methodRule : allMethodsAndRules()) {
            OrientationRequest request = makeRequest(methodRule, view, eye);
            request.towardLight = {0.0, 0.0, 1.0};
            for (const double shininess : {0.0, 1.0, 32.0, 1e6}) {
                request.shininess = shininess;
                const MeshOrientation result = orientMesh(mesh, data, request);
                EXPECT_EQ(result.shadeCoords[0], glm::vec2(1.0f, 1.0f))
                    << describe(methodRule, view) << ", shininess " << shininess;
            }
        }
    }
}

/** Checks every vertex against the textbook Phong form r.v with r = 2(n.l)n - l and v surface -> eye: (s, t) where
 *  the vertex test passes clearly, (0, 0) where it fails clearly, against the vertex's own cut-off
 *  sin(min(pi/2, alpha + beta_v)). Returns how many vertices had 0.05 < t < 0.95. */
int expectTextbookLighting(const Mesh& mesh, const OrientationMeshData& data, const MeshOrientation& result,
                           const OrientationRequest& request) {
    int partial = 0;
    const glm::dvec3 light = glm::normalize(request.towardLight);
    const double alpha = request.view.constant ? std::asin(request.view.sinAlpha) : 0.0;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const double beta = std::atan2(double(data.vertexBeta[v].x), double(data.vertexBeta[v].y));
        const double cutoff = std::sin(std::min(glm::half_pi<double>(), alpha + beta));
        const glm::dvec3 n(mesh.normals[v]);
        const glm::dvec3 p(mesh.positions[v]);
        const glm::dvec3 toEye = request.view.constant ? -request.view.constantView : glm::normalize(request.eye - p);
        const double dotNV = -glm::dot(n, toEye);
        const glm::vec2 got = result.shadeCoords[v];
        EXPECT_LE(cutoff, result.cutoff + 1e-6) << "the reported cut-off is the largest";
        if (dotNV > cutoff + 1e-4) {
            EXPECT_EQ(got, glm::vec2(0.0f)) << "back vertex " << v;
            continue;
        }
        if (dotNV > cutoff - 1e-4) {
            continue; // on the cut-off: either answer is right
        }
        const double dotNL = glm::dot(n, light);
        const glm::dvec3 mirror = 2.0 * dotNL * n - light;
        const double base = std::max(glm::dot(mirror, toEye), 0.0);
        const double s = std::max(dotNL, 0.0);
        const double t = dotNL > 0.0 ? (request.shininess == 0.0 ? 1.0 : std::pow(base, request.shininess)) : 0.0;
        EXPECT_NEAR(got.x, s, 1e-6) << "vertex " << v;
        EXPECT_NEAR(got.y, t, 2e-5) << "vertex " << v;
        partial += (t > 0.05 && t < 0.95) ? 1 : 0;
    }
    return partial;
}

TEST(FaceOrientationLighting, MatchesTheTextbookForm) {
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 128, 64);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 eye(0.5, -1.0, 4.0);
    for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
        const ViewVectorChoice view = chooseViewVector(mode, eye, {0, 0, 0}, 1.0);
        for (const FaceOrientationMethod method :
             {FaceOrientationMethod::DuringVertices, FaceOrientationMethod::AfterVertices}) {
            // Whole shininess up to 1024 is raised by repeated squaring, the rest by std::pow: both are checked.
            for (const double shininess : {1.0, 7.5, 32.0, 1000.0, 1500.0}) {
                OrientationRequest request = makeRequest({method, 3}, view, eye);
                request.shininess = shininess;
                const MeshOrientation result = orientMesh(mesh, data, request);
                const int partial = expectTextbookLighting(mesh, data, result, request);
                if (shininess == 32.0) {
                    EXPECT_GT(partial, 10) << describe({method, 3}, view) << ": too few vertices in the highlight";
                }
            }
        }
    }
}

TEST(FaceOrientationLighting, ShininessZeroGivesFullSpecularWhereLit) {
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 64, 32);
    const OrientationMeshData data = deriveOrientationData(mesh, false);
    const glm::dvec3 eye(0.0, 3.0, 3.0);
    const ViewVectorChoice view = chooseViewVector(ViewVectorMode::Exact, eye, {0, 0, 0}, 1.0);
    OrientationRequest request = makeRequest({FaceOrientationMethod::DuringTriangles, 3}, view, eye);
    request.shininess = 0.0;
    const MeshOrientation result = orientMesh(mesh, data, request);
    // During-triangles lights exactly the vertices of front triangles.
    std::vector<bool> lit(mesh.positions.size(), false);
    for (const glm::uvec3& triangle : result.frontTriangles) lit[triangle.x] = lit[triangle.y] = lit[triangle.z] = true;
    std::size_t litCount = 0;
    int shadowed = 0;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::vec2 got = result.shadeCoords[v];
        if (!lit[v]) {
            EXPECT_EQ(got, glm::vec2(0.0f));
            continue;
        }
        ++litCount;
        const double dotNL = glm::dot(glm::dvec3(mesh.normals[v]), request.towardLight);
        if (dotNL > 0.0) {
            EXPECT_EQ(got.y, 1.0f) << "vertex " << v;
        } else {
            EXPECT_EQ(got, glm::vec2(0.0f)) << "vertex " << v;
            ++shadowed;
        }
    }
    EXPECT_EQ(result.frontVertexCount, litCount);
    EXPECT_GT(shadowed, 0); // the check above covered both branches
}

TEST(FaceOrientationLighting, HugeShininessAndEyeOnAVertexStayFinite) {
    const Mesh mesh = makeUvSphere({0, 0, 0}, 1.0f, 64, 32);
    const OrientationMeshData data = deriveOrientationData(mesh, true);
    const glm::dvec3 onVertex(mesh.positions[100]);
    for (const glm::dvec3& eye : {glm::dvec3(0.2, -3.0, 1.0), onVertex}) {
        for (const ViewVectorMode mode : {ViewVectorMode::Exact, ViewVectorMode::Constant}) {
            const ViewVectorChoice view = chooseViewVector(mode, eye, {0, 0, 0}, 1.0);
            for (const MethodRule& methodRule : allMethodsAndRules()) {
                for (const double shininess : {0.0, 1e6}) {
                    OrientationRequest request = makeRequest(methodRule, view, eye);
                    request.shininess = shininess;
                    const MeshOrientation result = orientMesh(mesh, data, request);
                    std::size_t bad = 0;
                    for (const glm::vec2& st : result.shadeCoords) {
                        const bool inRange = st.x >= 0.0f && st.x <= 1.0f && st.y >= 0.0f && st.y <= 1.0f;
                        bad += (std::isfinite(st.x) && std::isfinite(st.y) && inRange) ? 0 : 1;
                    }
                    EXPECT_EQ(bad, 0u) << describe(methodRule, view) << ", shininess " << shininess;
                    EXPECT_TRUE(std::isfinite(result.cutoff));
                }
            }
        }
    }
}

// ---- argument checks ---------------------------------------------------------------------------------------------

TEST(OrientMesh, RejectsBadRequests) {
    const Mesh mesh = makeCube();
    const OrientationMeshData data = deriveOrientationData(mesh, false);
    const ViewVectorChoice view = chooseViewVector(ViewVectorMode::Exact, {0, 0, 5}, {0, 0, 0}, 2.0);
    const auto messageOf = [&](OrientationRequest request) -> std::string {
        try {
            orientMesh(mesh, data, request);
        } catch (const std::invalid_argument& error) {
            return error.what();
        }
        return "no exception";
    };
    const OrientationRequest good = makeRequest({FaceOrientationMethod::AfterVertices, 3}, view, {0, 0, 5});
    EXPECT_NO_THROW(orientMesh(mesh, data, good));

    OrientationRequest standard = good;
    standard.method = FaceOrientationMethod::Standard;
    EXPECT_EQ(messageOf(standard).rfind("orientMesh(): the 'standard' method", 0), 0u) << messageOf(standard);
    for (const int rule : {0, 4}) {
        OrientationRequest badRule = good;
        badRule.frontRule = rule;
        EXPECT_EQ(messageOf(badRule).rfind("orientMesh(): the front rule", 0), 0u) << messageOf(badRule);
    }
    for (const double shininess : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
        OrientationRequest badShininess = good;
        badShininess.shininess = shininess;
        EXPECT_EQ(messageOf(badShininess).rfind("orientMesh(): the shininess", 0), 0u) << messageOf(badShininess);
    }
    OrientationRequest noLight = good;
    noLight.towardLight = glm::dvec3(0.0);
    EXPECT_EQ(messageOf(noLight).rfind("orientMesh(): 'towardLight'", 0), 0u) << messageOf(noLight);
    OrientationRequest needsAdjacency = good;
    needsAdjacency.method = FaceOrientationMethod::DuringVertices;
    EXPECT_EQ(messageOf(needsAdjacency).rfind("orientMesh(): 'during-vertices' needs", 0), 0u)
        << messageOf(needsAdjacency);
}

TEST(OrientMesh, Names) {
    EXPECT_EQ(viewVectorModeName(ViewVectorMode::Exact), "exact");
    EXPECT_EQ(viewVectorModeName(ViewVectorMode::Constant), "constant");
    EXPECT_EQ(faceOrientationMethodName(FaceOrientationMethod::Standard), "standard");
    EXPECT_EQ(faceOrientationMethodName(FaceOrientationMethod::DuringTriangles), "during-triangles");
    EXPECT_EQ(faceOrientationMethodName(FaceOrientationMethod::DuringVertices), "during-vertices");
    EXPECT_EQ(faceOrientationMethodName(FaceOrientationMethod::AfterVertices), "after-vertices");
}

} // namespace
} // namespace inkgraph
