#include "scene/Scene.h"
#include "scene/mesh/EdgeAdjacency.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace inkgraph {
namespace {

using test::TempFile;

std::string cubeObj(bool negativeIndices = false) {
    std::ostringstream obj;
    obj << "# cube with quad faces\n";
    for (const glm::vec3& corner : test::cubeCorners()) {
        obj << "v " << corner.x << ' ' << corner.y << ' ' << corner.z << '\n';
    }
    const int count = int(test::cubeCorners().size());
    for (const glm::uvec4& quad : test::cubeQuads()) {
        obj << 'f';
        for (int corner = 0; corner < 4; ++corner) {
            const int index = int(quad[corner]);
            obj << ' ' << (negativeIndices ? index - count - 1 : index);
        }
        obj << '\n';
    }
    return obj.str();
}

std::size_t findVertex(const Mesh& mesh, glm::vec3 position) {
    const auto it = std::find(mesh.positions.begin(), mesh.positions.end(), position);
    EXPECT_NE(it, mesh.positions.end()) << "no vertex at (" << position.x << ", " << position.y << ", " << position.z
                                        << ")";
    return std::size_t(it - mesh.positions.begin());
}

TEST(ObjLoader, CubeOfQuadsGivesTwelveTrianglesOnEightVertices) {
    const TempFile file("cube.obj", cubeObj());
    const Scene scene = loadScene(file.path());

    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_EQ(scene.report.format, "obj");
    EXPECT_EQ(scene.report.trianglesRead, 12u);
    EXPECT_EQ(scene.report.verticesBeforeWeld, 8u);
    EXPECT_EQ(scene.report.verticesAfterWeld, 8u);
    EXPECT_EQ(scene.report.degenerateDropped, 0u);
    EXPECT_TRUE(scene.report.normalsComputed);
    EXPECT_FALSE(scene.camera.has_value());
    EXPECT_FALSE(scene.light.has_value());
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
    test::expectUnitNormals(mesh);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_GT(glm::dot(mesh.normals[i], mesh.positions[i]), 0.5f) << "normal of vertex " << i << " points inward";
    }
}

TEST(ObjLoader, SmoothNormalsAreAreaWeighted) {
    // Fans from each face's lowest vertex index give corner (-1,-1,-1) (vertex 1) both triangles of each of its three
    // faces: a symmetric normal. Corner (1,1,-1) gets both triangles of the -z and +y faces but one of +x, so area
    // weighting tilts its normal away from +x: (4, 8, -8) / |.|. An angle-weighted or per-face average would not.
    const TempFile file("weighted.obj", cubeObj());
    const Mesh mesh = loadScene(file.path()).meshes.at(0);

    const glm::vec3 symmetric = mesh.normals[findVertex(mesh, {-1, -1, -1})];
    const glm::vec3 expectedSymmetric = glm::normalize(glm::vec3(-1, -1, -1));
    const glm::vec3 tilted = mesh.normals[findVertex(mesh, {1, 1, -1})];
    const glm::vec3 expectedTilted = glm::normalize(glm::vec3(1, 2, -2));
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(symmetric[axis], expectedSymmetric[axis], 1e-6);
        EXPECT_NEAR(tilted[axis], expectedTilted[axis], 1e-6);
    }
}

TEST(ObjLoader, NegativeIndicesMatchPositiveOnes) {
    const TempFile positive("positive.obj", cubeObj(false));
    const TempFile negative("negative.obj", cubeObj(true));
    const Mesh a = loadScene(positive.path()).meshes.at(0);
    const Mesh b = loadScene(negative.path()).meshes.at(0);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.triangles, b.triangles);
}

TEST(ObjLoader, NegativeIndicesAreRelativeToTheCurrentLine) {
    // Each face refers to the three vertices just above it.
    const TempFile file("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"
                                        "v 5 0 0\nv 6 0 0\nv 5 1 0\nf -3 -2 -1\n");
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    ASSERT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.positions.size(), 6u);
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[mesh.triangles[1].x]), glm::dvec3(5, 0, 0));
    EXPECT_EQ(test::worldPosition(scene, mesh.positions[mesh.triangles[1].z]), glm::dvec3(5, 1, 0));
}

TEST(ObjLoader, FileNormalsArePreservedAndKeepHardEdgesSplit) {
    // The cube with one normal per face (v//vn): each corner has three normals, so 24 vertices survive welding.
    std::ostringstream obj;
    for (const glm::vec3& corner : test::cubeCorners()) {
        obj << "v " << corner.x << ' ' << corner.y << ' ' << corner.z << '\n';
    }
    const std::vector<glm::vec3> faceNormals = {{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0}};
    for (const glm::vec3& n : faceNormals) {
        obj << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
    }
    for (std::size_t face = 0; face < 6; ++face) {
        const glm::uvec4& quad = test::cubeQuads()[face];
        obj << "f " << quad.x << "//" << face + 1 << ' ' << quad.y << "//" << face + 1 << ' ' << quad.z << "//"
            << face + 1 << ' ' << quad.w << "//" << face + 1 << '\n';
    }
    const TempFile file("hard.obj", obj.str());
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);

    EXPECT_FALSE(scene.report.normalsComputed);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.positions.size(), 24u);
    for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::vec3 faceNormal = glm::vec3(glm::normalize(test::triangleCross(mesh, triangle)));
        for (int corner = 0; corner < 3; ++corner) {
            EXPECT_EQ(mesh.normals[triangle[corner]], faceNormal);
        }
    }
}

TEST(ObjLoader, AcceptsTextureCoordinateFormsCommentsCrlfAndObjectNames) {
    const TempFile file("forms.obj",
                        "# comment\r\nmtllib none.mtl\r\no thing\r\nv 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\n"
                        "vt 0 0\r\nvt 1 0\r\nvt 1 1\r\nvn 0 0 2\r\ng group\r\nusemtl m\r\ns off\r\n"
                        "f 1/1/1 2/2/1 3/3/1\r\n"
                        "f 1/1/1 3/3/1 4/1/1\r\n");
    const Scene scene = loadScene(file.path());
    const Mesh& mesh = scene.meshes.at(0);
    EXPECT_EQ(mesh.name, "thing");
    EXPECT_EQ(mesh.triangleCount(), 2u);
    EXPECT_EQ(mesh.positions.size(), 4u);
    for (const glm::vec3& normal : mesh.normals) {
        EXPECT_EQ(normal, glm::vec3(0, 0, 1)); // normalised from the file's (0, 0, 2)
    }

    const TempFile uvOnly("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n");
    const Scene uvScene = loadScene(uvOnly.path());
    EXPECT_EQ(uvScene.triangleCount(), 1u);
    EXPECT_TRUE(uvScene.report.normalsComputed);
    EXPECT_EQ(uvScene.meshes.at(0).normals.at(0), glm::vec3(0, 0, 1));
}

TEST(ObjLoader, ALineEndingInABackslashGoesOnOnTheNextLine) {
    // The OBJ specification's continuation (long `f` lines of some exporters) was refused. Only statements of
    // numbers continue: a comment, or a name ending in '\\' (a Windows folder: `g C:\models\`, `s 1 \`), does not
    // swallow the next line, and an error names the statement's first line.
    const TempFile file("continued.obj",
                        "# exported from C:\\models\\\ng C:\\models\\\nv 0 0 0\nv 1 0 \\\r\n  0\nv 1 1 0\n"
                        "v 0 1 0\ns 1 \\\nf 1 2 \\\n3 \\ \n 4\nv 5 5 5 \\");
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 2u) << "the quad read whole, cut in two";
    EXPECT_EQ(scene.report.trianglesRead, 2u);
    const auto atWorld = [&](glm::dvec3 world) {
        return std::ranges::any_of(scene.meshes[0].positions, [&](const glm::vec3& position) {
            return glm::length(test::worldPosition(scene, position) - world) < 1e-6;
        });
    };
    EXPECT_TRUE(atWorld({1, 0, 0})) << "'v 1 0 \\' went on to its z on the next line";

    const TempFile bad("continued_bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n2 \\\nx\nv 1 1 1\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(bad.path()); });
    EXPECT_NE(message.find("line 4"), std::string::npos) << message;
    const TempFile after("continued_after.obj", "v 0 0 0\nv 1 \\\n0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(after.path()); }).find("line 6"), std::string::npos)
        << "lines after a continued statement keep their numbers";
}

TEST(ObjLoader, ACommentAfterTheNumbersEndsThem) {
    // `f 1 2 3 # first` was refused ("cannot read face index in '#'"); a comment ending in '\\' does not continue,
    // and a '\\' before a comment does, on the first line as on the next.
    const TempFile file("comments.obj", "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nvn 0 0 1 # up\nvt 0 0 #\n"
                                        "f 1//1 2//1 3//1 # first C:\\dir\\\nf 1//1 3//1 2//1#second\n"
                                        "f 2//1 \\ # third\n1//1 \\ # goes on\n3//1\n");
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.trianglesRead, 3u);
    EXPECT_TRUE(scene.report.warnings.empty()) << ::testing::PrintToString(scene.report.warnings);
}

/** A double-faced card as exporters write it: a square and the same square in reverse, on the same vertices or on a
 *  copy of them. Cut from each face's first corner, the two crossed diagonals and the pair's smooth normals pointed
 *  either way, shading half the card black; now the reverse is cut along the same diagonal and, the material being
 *  two-sided, dropped as the first's twin: the single square, with +z normals. */
TEST(ObjLoader, ADoubleFacedCardLoadsAsItsFirstSide) {
    const std::string square = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";
    for (const std::string& faces : {std::string("f 1 2 3 4\nf 4 3 2 1\n"), std::string("f 1 2 3 4\nf 3 2 1 4\n"),
                                     square + "f 1 2 3 4\nf 8 7 6 5\n"}) {
        const TempFile file("card.obj", square + faces);
        const Scene scene = loadScene(file.path());
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(mesh.triangleCount(), 2u) << faces;
        EXPECT_EQ(mesh.positions.size(), 4u) << faces;
        EXPECT_EQ(scene.report.backToBackDropped, 2u) << faces;
        for (const glm::vec3& normal : mesh.normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1)) << faces;
        for (const glm::uvec3& triangle : mesh.triangles) EXPECT_GT(test::triangleCross(mesh, triangle).z, 0.0);
    }
    // A polygon is cut from its lowest vertex index on: the same two triangles whichever corner the face starts at.
    const TempFile rotated("rotated.obj", square + "f 3 4 1 2\n");
    const Mesh mesh = loadScene(rotated.path()).meshes.at(0);
    std::vector<std::uint32_t> corners;
    for (const glm::uvec3& triangle : mesh.triangles)
        for (int k = 0; k < 3; ++k) corners.push_back(triangle[k]);
    EXPECT_EQ(std::count(corners.begin(), corners.end(), findVertex(mesh, {-1, -1, 0})), 2)
        << "the diagonal from vertex 1";
}

/** A closed mesh whose faces the file gives twice (an exporter's merge of two copies of one object, a scan saved
 *  with its faces appended again) made every edge one of four faces, non-manifold, so `border` drew its wireframe.
 *  The second copy of each face is dropped, whichever corner it starts at and whether it names the same vertices
 *  or copies of them at the same places. */
TEST(ObjLoader, FacesTheFileGivesTwiceLoadOnce) {
    const std::string cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
    const std::string faces = "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const std::string facesOfTheCopy = "f 9 12 11 10\nf 13 14 15 16\nf 9 10 14 13\nf 10 11 15 14\nf 11 12 16 15\n"
                                       "f 12 9 13 16\n";
    const std::string turnedCorners = "f 4 3 2 1\nf 6 7 8 5\nf 2 6 5 1\nf 3 7 6 2\nf 4 8 7 3\nf 1 5 8 4\n";
    for (const std::string& body :
         {cube + faces + faces, cube + faces + turnedCorners, cube + cube + faces + facesOfTheCopy}) {
        const Scene scene = loadScene(TempFile("twice.obj", body).path());
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        EXPECT_EQ(mesh.triangleCount(), 12u) << body;
        EXPECT_EQ(scene.report.repeatedDropped, 12u) << body;
        EXPECT_EQ(scene.report.backToBackDropped, 0u) << body;
        const EdgeAdjacency adjacency = buildEdgeAdjacency(mesh.positions, mesh.triangles, 0.0);
        EXPECT_EQ(adjacency.counts.manifold, 18u) << body;
        EXPECT_EQ(adjacency.counts.boundary + adjacency.counts.nonManifold, 0u) << body;
    }
}

TEST(ObjLoader, AFaceGivenAgainWithNormalsOfItsOwnLoadsOnce) {
    // A flat copy of a smooth face (or a smooth copy of a flat one) is the same face: found on the surface's
    // vertices, as back-to-back twins are; the first copy's normals stay.
    const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0.6 0 0.8\n";
    const Scene scene =
        loadScene(TempFile("copies.obj", square + "f 1//1 2//1 3//1 4//1\nf 1//2 2//2 3//2 4//2\n").path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 2u);
    EXPECT_EQ(scene.report.repeatedDropped, 2u);
    for (const glm::vec3& normal : scene.meshes[0].normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    const EdgeAdjacency adjacency = buildEdgeAdjacency(scene.meshes[0].positions, scene.meshes[0].triangles, 0.0);
    EXPECT_EQ(adjacency.counts.boundary, 4u);
    EXPECT_EQ(adjacency.counts.nonManifold, 0u);
    // A copy with texture coordinates of its own is a face of its own (another picture on the same place).
    const std::string textured = square + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n";
    const Scene kept = loadScene(TempFile("own.obj", textured + "f 1/1 2/2 3/3 4/4\nf 1/5 2/5 3/5 4/5\n").path());
    EXPECT_EQ(kept.report.repeatedDropped, 0u);
}

TEST(ObjLoader, AConcaveDoubleFacedPolygonShadesAsItsOwnSides) {
    // A star written again in reverse is cut into other ears, so only some of its triangles pair up as back-to-back
    // twins; the rest share their corners with the other side, whose smooth normals cancelled: black wedges.
    std::string star;
    for (int i = 0; i < 10; ++i) {
        const double radius = i % 2 == 0 ? 1.0 : 0.4;
        const double angle = 3.14159265358979 / 2 + i * 3.14159265358979 / 5;
        star +=
            "v " + std::to_string(radius * std::cos(angle)) + " " + std::to_string(radius * std::sin(angle)) + " 0\n";
    }
    star += "f 1 2 3 4 5 6 7 8 9 10\nf 10 9 8 7 6 5 4 3 2 1\n";
    const Scene scene = loadScene(TempFile("star.obj", star).path());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_LT(scene.report.backToBackDropped, 8u) << "only some of the star's triangles pair up";
    test::expectCornerNormalsAlongTheirFaces(scene.meshes[0], "star");
}

TEST(ObjLoader, PentagonIsFanTriangulated) {
    const TempFile file("pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n");
    const Mesh mesh = loadScene(file.path()).meshes.at(0);
    EXPECT_EQ(mesh.triangleCount(), 3u);
    for (const glm::uvec3& triangle : mesh.triangles) {
        EXPECT_GT(test::triangleCross(mesh, triangle).z, 0.0);
    }
}

/** The triangles' areas (their normals all along +z, else a failure) add up to `area`: a fan of a concave polygon
 *  has triangles turned the other way, outside the outline. */
void expectCoveredWithinOutline(const Mesh& mesh, double area) {
    double sum = 0.0;
    for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::dvec3 cross = test::triangleCross(mesh, triangle);
        EXPECT_GT(cross.z, 0.0) << mesh.name << ": triangle " << triangle.x << " " << triangle.y << " " << triangle.z;
        sum += 0.5 * glm::length(cross);
    }
    EXPECT_NEAR(sum, area, 1e-5 * area) << mesh.name;
}

TEST(ObjLoader, ConcavePolygonsAreCutInsideTheirOutline) {
    // A ten-pointed star and an L-shape as Blender exports n-gons, the L naming vertices defined after it, with
    // texture coordinates that must stay with their corners.
    std::ostringstream obj;
    obj << "o star\n";
    for (int i = 0; i < 10; ++i) {
        const double radius = i % 2 == 0 ? 2.0 : 0.75;
        obj << "v " << radius * std::cos(i * 0.6283185307179586) << ' ' << radius * std::sin(i * 0.6283185307179586)
            << " 0\n";
    }
    obj << "f 1 2 3 4 5 6 7 8 9 10\n";
    obj << "o ell\nf 11/1 12/2 13/3 14/4 15/5 16/6\n";
    for (const char* corner : {"0 0", "3 0", "3 1", "1 1", "1 3", "0 3"}) {
        obj << "v " << corner << " 1\nvt " << corner << "\n";
    }
    const TempFile file("concave.obj", obj.str());
    const Scene scene = loadScene(file.path());
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.meshes[0].triangleCount(), 8u);
    expectCoveredWithinOutline(scene.meshes[0], 10 * 0.5 * 2.0 * 0.75 * std::sin(0.6283185307179586));
    const Mesh& ell = scene.meshes[1];
    EXPECT_EQ(ell.triangleCount(), 4u);
    expectCoveredWithinOutline(ell, 5.0);
    ASSERT_EQ(ell.texcoords[0].size(), ell.positions.size());
    for (std::size_t v = 0; v < ell.positions.size(); ++v) {
        const glm::dvec3 world = scene.origin + glm::dvec3(ell.positions[v]);
        EXPECT_NEAR(ell.texcoords[0][v].x, world.x, 1e-5) << v;
        EXPECT_NEAR(ell.texcoords[0][v].y, 1.0 - world.y, 1e-5) << v;
    }
    EXPECT_TRUE(scene.report.warnings.empty());
}

TEST(ObjLoader, APolygonThatCrossesItselfIsFannedWithAWarning) {
    std::ostringstream obj;
    for (int i = 0; i < 5; ++i) {
        obj << "v " << std::cos(i * 2.5132741228718345) << ' ' << std::sin(i * 2.5132741228718345) << " 0\n";
    }
    obj << "f 1 2 3 4 5\n";
    const TempFile file("pentagram.obj", obj.str());
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.meshes.at(0).triangleCount(), 3u);
    const auto warning = std::find_if(scene.report.warnings.begin(), scene.report.warnings.end(), [](const Warning& w) {
        return w.code == warningCode(WarningKind::PolygonsFanned);
    });
    ASSERT_NE(warning, scene.report.warnings.end());
    EXPECT_EQ(warning->message.rfind("1 polygon crosses itself", 0), 0u) << warning->message;
    EXPECT_EQ(warning->file, file.path());
}

TEST(ObjLoader, ForwardReferencedVerticesAreAccepted) {
    const TempFile file("forward.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 1u);
}

TEST(ObjLoader, NonFiniteCoordinateNamesFileAndLine) {
    const TempFile file("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_EQ(message.rfind("loadScene(): '", 0), 0u) << message;
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
    EXPECT_NE(message.find("non-finite"), std::string::npos) << message;

    const TempFile infinite("inf.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n"); // overflows float
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(infinite.path()); }).find("line 2"), std::string::npos);
}

TEST(ObjLoader, IndexOutOfRangeIsAnErrorWithLine) {
    const TempFile file("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("line 5"), std::string::npos) << message;
    EXPECT_NE(message.find("out of range"), std::string::npos) << message;
    EXPECT_NE(message.find("file has 3 vertices"), std::string::npos) << message;

    const TempFile relative("relative_range.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -4\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(relative.path()); }).find("line 3"), std::string::npos);

    const TempFile normal("normal_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(normal.path()); }).find("normal index 2"), std::string::npos);
}

TEST(ObjLoader, ZeroIndexIsAnError) {
    const TempFile file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("line 4"), std::string::npos) << message;
    EXPECT_NE(message.find("index 0"), std::string::npos) << message;
}

TEST(ObjLoader, MalformedStatementsAreErrors) {
    const TempFile shortVertex("short.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(shortVertex.path()); }).find("line 1"), std::string::npos);
    const TempFile garbage("garbage.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(garbage.path()); }).find("line 4"), std::string::npos);
    const TempFile twoCorners("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(twoCorners.path()); }).find("needs at least 3"),
              std::string::npos);
}

TEST(ObjLoader, EmptyFileOrNoFacesIsAnError) {
    const TempFile empty("empty.obj", "");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(empty.path()); }).find("no triangles"), std::string::npos);
    const TempFile pointsOnly("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(pointsOnly.path()); }).find("no triangles"), std::string::npos);
}

TEST(ObjLoader, MissingFileNamesThePath) {
    const std::string path = (std::filesystem::temp_directory_path() / "inkgraph_no_such_model.obj").string();
    const std::string message = test::sceneErrorMessage([&] { loadScene(path); });
    EXPECT_NE(message.find("not found"), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(ObjLoader, DegenerateTrianglesAreDroppedAndCounted) {
    // Triangle 2 repeats a position under another index (welded into a repeated index); triangle 3 is collinear.
    const TempFile file("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\n"
                                          "f 1 2 3\nf 1 2 4\nf 1 2 5\n");
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.trianglesRead, 3u);
    EXPECT_EQ(scene.report.degenerateDropped, 2u);
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_EQ(scene.vertexCount(), 3u); // the welded duplicate and the unused collinear vertex are gone
    EXPECT_EQ(scene.report.verticesBeforeWeld, 5u);
    EXPECT_EQ(scene.report.verticesAfterWeld, 3u);

    const TempFile allDegenerate("all_degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(allDegenerate.path()); }).find("degenerate"), std::string::npos);
}

TEST(ObjLoader, DetailsSmallerThanTheWeldDistanceAreSaidWhenTheyVanish) {
    // The weld merges corners closer than 1e-6 of the model's size: ten half-unit triangles beside one a million
    // units across vanish (a weld distance of 1.4 units). They were dropped and only counted.
    std::ostringstream obj;
    obj << "v 0 0 0\nv 1000000 0 0\nv 0 1000000 0\nf 1 2 3\n";
    for (int i = 0; i < 10; ++i) {
        obj << "v " << 10 * i << " -10 0\nv " << 10 * i + 0.5 << " -10 0\nv " << 10 * i << " -9.5 0\nf -3 -2 -1\n";
    }
    const TempFile file("details.obj", obj.str());
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.triangleCount(), 1u);
    EXPECT_EQ(scene.report.degenerateDropped, 10u);
    ASSERT_EQ(scene.report.warnings.size(), 1u) << ::testing::PrintToString(scene.report.warnings);
    EXPECT_EQ(scene.report.warnings[0].code, warningCode(WarningKind::DetailsMerged));
    EXPECT_NE(scene.report.warnings[0].message.find("details': 10 of 11 triangles are smaller than the weld "
                                                    "distance (1.4142"),
              std::string::npos)
        << scene.report.warnings[0];
    EXPECT_NE(scene.report.warnings[0].message.find(" units, 1e-06 of the model's size) and were dropped"),
              std::string::npos)
        << scene.report.warnings[0];
    EXPECT_EQ(scene.report.warnings[0].file, file.path());

    // Two unit triangles a million units apart: nothing left, and the message says why.
    const TempFile apart("apart.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1000000 0 0\nv 1000001 0 0\nv 1000000 1 0\n"
                                      "f 1 2 3\nf 4 5 6\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(apart.path()); });
    EXPECT_NE(message.find("all 2 triangles are degenerate (smaller than the weld distance, 1e-06 of the model's "
                           "size: parts far apart for their size? --weld-distance 0 keeps them)"),
              std::string::npos)
        << message;
    // A model whose own triangles are fine says nothing: the bunny below, and every mesh of the other tests.
}

TEST(ObjLoader, StanfordBunnyLoadsWithExactCounts) {
    const std::string path = test::sourcePath("models/bunny_c3d_70k.obj");
    // Its load time is measured by bench/ (BM_LoadBunny), never here.
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.report.format, "obj");
    EXPECT_EQ(scene.report.trianglesRead, 69451u);
    EXPECT_EQ(scene.report.degenerateDropped, 0u);
    EXPECT_EQ(scene.triangleCount(), 69451u);
    EXPECT_EQ(scene.report.verticesBeforeWeld, 35947u);
    // 1,113 of the file's vertices are referenced by no face; no two referenced ones coincide.
    EXPECT_EQ(scene.report.verticesAfterWeld, 34834u);
    EXPECT_EQ(scene.vertexCount(), 34834u);
    EXPECT_TRUE(scene.report.normalsComputed);
    EXPECT_TRUE(scene.report.warnings.empty());
    ASSERT_EQ(scene.meshes.size(), 1u);
    test::expectUnitNormals(scene.meshes[0]);
}

} // namespace
} // namespace inkgraph
