// Closed meshes wound inside out are turned outward at load (scene/mesh/OutwardWinding.h); open surfaces, flat closed
// sheets and one-sided materials are left as they are.
#include "scene/Scene.h"
#include "scene/Warning.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/OutwardWinding.h"
#include "scene/mesh/Procedural.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

namespace inkgraph {
namespace {

constexpr double kWeld = 1e-6;

Mesh insideOut(Mesh mesh) {
    for (glm::uvec3& triangle : mesh.triangles) std::swap(triangle.y, triangle.z);
    return mesh;
}

std::vector<glm::vec3> negated(std::vector<glm::vec3> normals) {
    for (glm::vec3& normal : normals) normal = -normal;
    return normals;
}

/** The upper half of a sphere's triangles (every vertex at or above the equator): an open dish. */
Mesh upperHalf(Mesh mesh) {
    std::erase_if(mesh.triangles, [&](const glm::uvec3& triangle) {
        return mesh.positions[triangle.x].z < -1e-6f || mesh.positions[triangle.y].z < -1e-6f ||
               mesh.positions[triangle.z].z < -1e-6f;
    });
    return mesh;
}

TEST(OutwardWinding, AClosedSphereWoundInsideOutIsTurnedOutwardWithItsInwardNormals) {
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24);
    Mesh mesh = insideOut(outward);
    std::vector<glm::vec3> normals = negated(outward.normals);
    const OutwardTurn turn = orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld);
    EXPECT_TRUE(turn.windingReversed);
    EXPECT_TRUE(turn.normalsFlipped);
    EXPECT_EQ(mesh.triangles, outward.triangles);
    EXPECT_EQ(normals, outward.normals);
}

TEST(OutwardWinding, OutwardNormalsOnAnInsideOutWindingStayAsTheyAre) {
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24);
    Mesh mesh = insideOut(outward);
    std::vector<glm::vec3> normals = outward.normals;
    const OutwardTurn turn = orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld);
    EXPECT_TRUE(turn.windingReversed);
    EXPECT_FALSE(turn.normalsFlipped);
    EXPECT_EQ(normals, outward.normals);
}

TEST(OutwardWinding, AnOutwardMeshIsLeftAsItIs) {
    const Mesh outward = makeUvSphere(glm::vec3(5.0f, -3.0f, 2.0f), 0.5f, 32, 16);
    Mesh mesh = outward;
    std::vector<glm::vec3> normals;
    const OutwardTurn turn = orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld);
    EXPECT_FALSE(turn.windingReversed);
    EXPECT_EQ(mesh.triangles, outward.triangles);
}

TEST(OutwardWinding, ACubeOfSplitHardEdgesIsClosedThroughTheWeld) {
    // makeCube() keeps a vertex per face (its hard edges): closed only with positions welded.
    const Mesh outward = makeCube(glm::vec3(0.0f), 1.0f);
    Mesh mesh = insideOut(outward);
    std::vector<glm::vec3> normals;
    EXPECT_TRUE(orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld).windingReversed);
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
}

TEST(OutwardWinding, AnOpenDishWoundEitherWayIsLeftAsItIs) {
    const Mesh dish = upperHalf(makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24));
    for (const Mesh& wound : {dish, insideOut(dish)}) {
        Mesh mesh = wound;
        std::vector<glm::vec3> normals;
        EXPECT_FALSE(orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld).windingReversed);
        EXPECT_EQ(mesh.triangles, wound.triangles);
    }
}

TEST(OutwardWinding, AFewSmallHolesStillCountAsClosed) {
    // A scan with holes: two missing triangles leave 6 rim edges, well under 1% of the sphere's edges.
    Mesh mesh = insideOut(makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24));
    mesh.triangles.erase(mesh.triangles.begin() + 700);
    mesh.triangles.erase(mesh.triangles.begin() + 1500);
    std::vector<glm::vec3> normals;
    EXPECT_TRUE(orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld).windingReversed);
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
}

TEST(OutwardWinding, FacesThatDisagreeAmongThemselvesAreLeftAsTheyAre) {
    // Inside out but for a band of faces wound outward: reversing every face would turn the band inward, so a mesh
    // whose faces disagree on more than 1% of their shared edges is not guessed at.
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24);
    Mesh mesh = insideOut(outward);
    for (std::size_t face = 0; face < mesh.triangles.size(); ++face) {
        const glm::uvec3& t = mesh.triangles[face];
        const float z = (mesh.positions[t.x].z + mesh.positions[t.y].z + mesh.positions[t.z].z) / 3.0f;
        if (z > 0.3f && z < 0.5f) mesh.triangles[face] = outward.triangles[face];
    }
    const std::vector<glm::uvec3> before = mesh.triangles;
    std::vector<glm::vec3> normals;
    EXPECT_FALSE(orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld).windingReversed);
    EXPECT_EQ(mesh.triangles, before);
}

/** `mesh` with the faces whose centres lie at heights in (low, high) wound the other way; their indices in `band`. */
Mesh withBandTurned(Mesh mesh, float low, float high, std::vector<std::uint32_t>* band = nullptr) {
    for (std::size_t face = 0; face < mesh.triangles.size(); ++face) {
        glm::uvec3& t = mesh.triangles[face];
        const float z = (mesh.positions[t.x].z + mesh.positions[t.y].z + mesh.positions[t.z].z) / 3.0f;
        if (z <= low || z >= high) continue;
        std::swap(t.y, t.z);
        if (band != nullptr) band->push_back(std::uint32_t(face));
    }
    return mesh;
}

TEST(OutwardWinding, APatchWoundAgainstItsNeighboursIsTurnedToAgreeWithMostOfTheSurface) {
    // A scan merged from range images: a band of a sphere's faces wound the other way. Without normals the surface
    // is wound as most of its area is, so the band turns and nothing else.
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24);
    std::vector<std::uint32_t> band;
    Mesh mesh = withBandTurned(outward, 0.3f, 0.5f, &band);
    ASSERT_FALSE(band.empty());
    EXPECT_EQ(turnMixedWinding(mesh.positions, mesh.triangles, {}, kWeld), band);
    EXPECT_EQ(mesh.triangles, outward.triangles);
    EXPECT_TRUE(turnMixedWinding(mesh.positions, mesh.triangles, {}, kWeld).empty()) << "wound one way now";

    // Inside out but for the band: the band is what turns, and the whole is then inside out, for orientMeshOutward().
    Mesh inverted = withBandTurned(insideOut(outward), 0.3f, 0.5f);
    EXPECT_EQ(turnMixedWinding(inverted.positions, inverted.triangles, {}, kWeld), band);
    EXPECT_EQ(inverted.triangles, insideOut(outward).triangles);
}

TEST(OutwardWinding, GivenNormalsChooseTheWayAMixedSurfaceIsWound) {
    // Most of the sphere wound inward, its normals outward: the normals decide, so the larger part turns.
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 48, 24);
    std::vector<std::uint32_t> band;
    Mesh mesh = withBandTurned(outward, -0.8f, 1.1f, &band);
    ASSERT_GT(band.size(), outward.triangles.size() / 2);
    EXPECT_EQ(turnMixedWinding(mesh.positions, mesh.triangles, outward.normals, kWeld), band);
    EXPECT_EQ(mesh.triangles, outward.triangles);
    // Without them, most of the area wins: the smaller part turns, leaving the sphere inside out.
    Mesh unguided = withBandTurned(outward, -0.8f, 1.1f);
    EXPECT_EQ(turnMixedWinding(unguided.positions, unguided.triangles, {}, kWeld).size(),
              outward.triangles.size() - band.size());
    EXPECT_EQ(unguided.triangles, insideOut(outward).triangles);
}

TEST(OutwardWinding, LoadingAMixedScanTurnsItsPatchWithAWarningAndTheLabelsKeepTheFilesCorners) {
    const Mesh outward = makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16);
    std::vector<std::uint32_t> band;
    const Mesh mixed = withBandTurned(outward, -0.2f, 0.4f, &band);
    std::ostringstream obj;
    obj << "o scan\n";
    for (const glm::vec3& p : mixed.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const glm::uvec3& t : mixed.triangles) obj << "f " << t.x + 1 << ' ' << t.y + 1 << ' ' << t.z + 1 << '\n';
    const test::TempFile file("scan.obj", obj.str());
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
    std::vector<std::uint32_t> swapped;
    for (std::size_t face = 0; face < mesh.cornersSwapped.size(); ++face)
        if (mesh.cornersSwapped[face] != 0) swapped.push_back(std::uint32_t(face));
    EXPECT_EQ(swapped, band) << "the turned faces' barycentric weights are swapped back to the file's corners";
    const auto warning = std::find_if(scene.report.warnings.begin(), scene.report.warnings.end(), [](const Warning& w) {
        return w.code == warningCode(WarningKind::WindingMixed);
    });
    ASSERT_NE(warning, scene.report.warnings.end());
    EXPECT_EQ(warning->message, "mesh 'scan': " + std::to_string(band.size()) + " of " +
                                    std::to_string(mesh.triangles.size()) +
                                    " triangles were wound against their neighbours (and most of their surface); "
                                    "turned so each surface is wound one way");
}

/** A square floor 2 x half wide at height z, wound counter-clockwise seen from above (facing up). */
Mesh withFloor(Mesh mesh, float half, float z) {
    const auto first = std::uint32_t(mesh.positions.size());
    for (const glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        mesh.positions.push_back(glm::vec3(half * corner, z));
    mesh.triangles.push_back({first, first + 1, first + 2});
    mesh.triangles.push_back({first, first + 2, first + 3});
    return mesh;
}

TEST(OutwardWinding, EachConnectedSurfaceIsJudgedAlone) {
    // A ball on a wide floor facing up, in one mesh: seen from the middle of the box the floor encloses a negative
    // volume larger than the ball's, and its four rim edges are too few to call the whole mesh open. The ball is
    // outward and stays; turned inside out it is turned back; the floor, open, keeps its winding either way.
    const Mesh ball = makeUvSphere(glm::vec3(0.0f, 0.0f, 1.0f), 0.3f, 48, 24);
    const Mesh scene = withFloor(ball, 2.0f, 0.0f);
    Mesh mesh = scene;
    std::vector<glm::vec3> normals;
    EXPECT_FALSE(orientMeshOutward(mesh.positions, mesh.triangles, normals, kWeld).windingReversed);
    EXPECT_EQ(mesh.triangles, scene.triangles);

    Mesh turned = withFloor(insideOut(ball), 2.0f, 0.0f);
    EXPECT_TRUE(orientMeshOutward(turned.positions, turned.triangles, normals, kWeld).windingReversed);
    EXPECT_EQ(turned.triangles, scene.triangles);
}

TEST(OutwardWinding, AClosedFlatSheetDecidesNothing) {
    // Two coincident sides of a square, each wound its own way: closed, with no volume.
    const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    std::vector<glm::uvec3> triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}};
    const std::vector<glm::uvec3> before = triangles;
    std::vector<glm::vec3> normals;
    EXPECT_FALSE(orientMeshOutward(positions, triangles, normals, kWeld).windingReversed);
    EXPECT_EQ(triangles, before);
}

std::string sphereObj(bool insideOutWinding) {
    const Mesh sphere = makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16);
    std::ostringstream obj;
    for (const glm::vec3& p : sphere.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const glm::uvec3& t : sphere.triangles) {
        const glm::uvec3 corners = insideOutWinding ? glm::uvec3(t.x, t.z, t.y) : t;
        obj << "f " << corners.x + 1 << ' ' << corners.y + 1 << ' ' << corners.z + 1 << '\n';
    }
    return obj.str();
}

TEST(OutwardWinding, LoadingAnInsideOutObjTurnsItOutwardAndWarnsNamingTheMesh) {
    const test::TempFile file("inside-out.obj", "o ball\n" + sphereObj(true));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    test::expectOutwardWinding(scene.meshes[0], glm::dvec3(0.0));
    for (std::size_t i = 0; i < scene.meshes[0].positions.size(); ++i)
        ASSERT_GT(glm::dot(scene.meshes[0].normals[i], scene.meshes[0].positions[i]), 0.5f) << "vertex " << i;
    const auto warning = std::find_if(scene.report.warnings.begin(), scene.report.warnings.end(), [](const Warning& w) {
        return w.code == warningCode(WarningKind::MeshInsideOut);
    });
    ASSERT_NE(warning, scene.report.warnings.end());
    EXPECT_NE(warning->message.find("mesh 'ball'"), std::string::npos) << warning->message;
    EXPECT_EQ(warning->file, file.path());

    const test::TempFile right("outward.obj", "o ball\n" + sphereObj(false));
    const Scene outward = loadScene(right.path());
    EXPECT_TRUE(outward.report.warnings.empty());
    EXPECT_EQ(outward.meshes[0].triangles, scene.meshes[0].triangles);
}

/** A sphere with outward winding and its normals given, outward or inward (a caller's clockwise cross products). */
std::string sphereObjWithNormals(float normalSign) {
    const Mesh sphere = makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16);
    std::ostringstream obj;
    for (const glm::vec3& p : sphere.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    for (const glm::vec3& n : sphere.normals)
        obj << "vn " << normalSign * n.x << ' ' << normalSign * n.y << ' ' << normalSign * n.z << '\n';
    for (const glm::uvec3& t : sphere.triangles)
        obj << "f " << t.x + 1 << "//" << t.x + 1 << ' ' << t.y + 1 << "//" << t.y + 1 << ' ' << t.z + 1 << "//"
            << t.z + 1 << '\n';
    return obj.str();
}

TEST(OutwardWinding, NormalsGivenAgainstTheWindingAreTurnedRoundWithAWarning) {
    // The winding outward, the normals inward: they reached the G-buffer's normal as given (the shader turns only a
    // back face's), so lighting and the n . v lines read the front of the ball as facing away.
    const test::TempFile file("inward-normals.obj", "o ball\n" + sphereObjWithNormals(-1.0f));
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    test::expectOutwardWinding(scene.meshes[0], glm::dvec3(0.0));
    for (std::size_t i = 0; i < scene.meshes[0].positions.size(); ++i)
        ASSERT_GT(glm::dot(scene.meshes[0].normals[i], scene.meshes[0].positions[i]), 0.5f) << "vertex " << i;
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    const Warning& warning = scene.report.warnings[0];
    EXPECT_EQ(warning.code, "normals-inward");
    EXPECT_EQ(warning.item, "ball");
    EXPECT_NE(warning.message.find("mesh 'ball': its given normals point against its faces' winding"),
              std::string::npos)
        << warning.message;
    EXPECT_NE(warning.message.find(std::to_string(scene.meshes[0].positions.size()) + " of " +
                                   std::to_string(scene.meshes[0].positions.size()) + " turned round"),
              std::string::npos)
        << warning.message;
    // Outward normals, and normals that disagree on half the ball (all +z), are the author's: kept, no warning.
    const test::TempFile outward("outward-normals.obj", "o ball\n" + sphereObjWithNormals(1.0f));
    EXPECT_TRUE(loadScene(outward.path()).report.warnings.empty());
    Mesh sphere = makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16);
    std::vector<glm::vec3> up(sphere.positions.size(), glm::vec3(0, 0, 1));
    EXPECT_EQ(turnNormalsAlongWinding(sphere.positions, sphere.triangles, up), 0u);
    EXPECT_EQ(up, std::vector<glm::vec3>(sphere.positions.size(), glm::vec3(0, 0, 1)));
}

TEST(OutwardWinding, AOneSidedMaterialKeepsItsNormals) {
    // A baked inverted-hull outline: faces turned inward for culling, normals outward as the body's. Kept as given.
    Mesh sphere = insideOut(makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16));
    RawMesh raw;
    raw.name = "outline shell";
    raw.positions = sphere.positions;
    raw.normals = makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16).normals;
    raw.triangles = sphere.triangles;
    raw.material.doubleSided = false;
    LoadReport report;
    const Mesh mesh = finalizeMesh(std::move(raw), 2.0 * std::sqrt(3.0), LoadOptions{}, report);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        ASSERT_GT(glm::dot(mesh.normals[i], mesh.positions[i]), 0.5f) << "vertex " << i;
    EXPECT_TRUE(report.warnings.empty());
}

TEST(OutwardWinding, AOneSidedMaterialKeepsItsWinding) {
    // A one-sided glTF material culls by the winding the author chose: an inside-out shell drawn that way is a baked
    // outline (the inverted hull), not a mistake.
    Mesh sphere = insideOut(makeUvSphere(glm::vec3(0.0f), 1.0f, 32, 16));
    RawMesh raw;
    raw.name = "outline shell";
    raw.positions = sphere.positions;
    raw.triangles = sphere.triangles;
    raw.material.doubleSided = false;
    LoadReport report;
    const Mesh mesh = finalizeMesh(std::move(raw), 2.0 * std::sqrt(3.0), LoadOptions{}, report);
    EXPECT_EQ(mesh.triangles, sphere.triangles);
    EXPECT_TRUE(report.warnings.empty());
}

TEST(OutwardWinding, ATriangleTurnedOutwardOrMirroredByTheReaderSaysItsCornersAreSwapped) {
    // Two spheres in one mesh: the first inside out (turned by the loader), the second outward but with every other
    // triangle's corners swapped by the reader (a mirroring transform, as the glTF reader marks it), and a zero-area
    // triangle first, which the loader drops. Each kept triangle's corners with its swap undone are the file's.
    // The inward one the larger: only a mesh enclosing a negative volume in all is looked at surface by surface.
    Mesh inward = insideOut(makeUvSphere(glm::vec3(0.0f), 1.5f, 32, 16));
    const Mesh outward = makeUvSphere(glm::vec3(4.0f, 0.0f, 0.0f), 1.0f, 32, 16);
    RawMesh raw;
    raw.name = "spheres";
    raw.positions = inward.positions;
    raw.positions.insert(raw.positions.end(), outward.positions.begin(), outward.positions.end());
    const auto offset = std::uint32_t(inward.positions.size());
    raw.triangles = {glm::uvec3(0, 0, 1)};
    raw.triangles.insert(raw.triangles.end(), inward.triangles.begin(), inward.triangles.end());
    raw.cornersSwapped.assign(raw.triangles.size(), 0);
    std::vector<glm::uvec3> file = raw.triangles; // as the file gives them
    for (std::size_t index = 0; index < outward.triangles.size(); ++index) {
        const glm::uvec3 triangle = outward.triangles[index] + offset;
        raw.cornersSwapped.push_back(index % 2);
        raw.triangles.push_back(triangle);
        file.push_back(index % 2 ? glm::uvec3(triangle.x, triangle.z, triangle.y) : triangle);
    }
    const std::vector<glm::vec3> filePositions = raw.positions;
    LoadReport report;
    const Mesh mesh = finalizeMesh(std::move(raw), 8.0, LoadOptions{}, report);
    EXPECT_EQ(report.degenerateDropped, 1u);
    ASSERT_EQ(mesh.triangleCount(), file.size() - 1);
    ASSERT_EQ(mesh.cornersSwapped.size(), mesh.triangleCount());
    std::size_t swapped = 0;
    for (std::size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle) {
        glm::uvec3 corners = mesh.triangles[triangle];
        swapped += mesh.cornersSwapped[triangle];
        if (mesh.cornersSwapped[triangle]) std::swap(corners.y, corners.z);
        const glm::uvec3 given = file[mesh.fileTriangleOf(triangle)];
        for (int corner = 0; corner < 3; ++corner)
            ASSERT_EQ(mesh.positions[corners[corner]], filePositions[given[corner]]) << triangle << " " << corner;
    }
    // The whole first sphere was turned, and half the second swapped by the reader.
    EXPECT_EQ(swapped, inward.triangles.size() + outward.triangles.size() / 2);
    // A mesh with nothing swapped keeps the list empty.
    RawMesh plain;
    plain.positions = outward.positions;
    plain.triangles = outward.triangles;
    EXPECT_TRUE(finalizeMesh(std::move(plain), 8.0, LoadOptions{}, report).cornersSwapped.empty());
    EXPECT_TRUE(mesh.fileTriangles.size() == mesh.triangleCount() && mesh.fileTriangles.front() == 1u);
}

} // namespace
} // namespace inkgraph
