#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace inkgraph {
namespace {

using test::TempFile;

void appendU32(std::string& out, std::uint32_t value) {
    char bytes[4];
    std::memcpy(bytes, &value, 4);
    out.append(bytes, 4);
}

void appendFloat(std::string& out, float value) {
    char bytes[4];
    std::memcpy(bytes, &value, 4);
    out.append(bytes, 4);
}

/** A binary STL of the given triangle soup; facet normals are written as zero, as some exporters do. */
std::string binaryStl(const std::vector<glm::vec3>& soup, std::string header = "inkgraph test") {
    header.resize(80, ' ');
    std::string out = header;
    appendU32(out, std::uint32_t(soup.size() / 3));
    for (std::size_t i = 0; i < soup.size(); i += 3) {
        for (int k = 0; k < 3; ++k) {
            appendFloat(out, 0.0f);
        }
        for (std::size_t corner = i; corner < i + 3; ++corner) {
            appendFloat(out, soup[corner].x);
            appendFloat(out, soup[corner].y);
            appendFloat(out, soup[corner].z);
        }
        out.append(2, '\0');
    }
    return out;
}

std::string asciiStl(const std::vector<glm::vec3>& soup) {
    std::ostringstream out;
    out.precision(9);
    out << "solid cube\n";
    for (std::size_t i = 0; i < soup.size(); i += 3) {
        out << "  facet normal 0 0 0\n    outer loop\n";
        for (std::size_t corner = i; corner < i + 3; ++corner) {
            out << "      vertex " << soup[corner].x << ' ' << soup[corner].y << ' ' << soup[corner].z << '\n';
        }
        out << "    endloop\n  endfacet\n";
    }
    out << "endsolid cube\n";
    return out.str();
}

void expectWeldedCube(const Scene& scene) {
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& mesh = scene.meshes[0];
    EXPECT_EQ(scene.report.trianglesRead, 12u);
    EXPECT_EQ(scene.report.verticesBeforeWeld, 36u);
    EXPECT_EQ(scene.report.verticesAfterWeld, 8u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_TRUE(scene.report.normalsComputed);
    test::expectOutwardWinding(mesh, glm::dvec3(0.0));
    test::expectUnitNormals(mesh);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_GT(glm::dot(mesh.normals[i], mesh.positions[i]), 0.5f);
    }
}

TEST(StlLoader, BinaryCubeWeldsToEightVertices) {
    const TempFile file("cube.stl", binaryStl(test::cubeTriangleSoup()));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "stl-binary");
    expectWeldedCube(scene);
}

TEST(StlLoader, AsciiCubeWeldsToEightVertices) {
    const TempFile file("cube_ascii.STL", asciiStl(test::cubeTriangleSoup())); // extension case does not matter
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "stl-ascii");
    expectWeldedCube(scene);
}

TEST(StlLoader, BinaryWhoseHeaderStartsWithSolidIsStillBinary) {
    const TempFile file("solid_header.stl", binaryStl(test::cubeTriangleSoup(), "solid exported by a binary writer"));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.format, "stl-binary");
    expectWeldedCube(scene);
}

TEST(StlLoader, TruncatedBinaryIsRejectedBeforeAllocating) {
    std::string bytes(80, 'x');
    appendU32(bytes, 1'000'000);
    bytes.resize(200, '\0');
    const TempFile file("truncated.stl", bytes);
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find(file.fileName()), std::string::npos) << message;
    EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    EXPECT_NE(message.find("1000000 triangles"), std::string::npos) << message;
    EXPECT_NE(message.find("200 bytes"), std::string::npos) << message;
}

TEST(StlLoader, TruncatedBinaryWithSolidHeaderReportsBothReadings) {
    std::string bytes = binaryStl(test::cubeTriangleSoup(), "solid but binary");
    bytes.resize(bytes.size() - 30);
    const TempFile file("solid_truncated.stl", bytes);
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("ASCII"), std::string::npos) << message;
    EXPECT_NE(message.find("12 triangles"), std::string::npos) << message;
}

TEST(StlLoader, TrailingBytesAfterBinaryTrianglesAreIgnoredWithAWarning) {
    const TempFile file("padded.stl", binaryStl(test::cubeTriangleSoup()) + std::string(16, '\0'));
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.triangleCount(), 12u);
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_NE(scene.report.warnings[0].message.find("16 bytes"), std::string::npos);
}

TEST(StlLoader, TrailingBytesAfterBinaryWithSolidHeaderAreIgnoredLikeAnyBinary) {
    // The same file loads whether or not its free-form header starts with "solid".
    for (const std::string header : {"inkgraph test", "solid exported by a padding writer"}) {
        SCOPED_TRACE(header);
        const TempFile file("padded_solid.stl", binaryStl(test::cubeTriangleSoup(), header) + std::string(16, '\0'));
        const Scene scene = loadScene(file.path());
        EXPECT_EQ(scene.report.format, "stl-binary");
        expectWeldedCube(scene);
        ASSERT_EQ(scene.report.warnings.size(), 1u);
        EXPECT_NE(scene.report.warnings[0].message.find("16 bytes after the last triangle ignored"), std::string::npos)
            << scene.report.warnings[0];
    }
}

TEST(StlLoader, MalformedAsciiPastTheFirstLineReportsTheAsciiErrorNotABinaryReading) {
    // Long enough for a binary preamble, whose "triangle count" would be text bytes.
    std::string text = asciiStl(test::cubeTriangleSoup());
    const std::size_t typo = text.find("endloop", text.find("endloop") + 1); // the second facet's
    ASSERT_NE(typo, std::string::npos);
    text.replace(typo, 7, "endlop");
    const std::size_t line = std::size_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(typo), '\n')) + 1;
    ASSERT_EQ(line, 14u);
    const TempFile file("typo.stl", text);
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_EQ(message.rfind("loadScene(): '" + file.path() + "' line 14: invalid ASCII STL", 0), 0u) << message;
    EXPECT_NE(message.find("endlop"), std::string::npos) << message;
    EXPECT_EQ(message.find("binary"), std::string::npos) << message;
    EXPECT_EQ(message.find("declares"), std::string::npos) << message;

    // Truncated text: the error is the ASCII one at the last line.
    const std::string cut = asciiStl(test::cubeTriangleSoup()).substr(0, 300);
    const TempFile truncated("cut.stl", cut);
    const std::string cutMessage = test::sceneErrorMessage([&] { loadScene(truncated.path()); });
    EXPECT_NE(cutMessage.find("invalid ASCII STL"), std::string::npos) << cutMessage;
    EXPECT_EQ(cutMessage.find("declares"), std::string::npos) << cutMessage;
}

TEST(StlLoader, NonFiniteCoordinatesAreErrors) {
    std::vector<glm::vec3> soup = test::cubeTriangleSoup();
    soup[7].y = std::nanf("");
    const TempFile binary("nan.stl", binaryStl(soup));
    const std::string binaryMessage = test::sceneErrorMessage([&] { loadScene(binary.path()); });
    EXPECT_NE(binaryMessage.find("non-finite"), std::string::npos) << binaryMessage;
    EXPECT_NE(binaryMessage.find("triangle 2"), std::string::npos) << binaryMessage;

    const TempFile ascii("nan_ascii.stl",
                         "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 inf 0\n"
                         "endloop\nendfacet\nendsolid s\n");
    const std::string asciiMessage = test::sceneErrorMessage([&] { loadScene(ascii.path()); });
    EXPECT_NE(asciiMessage.find("line 6"), std::string::npos) << asciiMessage;
    EXPECT_NE(asciiMessage.find("non-finite"), std::string::npos) << asciiMessage;
}

TEST(StlLoader, AFacetNormalAsTheWindowsRuntimePrintsANaNIsReadAndIgnored) {
    // Old Windows exporters write a degenerate facet's normal as -1.#IND00e+000 or 1.#QNAN0: the normal is not used,
    // so the file loads (it was refused as "cannot read facet normal"); a word that is no number still is not.
    const std::string facets = "solid s\nfacet normal -1.#IND00e+000 1.#QNAN0 1.#INF00\nouter loop\nvertex 0 0 0\n"
                               "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                               "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\n"
                               "endfacet\nendsolid s\n";
    const TempFile file("windows.stl", facets);
    EXPECT_EQ(loadScene(file.path()).triangleCount(), 2u);
    const TempFile word("word.stl", "solid s\nfacet normal 0 up 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                    "vertex 0 1 0\nendloop\nendfacet\nendsolid s\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(word.path()); });
    EXPECT_NE(message.find("line 2: invalid ASCII STL: cannot read facet normal"), std::string::npos) << message;
}

TEST(StlLoader, MalformedAsciiNamesTheLine) {
    const TempFile file("broken.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertx 1 0 0\n");
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_NE(message.find("line 5"), std::string::npos) << message;
    EXPECT_NE(message.find("vertx"), std::string::npos) << message;
}

TEST(StlLoader, EmptyOrTinyFilesAreErrors) {
    const TempFile emptySolid("empty_solid.stl", "solid nothing\nendsolid nothing\n");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(emptySolid.path()); }).find("no triangles"), std::string::npos);
    const TempFile zeroTriangles("zero.stl", binaryStl({}));
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(zeroTriangles.path()); }).find("no triangles"),
              std::string::npos);
    const TempFile tiny("tiny.stl", "abc");
    EXPECT_NE(test::sceneErrorMessage([&] { loadScene(tiny.path()); }).find("not an STL"), std::string::npos);
}

} // namespace
} // namespace inkgraph
