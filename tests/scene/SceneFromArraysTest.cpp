/** @file sceneFromArrays() (scene/MeshArrays.h): the Scene of arrays equals loadScene()'s of the OBJ file with the same
 *  lines, field by field, and bad arrays are refused with messages that name the array and the value. */

#include "scene/MeshArrays.h"
#include "tests/support/MeshArraysFixtures.h"

#include "SceneTestSupport.h"
#include "scene/mesh/Procedural.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace inkgraph {
namespace {

using test::exact;
using test::OwnedArrays;
using test::readObjTriangles;

/** The OBJ file MeshArrays.h says the arrays equal: `o name`, a `v` line per vertex (with its colour), `vn` and `vt`
 *  lines when given, an `f` line per triangle naming the same index for each. */
std::string objOf(const OwnedArrays& mesh) {
    std::ostringstream obj;
    if (!mesh.name.empty()) obj << "o " << mesh.name << '\n';
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        obj << "v " << exact(mesh.positions[3 * v]) << ' ' << exact(mesh.positions[3 * v + 1]) << ' '
            << exact(mesh.positions[3 * v + 2]);
        for (int c = 0; c < mesh.colorChannels; ++c) {
            obj << ' ' << exact(mesh.colors[std::size_t(mesh.colorChannels) * v + std::size_t(c)]);
        }
        obj << '\n';
    }
    for (std::size_t v = 0; v < mesh.normals.size() / 3; ++v) {
        obj << "vn " << exact(mesh.normals[3 * v]) << ' ' << exact(mesh.normals[3 * v + 1]) << ' '
            << exact(mesh.normals[3 * v + 2]) << '\n';
    }
    for (std::size_t v = 0; v < mesh.uvs.size() / 2; ++v) {
        obj << "vt " << exact(mesh.uvs[2 * v]) << ' ' << exact(mesh.uvs[2 * v + 1]) << '\n';
    }
    for (std::size_t t = 0; t < mesh.triangles.size() / 3; ++t) {
        obj << 'f';
        for (std::size_t c = 0; c < 3; ++c) {
            const std::string index = std::to_string(mesh.triangles[3 * t + c] + 1);
            obj << ' ' << index;
            if (!mesh.uvs.empty()) {
                obj << '/' << index;
            } else if (!mesh.normals.empty()) {
                obj << '/';
            }
            if (!mesh.normals.empty()) obj << '/' << index;
        }
        obj << '\n';
    }
    return obj.str();
}

OwnedArrays arraysOf(const Mesh& mesh, bool withNormals) {
    OwnedArrays owned;
    for (const glm::vec3& p : mesh.positions) owned.positions.insert(owned.positions.end(), {p.x, p.y, p.z});
    for (const glm::uvec3& t : mesh.triangles) owned.triangles.insert(owned.triangles.end(), {t.x, t.y, t.z});
    if (withNormals) {
        for (const glm::vec3& n : mesh.normals) owned.normals.insert(owned.normals.end(), {n.x, n.y, n.z});
    }
    return owned;
}

/** The rows of every per-vertex array in a fixed shuffled order (indices renumbered), so the order in which the
 *  triangles first use the vertices is not the rows' order. */
void shuffleVertices(OwnedArrays& mesh) {
    const std::size_t count = mesh.vertexCount();
    std::vector<std::uint32_t> order(count);
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    std::vector<std::uint32_t> rowOf(count);
    for (std::size_t row = 0; row < count; ++row) rowOf[order[row]] = std::uint32_t(row);
    const auto permute = [&](std::vector<float>& values, std::size_t perVertex) {
        if (values.empty()) return;
        std::vector<float> moved(values.size());
        for (std::size_t row = 0; row < count; ++row) {
            std::copy_n(values.begin() + std::ptrdiff_t(perVertex * order[row]), perVertex,
                        moved.begin() + std::ptrdiff_t(perVertex * row));
        }
        values = std::move(moved);
    };
    permute(mesh.positions, 3);
    permute(mesh.normals, 3);
    permute(mesh.uvs, 2);
    permute(mesh.colors, std::size_t(mesh.colorChannels));
    for (std::uint32_t& index : mesh.triangles) index = rowOf[index];
}

/** Equal as the renderer sees them: every mesh field it reads, exactly, and the report's counts. */
void expectSameScene(const Scene& arrays, const Scene& obj) {
    EXPECT_EQ(arrays.origin, obj.origin);
    EXPECT_EQ(arrays.triangleCount(), obj.triangleCount());
    EXPECT_EQ(arrays.vertexCount(), obj.vertexCount());
    ASSERT_EQ(arrays.meshes.size(), obj.meshes.size());
    for (std::size_t m = 0; m < obj.meshes.size(); ++m) {
        const Mesh& a = arrays.meshes[m];
        const Mesh& b = obj.meshes[m];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.nodePath, b.nodePath);
        EXPECT_TRUE(a.positions == b.positions) << "mesh " << m << ": positions differ";
        EXPECT_TRUE(a.normals == b.normals) << "mesh " << m << ": normals differ";
        EXPECT_TRUE(a.triangles == b.triangles) << "mesh " << m << ": triangles differ";
        EXPECT_TRUE(a.texcoords[0] == b.texcoords[0]) << "mesh " << m << ": texture coordinates differ";
        EXPECT_TRUE(a.texcoords[1] == b.texcoords[1]);
        EXPECT_TRUE(a.colors == b.colors) << "mesh " << m << ": colours differ";
        EXPECT_EQ(a.material.name, b.material.name);
        EXPECT_EQ(a.material.baseColorFactor, b.material.baseColorFactor);
        EXPECT_EQ(a.positionsWeldedAt, b.positionsWeldedAt);
        EXPECT_EQ(a.normalsAreSmooth, b.normalsAreSmooth);
    }
    EXPECT_EQ(arrays.report.trianglesRead, obj.report.trianglesRead);
    EXPECT_EQ(arrays.report.degenerateDropped, obj.report.degenerateDropped);
    EXPECT_EQ(arrays.report.verticesBeforeWeld, obj.report.verticesBeforeWeld);
    EXPECT_EQ(arrays.report.verticesAfterWeld, obj.report.verticesAfterWeld);
    EXPECT_EQ(arrays.report.normalsComputed, obj.report.normalsComputed);
    EXPECT_EQ(arrays.report.format, "arrays");
    EXPECT_TRUE(arrays.report.inputFiles.empty());
}

/** sceneFromArrays() against loadScene() of objOf() the same arrays. */
void expectSameAsObj(const OwnedArrays& mesh) {
    const test::TempFile obj("arrays.obj", objOf(mesh));
    expectSameScene(sceneFromArrays(mesh.view()), loadScene(obj.path()));
}

std::string arraysError(const OwnedArrays& mesh, const LoadOptions& options = {}) {
    return test::sceneErrorMessage([&] { sceneFromArrays(mesh.view(), options); });
}

OwnedArrays cube() { return arraysOf(makeCube(glm::vec3(0.0f), 1.0f), false); }

TEST(SceneFromArrays, ARealModelMatchesItsObjFile) {
    // The torus knot's own file (no `o` line: the mesh is named after the file, without a node path).
    const std::string path = test::sourcePath("models/torusknot_open3d.obj");
    OwnedArrays mesh = readObjTriangles(path);
    ASSERT_EQ(mesh.triangles.size() / 3, 2880u);
    mesh.name = "torusknot_open3d";
    const Scene fromArrays = sceneFromArrays(mesh.view());
    Scene fromFile = loadScene(path);
    ASSERT_EQ(fromArrays.meshes.size(), 1u);
    EXPECT_EQ(fromArrays.meshes[0].nodePath, std::vector<std::string>{"torusknot_open3d"});
    fromFile.meshes[0].nodePath = {"torusknot_open3d"}; // what an `o torusknot_open3d` line would add
    expectSameScene(fromArrays, fromFile);
    EXPECT_TRUE(fromArrays.meshes[0].normalsAreSmooth);
    // And the file as objOf() writes it.
    expectSameAsObj(mesh);
}

TEST(SceneFromArrays, WeldingAndSmoothNormalsMatchObj) {
    // The cube's 24 vertices (4 per face) weld to 8 without normals, with smooth normals computed.
    const OwnedArrays mesh = cube();
    const Scene scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.vertexCount(), 8u);
    EXPECT_EQ(scene.report.verticesBeforeWeld, 24u);
    EXPECT_TRUE(scene.report.normalsComputed);
    expectSameAsObj(mesh);
}

TEST(SceneFromArrays, NormalsMatchObjWithVn) {
    // Split normals keep the cube's hard edges: 24 vertices, as given.
    OwnedArrays mesh = arraysOf(makeCube(glm::vec3(0.0f), 1.0f), true);
    shuffleVertices(mesh);
    const Scene scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.vertexCount(), 24u);
    EXPECT_FALSE(scene.report.normalsComputed);
    expectSameAsObj(mesh);
}

TEST(SceneFromArrays, NormalsAndUvsMatchObjWithVnAndVt) {
    OwnedArrays mesh = arraysOf(makeUvSphere(glm::vec3(0.25f, -0.5f, 2.0f), 1.5f, 24, 12), true);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const glm::vec3 n(mesh.normals[3 * v], mesh.normals[3 * v + 1], mesh.normals[3 * v + 2]);
        mesh.uvs.push_back(float(std::atan2(n.y, n.x) / (2.0 * M_PI) + 0.5));
        mesh.uvs.push_back(float(std::acos(std::clamp(n.z, -1.0f, 1.0f)) / M_PI));
    }
    shuffleVertices(mesh);
    mesh.name = "sphere";
    const Scene scene = sceneFromArrays(mesh.view());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& sphere = scene.meshes[0];
    ASSERT_EQ(sphere.texcoords[0].size(), sphere.positions.size());
    // The first triangle's first corner is vertex 0, with v flipped to the top-left origin as OBJ's vt.
    const std::uint32_t first = mesh.triangles[0];
    EXPECT_EQ(sphere.triangles[0].x, 0u);
    EXPECT_EQ(sphere.texcoords[0][0], glm::vec2(mesh.uvs[2 * first], float(1.0 - double(mesh.uvs[2 * first + 1]))));
    expectSameAsObj(mesh);

    OwnedArrays uvsOnly = mesh;
    uvsOnly.normals.clear();
    expectSameAsObj(uvsOnly);
}

TEST(SceneFromArrays, ColoursMatchObjVertexColours) {
    OwnedArrays rgb = cube();
    rgb.colorChannels = 3;
    for (std::size_t v = 0; v < rgb.vertexCount(); ++v) {
        // Out of [0, 1] on some vertices: clamped, as OBJ clamps.
        rgb.colors.insert(rgb.colors.end(), {float(v % 3) * 0.6f, 0.25f, v % 5 == 0 ? -0.5f : 1.0f});
    }
    const Scene scene = sceneFromArrays(rgb.view());
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].material.baseColorFactor, glm::vec4(1.0f));
    ASSERT_FALSE(scene.meshes[0].colors.empty());
    for (const glm::vec4& colour : scene.meshes[0].colors) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(colour, glm::vec4(0.0f))) &&
                    glm::all(glm::lessThanEqual(colour, glm::vec4(1.0f))));
        EXPECT_EQ(colour.a, 1.0f);
    }
    // Said, as OBJ and PLY say it (bytes given as float drew every channel above 1/255 at full strength silently).
    const auto outOfRange = [](const Scene& loaded) {
        std::string messages;
        for (const Warning& warning : loaded.report.warnings)
            if (warning.code == "value-out-of-range") messages += warning.message;
        return messages;
    };
    EXPECT_EQ(outOfRange(scene), "colors: 13 vertex colour components lie outside [0, 1] (as far out as -0.5); "
                                 "clamped into [0, 1]");
    OwnedArrays bytes = cube();
    bytes.colorChannels = 3;
    for (std::size_t v = 0; v < bytes.vertexCount(); ++v)
        bytes.colors.insert(bytes.colors.end(), {255.0f, 128.0f, 0.0f});
    EXPECT_NE(
        outOfRange(sceneFromArrays(bytes.view())).find("as far out as 255; colours of 0 to 255? give them divided"),
        std::string::npos);
    expectSameAsObj(rgb);

    OwnedArrays rgba = cube();
    rgba.colorChannels = 4;
    for (std::size_t v = 0; v < rgba.vertexCount(); ++v) {
        rgba.colors.insert(rgba.colors.end(), {0.5f, float(v) / 24.0f, 0.125f, 0.75f});
    }
    expectSameAsObj(rgba);
}

TEST(SceneFromArrays, DegenerateTrianglesAreDroppedAsObjDropsThem) {
    OwnedArrays mesh = cube();
    mesh.triangles.insert(mesh.triangles.end(), {0, 0, 1}); // a repeated index
    mesh.triangles.insert(mesh.triangles.end(), {0, 1, 1}); // and another
    const Scene scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.report.degenerateDropped, 2u);
    EXPECT_EQ(scene.triangleCount(), 12u);
    expectSameAsObj(mesh);

    OwnedArrays flat;
    flat.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    flat.triangles = {0, 1, 2};
    EXPECT_EQ(arraysError(flat), "sceneFromArrays(): 'arrays': no triangles left: all 1 triangles are degenerate");
}

TEST(SceneFromArrays, AModelFarFromTheOriginIsPlacedAsObjPlacesIt) {
    OwnedArrays mesh = cube();
    for (std::size_t i = 0; i < mesh.positions.size(); i += 3) mesh.positions[i] += 1e7f;
    const Scene scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.origin, glm::dvec3(1e7, 0.0, 0.0));
    expectSameAsObj(mesh);
}

TEST(SceneFromArrays, NamesTheMeshAndItsNodePath) {
    OwnedArrays mesh = cube();
    mesh.name = "box";
    Scene scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.meshes[0].name, "box");
    EXPECT_EQ(scene.meshes[0].nodePath, std::vector<std::string>{"box"});
    mesh.name.clear();
    scene = sceneFromArrays(mesh.view());
    EXPECT_EQ(scene.meshes[0].name, "arrays");
    EXPECT_TRUE(scene.meshes[0].nodePath.empty());
}

TEST(SceneFromArrays, RefusesNonFiniteValuesNamingTheArrayAndTheVertex) {
    OwnedArrays mesh = cube();
    mesh.positions[3 * 5 + 1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(arraysError(mesh), "sceneFromArrays(): 'arrays': vertices: vertex 5: y is not finite (nan)");

    mesh = arraysOf(makeCube(glm::vec3(0.0f), 1.0f), true);
    mesh.name = "box";
    mesh.normals[3 * 2] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(arraysError(mesh), "sceneFromArrays(): 'box': normals: vertex 2: x is not finite (inf)");

    mesh = cube();
    mesh.uvs.assign(2 * mesh.vertexCount(), 0.5f);
    mesh.uvs[2 * 7 + 1] = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(arraysError(mesh), "sceneFromArrays(): 'arrays': uvs: vertex 7: v is not finite (-inf)");

    mesh = cube();
    mesh.colorChannels = 4;
    mesh.colors.assign(4 * mesh.vertexCount(), 1.0f);
    mesh.colors[4 * 3 + 3] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(arraysError(mesh), "sceneFromArrays(): 'arrays': colors: vertex 3: a is not finite (nan)");
}

TEST(SceneFromArrays, RefusesIndicesOutOfRangeNamingTheTriangle) {
    OwnedArrays mesh = cube();
    mesh.triangles[3 * 4 + 2] = 24;
    EXPECT_EQ(arraysError(mesh),
              "sceneFromArrays(): 'arrays': face 4: vertex index 24 out of range (vertices has 24 rows)");
}

TEST(SceneFromArrays, RefusesMissingArraysAndCounts) {
    OwnedArrays mesh = cube();
    MeshArrays arrays = mesh.view();
    arrays.faceCount = 0;
    EXPECT_EQ(test::sceneErrorMessage([&] { sceneFromArrays(arrays); }),
              "sceneFromArrays(): 'arrays': no faces: faceCount is 0");

    arrays = mesh.view();
    arrays.vertices = nullptr;
    EXPECT_EQ(test::sceneErrorMessage([&] { sceneFromArrays(arrays); }),
              "sceneFromArrays(): 'arrays': vertices is null but vertexCount is 24");

    arrays = mesh.view();
    arrays.faces = nullptr;
    EXPECT_EQ(test::sceneErrorMessage([&] { sceneFromArrays(arrays); }),
              "sceneFromArrays(): 'arrays': faces is null but faceCount is 12");

    // Counts no array can hold are refused before any row is read.
    arrays = mesh.view();
    arrays.vertexCount = std::size_t(1) << 33;
    EXPECT_EQ(test::sceneErrorMessage([&] { sceneFromArrays(arrays); }),
              "sceneFromArrays(): 'arrays': vertexCount 8589934592 is more than the 4294967295 vertices 32-bit "
              "indices reach");
    arrays = mesh.view();
    arrays.faceCount = std::numeric_limits<std::size_t>::max() / 6;
    EXPECT_EQ(test::sceneErrorMessage([&] { sceneFromArrays(arrays); }),
              "sceneFromArrays(): 'arrays': faceCount 3074457345618258602 overflows: its 3 indices a face "
              "would need more bytes than memory can address");
}

TEST(SceneFromArrays, RefusesColourChannelsOtherThanThreeOrFour) {
    OwnedArrays mesh = cube();
    mesh.colorChannels = 2;
    mesh.colors.assign(2 * mesh.vertexCount(), 0.5f);
    EXPECT_EQ(arraysError(mesh),
              "sceneFromArrays(): 'arrays': colorChannels is 2; colors need 3 (RGB) or 4 (RGBA) values per vertex");
}

TEST(SceneFromArrays, KeepsToTheMemoryLimit) {
    // The readers' budget: 96 bytes a vertex and 64 a triangle (detail::MeshBudget), checked before any copy.
    const OwnedArrays mesh = arraysOf(makeUvSphere(glm::vec3(0.0f), 1.0f, 512, 512), false);
    LoadOptions options;
    options.memoryLimitBytes = std::size_t(20) << 20;
    EXPECT_EQ(arraysError(mesh, options),
              "sceneFromArrays(): 'arrays': the mesh would need about 55 MiB (261634 vertices, 523264 triangles), "
              "above the memory limit of 20 MiB (LoadOptions::memoryLimitBytes)");
    options.memoryLimitBytes = std::size_t(64) << 20;
    EXPECT_EQ(sceneFromArrays(mesh.view(), options).triangleCount(), 523264u);
}

TEST(SceneFromArrays, RefusesModelsOutsideTheRendersExtent) {
    OwnedArrays huge = cube();
    for (float& coordinate : huge.positions) coordinate *= 1e15f;
    EXPECT_EQ(arraysError(huge),
              "sceneFromArrays(): 'arrays': the model is 3.46e+15 units across (bounding-box diagonal), above the "
              "1e+15 the renderer can hold (float relative to the model's centre); check the units or the node "
              "scales");
    OwnedArrays tiny = cube();
    for (float& coordinate : tiny.positions) coordinate *= 1e-14f;
    EXPECT_NE(arraysError(tiny).find("sceneFromArrays(): 'arrays': the model is 3.46e-14 units across"),
              std::string::npos);
}

TEST(SceneFromArrays, RefusesTheOptionsLoadSceneRefuses) {
    LoadOptions options;
    options.weldTolerance = -1.0;
    try {
        sceneFromArrays(cube().view(), options);
        ADD_FAILURE() << "a negative weld tolerance was taken";
    } catch (const std::invalid_argument& error) {
        EXPECT_EQ(std::string(error.what()).rfind("sceneFromArrays(): weldTolerance must be finite and >= 0", 0), 0u)
            << error.what();
    }
}

} // namespace
} // namespace inkgraph
