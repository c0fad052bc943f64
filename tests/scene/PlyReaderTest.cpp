// The PLY reader (scene/formats/PlyReader.cpp): the three encodings read alike, polygons fanned, colours and normals,
// unknown elements and properties skipped, and every refusal naming the file and the problem.
#include "scene/Scene.h"

#include "SceneTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <sstream>
#include <tuple>

namespace inkgraph {
namespace {

using test::TempFile;

enum class Encoding { Ascii, LittleEndian, BigEndian };

const char* formatName(Encoding encoding) {
    switch (encoding) {
    case Encoding::Ascii: return "ascii";
    case Encoding::LittleEndian: return "binary_little_endian";
    case Encoding::BigEndian: return "binary_big_endian";
    }
    return "";
}

/** A PLY file written value by value: header lines as given, each value in the encoding as its PLY type says. */
class PlyWriter {
public:
    explicit PlyWriter(Encoding encoding) : mEncoding(encoding) {}

    PlyWriter& header(const std::string& line) {
        mHeader += line + "\n";
        return *this;
    }

    /** One value of PLY type `type` (char, uchar, short, ushort, int, uint, float, double or the sized aliases). */
    PlyWriter& value(const std::string& type, double value) {
        if (mEncoding == Encoding::Ascii) {
            std::ostringstream text;
            text.precision(17);
            text << value;
            mBody += (mRowStarted ? " " : "") + text.str();
            mRowStarted = true;
            return *this;
        }
        if (type == "char" || type == "int8") append(std::int8_t(value));
        if (type == "uchar" || type == "uint8") append(std::uint8_t(value));
        if (type == "short" || type == "int16") append(std::int16_t(value));
        if (type == "ushort" || type == "uint16") append(std::uint16_t(value));
        if (type == "int" || type == "int32") append(std::int32_t(value));
        if (type == "uint" || type == "uint32") append(std::uint32_t(value));
        if (type == "float" || type == "float32") append(float(value));
        if (type == "double" || type == "float64") append(value);
        return *this;
    }

    PlyWriter& values(const std::string& type, std::initializer_list<double> list) {
        for (const double v : list) value(type, v);
        return *this;
    }

    /** Ends an element instance (a line in ASCII). */
    PlyWriter& row() {
        if (mEncoding == Encoding::Ascii) mBody += "\n";
        mRowStarted = false;
        return *this;
    }

    std::string text() const {
        return std::string("ply\nformat ") + formatName(mEncoding) + " 1.0\n" + mHeader + "end_header\n" + mBody;
    }

private:
    template <typename T>
    void append(T value) {
        char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        const bool big = mEncoding == Encoding::BigEndian;
        if (big != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
        mBody.append(bytes, sizeof(T));
    }

    Encoding mEncoding;
    std::string mHeader;
    std::string mBody;
    bool mRowStarted = false;
};

constexpr Encoding kEncodings[] = {Encoding::Ascii, Encoding::LittleEndian, Encoding::BigEndian};

const std::vector<glm::dvec3> kTetrahedron = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<std::vector<int>> kTetrahedronFaces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

/** The tetrahedron with float x y z and a `uchar int vertex_indices` list, the layout most writers use. */
std::string tetrahedron(Encoding encoding) {
    PlyWriter ply(encoding);
    ply.header("comment made by hand").header("obj_info a tetrahedron");
    ply.header("element vertex 4").header("property float x").header("property float y").header("property float z");
    ply.header("element face 4").header("property list uchar int vertex_indices");
    for (const glm::dvec3& p : kTetrahedron) ply.values("float", {p.x, p.y, p.z}).row();
    for (const auto& face : kTetrahedronFaces) {
        ply.value("uchar", double(face.size()));
        for (const int index : face) ply.value("int", index);
        ply.row();
    }
    return ply.text();
}

/** Every triangle of the scene as its three world-space corners, so meshes compare independently of vertex order. */
std::multiset<std::vector<double>> worldTriangles(const Scene& scene) {
    std::multiset<std::vector<double>> triangles;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::uvec3& t : mesh.triangles) {
            std::vector<double> corners;
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 p = scene.origin + glm::dvec3(mesh.positions[t[k]]);
                corners.insert(corners.end(), {p.x, p.y, p.z});
            }
            triangles.insert(corners);
        }
    }
    return triangles;
}

Scene loadPly(const std::string& content, const LoadOptions& options = {}) {
    const TempFile file("model.ply", content);
    return loadScene(file.path(), options);
}

TEST(PlyReader, TheThreeEncodingsGiveTheSameTetrahedron) {
    std::multiset<std::vector<double>> expected;
    for (const auto& face : kTetrahedronFaces) {
        std::vector<double> corners;
        for (const int index : face)
            corners.insert(corners.end(), {kTetrahedron[index].x, kTetrahedron[index].y, kTetrahedron[index].z});
        expected.insert(corners);
    }
    for (const Encoding encoding : kEncodings) {
        const Scene scene = loadPly(tetrahedron(encoding));
        SCOPED_TRACE(formatName(encoding));
        EXPECT_EQ(scene.report.format, encoding == Encoding::Ascii ? "ply-ascii" : "ply-binary");
        ASSERT_EQ(scene.meshes.size(), 1u);
        EXPECT_EQ(scene.triangleCount(), 4u);
        EXPECT_EQ(scene.vertexCount(), 4u);
        EXPECT_EQ(worldTriangles(scene), expected);
        EXPECT_TRUE(scene.meshes[0].colors.empty());
        EXPECT_TRUE(scene.report.warnings.empty()) << scene.report.warnings.front();
    }
}

TEST(PlyReader, EveryTypeNameReadsCoordinatesAndIndices) {
    // x as double, y as int16, z as uchar; the list counted by uint16 with uint32 indices; then every other alias.
    for (const Encoding encoding : kEncodings) {
        PlyWriter ply(encoding);
        ply.header("element vertex 4").header("property double x").header("property int16 y");
        ply.header("property uchar z").header("element face 4").header("property list uint16 uint32 vertex_indices");
        for (const glm::dvec3& p : kTetrahedron) ply.value("double", p.x).value("int16", p.y).value("uchar", p.z).row();
        for (const auto& face : kTetrahedronFaces) {
            ply.value("uint16", 3.0);
            for (const int index : face) ply.value("uint32", index);
            ply.row();
        }
        const Scene scene = loadPly(ply.text());
        EXPECT_EQ(worldTriangles(scene), worldTriangles(loadPly(tetrahedron(encoding)))) << formatName(encoding);
    }
    for (const char* type : {"char", "int8", "uchar", "uint8", "short", "int16", "ushort", "uint16", "int", "int32",
                             "uint", "uint32", "float", "float32", "double", "float64"}) {
        for (const Encoding encoding : kEncodings) {
            PlyWriter ply(encoding);
            ply.header("element vertex 4");
            for (const char* axis : {"x", "y", "z"}) ply.header(std::string("property ") + type + " " + axis);
            ply.header("element face 4")
                .header(std::string("property list uchar ") +
                        (std::string(type).find("float") == std::string::npos && std::string(type) != "double"
                             ? type
                             : "int") +
                        " vertex_indices");
            const bool integerIndices =
                std::string(type).find("float") == std::string::npos && std::string(type) != "double";
            for (const glm::dvec3& p : kTetrahedron) ply.values(type, {p.x, p.y, p.z}).row();
            for (const auto& face : kTetrahedronFaces) {
                ply.value("uchar", 3.0);
                for (const int index : face) ply.value(integerIndices ? type : "int", index);
                ply.row();
            }
            EXPECT_EQ(worldTriangles(loadPly(ply.text())), worldTriangles(loadPly(tetrahedron(encoding))))
                << type << " " << formatName(encoding);
        }
    }
}

TEST(PlyReader, ConvexPolygonsAreFannedIntoNMinusTwoTriangles) {
    // A cube of six quads (12 triangles), and one planar pentagon and hexagon (3 and 4 triangles).
    for (const Encoding encoding : kEncodings) {
        PlyWriter cube(encoding);
        cube.header("element vertex 8").header("property float x").header("property float y");
        cube.header("property float z").header("element face 6").header("property list uchar int vertex_index");
        for (int i = 0; i < 8; ++i) cube.values("float", {double(i & 1), double((i >> 1) & 1), double(i >> 2)}).row();
        for (const auto& quad : std::vector<std::vector<int>>{
                 {0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}) {
            cube.value("uchar", 4);
            for (const int index : quad) cube.value("int", index);
            cube.row();
        }
        const Scene scene = loadPly(cube.text());
        EXPECT_EQ(scene.report.trianglesRead, 12u) << formatName(encoding);
        EXPECT_EQ(scene.triangleCount(), 12u) << formatName(encoding);
        EXPECT_EQ(scene.vertexCount(), 8u) << formatName(encoding);

        PlyWriter polygons(encoding);
        polygons.header("element vertex 11").header("property float x").header("property float y");
        polygons.header("property float z").header("element face 2").header("property list uchar int vertex_indices");
        for (int i = 0; i < 5; ++i) {
            polygons.values("float", {std::cos(i * 2 * M_PI / 5), std::sin(i * 2 * M_PI / 5), 0.0}).row();
        }
        for (int i = 0; i < 6; ++i) {
            polygons.values("float", {std::cos(i * M_PI / 3), 3.0, std::sin(i * M_PI / 3)}).row();
        }
        polygons.value("uchar", 5).values("int", {0, 1, 2, 3, 4}).row();
        polygons.value("uchar", 6).values("int", {5, 6, 7, 8, 9, 10}).row();
        const Scene fanned = loadPly(polygons.text());
        EXPECT_EQ(fanned.triangleCount(), 3u + 4u) << formatName(encoding);
    }
}

/** An L-shape (concave, area 5) and a pentagram (crosses itself) in the z = 0 plane, the faces written before the
 *  vertices or after them. */
std::string concavePolygons(Encoding encoding, bool facesFirst) {
    PlyWriter ply(encoding);
    const auto declareVertices = [&] {
        ply.header("element vertex 11")
            .header("property float x")
            .header("property float y")
            .header("property float z");
    };
    const auto declareFaces = [&] { ply.header("element face 2").header("property list uchar int vertex_indices"); };
    const auto writeVertices = [&] {
        for (const glm::dvec2 corner : {glm::dvec2(0, 0), {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}) {
            ply.values("float", {corner.x, corner.y, 0.0}).row();
        }
        for (int i = 0; i < 5; ++i) {
            ply.values("float", {10.0 + std::cos(i * 4 * M_PI / 5), std::sin(i * 4 * M_PI / 5), 0.0}).row();
        }
    };
    const auto writeFaces = [&] {
        ply.value("uchar", 6).values("int", {0, 1, 2, 3, 4, 5}).row();
        ply.value("uchar", 5).values("int", {6, 7, 8, 9, 10}).row();
    };
    if (facesFirst) {
        declareFaces();
        declareVertices();
        writeFaces();
        writeVertices();
    } else {
        declareVertices();
        declareFaces();
        writeVertices();
        writeFaces();
    }
    return ply.text();
}

TEST(PlyReader, ADoubleFacedCardLoadsAsItsFirstSide) {
    // A square and the same square in reverse: cut from its lowest vertex on, as OBJ's polygons, the reverse gives the
    // first's triangles wound the other way, which the two-sided material drops (from its first corner, the two
    // sheets' diagonals crossed and the card was shaded in black wedges).
    for (const Encoding encoding : kEncodings) {
        PlyWriter card(encoding);
        card.header("element vertex 4").header("property float x").header("property float y");
        card.header("property float z").header("element face 2").header("property list uchar int vertex_indices");
        for (const glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
            card.values("float", {corner.x, corner.y, 0.0}).row();
        for (const auto& face : std::vector<std::vector<int>>{{0, 1, 2, 3}, {3, 2, 1, 0}}) {
            card.value("uchar", 4);
            for (const int index : face) card.value("int", index);
            card.row();
        }
        const Scene scene = loadPly(card.text());
        EXPECT_EQ(scene.triangleCount(), 2u) << formatName(encoding);
        EXPECT_EQ(scene.report.backToBackDropped, 2u) << formatName(encoding);
        for (const glm::vec3& normal : scene.meshes.at(0).normals) EXPECT_EQ(normal, glm::vec3(0, 0, 1));
    }
}

TEST(PlyReader, AConcavePolygonIsCutInsideItsOutlineAndOneThatCrossesItselfWarns) {
    for (const Encoding encoding : kEncodings) {
        const Scene scene = loadPly(concavePolygons(encoding, false));
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        ASSERT_EQ(mesh.triangleCount(), 4u + 3u) << formatName(encoding);
        double lArea = 0.0;
        for (const glm::uvec3& triangle : mesh.triangles) {
            const glm::dvec3 a = scene.origin + glm::dvec3(mesh.positions[triangle.x]);
            const glm::dvec3 b = scene.origin + glm::dvec3(mesh.positions[triangle.y]);
            const glm::dvec3 c = scene.origin + glm::dvec3(mesh.positions[triangle.z]);
            if (a.x < 5.0) { // the L's
                const double cross = glm::cross(b - a, c - a).z;
                EXPECT_GT(cross, 0.0) << formatName(encoding) << ": a triangle outside the L";
                lArea += 0.5 * std::abs(cross);
            }
        }
        EXPECT_NEAR(lArea, 5.0, 1e-6) << formatName(encoding);
        const auto warning =
            std::find_if(scene.report.warnings.begin(), scene.report.warnings.end(),
                         [](const Warning& w) { return w.code == warningCode(WarningKind::PolygonsFanned); });
        ASSERT_NE(warning, scene.report.warnings.end()) << formatName(encoding);
        EXPECT_EQ(warning->message.rfind("1 polygon crosses itself", 0), 0u) << warning->message;
        // Faces before the vertices they name: the same triangles, cut once the positions are read.
        EXPECT_EQ(worldTriangles(loadPly(concavePolygons(encoding, true))), worldTriangles(scene))
            << formatName(encoding);
    }
}

TEST(PlyReader, VertexColoursAndNormalsAreRead) {
    // uchar colours scale by 255, ushort by 65535, floats are as written; alpha is optional.
    for (const Encoding encoding : kEncodings) {
        PlyWriter ply(encoding);
        ply.header("element vertex 4").header("property float x").header("property float y").header("property float z");
        ply.header("property float nx").header("property float ny").header("property float nz");
        ply.header("property uchar red").header("property uchar green").header("property uchar blue");
        ply.header("property uchar alpha");
        ply.header("element face 4").header("property list uchar int vertex_indices");
        const std::vector<std::array<double, 4>> colours = {
            {255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 51}, {255, 255, 255, 255}};
        for (std::size_t i = 0; i < 4; ++i) {
            const glm::dvec3 p = kTetrahedron[i];
            const glm::dvec3 n = p - glm::dvec3(0.25);
            ply.values("float", {p.x, p.y, p.z, n.x, n.y, n.z});
            for (const double c : colours[i]) ply.value("uchar", c);
            ply.row();
        }
        for (const auto& face : kTetrahedronFaces)
            ply.value("uchar", 3).values("int", {double(face[0]), double(face[1]), double(face[2])}).row();
        const Scene scene = loadPly(ply.text());
        SCOPED_TRACE(formatName(encoding));
        ASSERT_EQ(scene.meshes.size(), 1u);
        const Mesh& mesh = scene.meshes[0];
        ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
        EXPECT_EQ(mesh.material.baseColorFactor, glm::vec4(1.0f)); // the colours as written, not 80 % of them
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            const glm::dvec3 world = scene.origin + glm::dvec3(mesh.positions[v]);
            const auto source = std::find(kTetrahedron.begin(), kTetrahedron.end(), world);
            ASSERT_NE(source, kTetrahedron.end());
            const auto& expected = colours[std::size_t(source - kTetrahedron.begin())];
            for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(mesh.colors[v][c], float(expected[c] / 255.0));
            const glm::vec3 normal = glm::normalize(glm::vec3(*source - glm::dvec3(0.25)));
            EXPECT_NEAR(glm::distance(mesh.normals[v], normal), 0.0f, 1e-6f);
        }
    }
    // Float and ushort colours, no alpha.
    PlyWriter ply(Encoding::LittleEndian);
    ply.header("element vertex 4").header("property float x").header("property float y").header("property float z");
    ply.header("property float red").header("property ushort green").header("property float blue");
    ply.header("element face 4").header("property list uchar int vertex_indices");
    for (const glm::dvec3& p : kTetrahedron) {
        ply.values("float", {p.x, p.y, p.z}).value("float", 0.25).value("ushort", 65535).value("float", 7.0).row();
    }
    for (const auto& face : kTetrahedronFaces)
        ply.value("uchar", 3).values("int", {double(face[0]), double(face[1]), double(face[2])}).row();
    const Scene scene = loadPly(ply.text());
    for (const glm::vec4& colour : scene.meshes.at(0).colors) {
        EXPECT_EQ(colour, glm::vec4(0.25f, 1.0f, 1.0f, 1.0f)); // blue 7 clamped to 1, alpha 1
    }
    // Clamped with a word, as the OBJ reader says it (a float property holding 0 to 255 was clamped silently).
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0].code, "value-out-of-range");
    EXPECT_EQ(scene.report.warnings[0].message, "4 vertex colour components lie outside [0, 1] (as far out as 7; "
                                                "colours of 0 to 255 in a float property?); clamped into [0, 1]");
}

TEST(PlyReader, ATextureItCannotReadIsSaid) {
    // MeshLab's textured PLY: a TextureFile comment and per-vertex s, t. Drawn untextured, which was said nowhere.
    PlyWriter ply(Encoding::Ascii);
    ply.header("comment TextureFile scan_0.png");
    ply.header("element vertex 4").header("property float x").header("property float y").header("property float z");
    ply.header("property float s").header("property float t");
    ply.header("element face 4").header("property list uchar int vertex_indices");
    for (const glm::dvec3& p : kTetrahedron) ply.values("float", {p.x, p.y, p.z, 0.5, 0.5}).row();
    for (const auto& face : kTetrahedronFaces)
        ply.value("uchar", 3).values("int", {double(face[0]), double(face[1]), double(face[2])}).row();
    const Scene scene = loadPly(ply.text());
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0].code, "texture-ignored");
    EXPECT_EQ(scene.report.warnings[0].message,
              "texture coordinates and images are not read from PLY (vertex property 's' and the image 'scan_0.png' "
              "(comment TextureFile)): drawn untextured, in its vertex colours or grey (OBJ with MTL or glTF carry a "
              "texture)");
    // A plain PLY says nothing.
    EXPECT_TRUE(loadPly(tetrahedron(Encoding::Ascii)).report.warnings.empty());
}

TEST(PlyReader, UnknownElementsAndPropertiesAreSkipped) {
    // Scalars and lists around the ones read, in the vertex and face elements, and whole elements between them, some
    // of them empty or with no properties at all.
    for (const Encoding encoding : kEncodings) {
        PlyWriter ply(encoding);
        ply.header("element camera 1").header("property float view_px").header("property list uchar float params");
        ply.header("element vertex 4").header("property list uchar int before").header("property float x");
        ply.header("property double confidence").header("property float y").header("property float z");
        ply.header("property list int double after");
        ply.header("element material 2").header("property uchar ambient_red").header("property list short uchar name");
        ply.header("element nothing 1000000");
        ply.header("element none 0").header("property list uint int items");
        ply.header("element face 4").header("property short flags");
        ply.header("property list uchar int vertex_indices").header("property list uchar float texcoord");
        ply.header("property list uchar int vertex_indices"); // a repeated name: skipped
        ply.value("float", 1.5).value("uchar", 2).values("float", {1, 2}).row();
        for (const glm::dvec3& p : kTetrahedron) {
            ply.value("uchar", 2).values("int", {7, 8}).value("float", p.x).value("double", 0.5);
            ply.values("float", {p.y, p.z}).value("int", 1).value("double", -1).row();
        }
        ply.value("uchar", 9).value("short", 0).row();
        ply.value("uchar", 1).value("short", 3).values("uchar", {65, 66, 67}).row();
        for (const auto& face : kTetrahedronFaces) {
            ply.value("short", -4).value("uchar", 3);
            for (const int index : face) ply.value("int", index);
            ply.value("uchar", 6).values("float", {0, 0, 1, 0, 0, 1}).value("uchar", 3).values("int", {0, 0, 0}).row();
        }
        const Scene scene = loadPly(ply.text());
        EXPECT_EQ(worldTriangles(scene), worldTriangles(loadPly(tetrahedron(encoding)))) << formatName(encoding);
        // Only the face's texcoord list is said: the picture lacks what it would give.
        ASSERT_EQ(scene.report.warnings.size(), 1u) << scene.report.warnings.back();
        EXPECT_EQ(scene.report.warnings[0].code, "texture-ignored");
    }
}

TEST(PlyReader, BytesAfterTheLastElementAreAWarning) {
    const Scene binary = loadPly(tetrahedron(Encoding::LittleEndian) + "abc");
    ASSERT_EQ(binary.report.warnings.size(), 1u);
    EXPECT_EQ(binary.report.warnings[0].message, "3 bytes after the last element ignored");
    const Scene ascii = loadPly(tetrahedron(Encoding::Ascii) + "\n\n7 8\n");
    ASSERT_EQ(ascii.report.warnings.size(), 1u);
    EXPECT_EQ(ascii.report.warnings[0].message, "text after the last element ignored (line 22: '7')");
}

TEST(PlyReader, CrLfHeaderLinesAreRead) {
    // Every line ended by CR LF, as Windows tools write it (the body too: ASCII values are whitespace-separated).
    std::string text;
    for (const char c : tetrahedron(Encoding::Ascii)) {
        if (c == '\n') text += '\r';
        text += c;
    }
    EXPECT_EQ(loadPly(text).triangleCount(), 4u);
}

struct Refusal {
    std::string name;
    std::string content;
    std::string problem; ///< the message after "loadScene(): '<path>'"
};

void PrintTo(const Refusal& refusal, std::ostream* out) { *out << refusal.name; }

/** The tetrahedron's header and body as text, to be broken in one place. */
std::string asciiWith(const std::string& header, const std::string& body) {
    return "ply\nformat ascii 1.0\n" + header + "end_header\n" + body;
}

const std::string kHeader = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                            "element face 4\nproperty list uchar int vertex_indices\n";
const std::string kVertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

/** The binary tetrahedron with `bytes` removed from its end. */
std::string binaryCut(std::size_t bytes) {
    const std::string text = tetrahedron(Encoding::LittleEndian);
    return text.substr(0, text.size() - bytes);
}

std::string binaryWithVertex(float x) {
    PlyWriter ply(Encoding::BigEndian);
    ply.header("element vertex 3").header("property float x").header("property float y").header("property float z");
    ply.header("element face 1").header("property list uchar int vertex_indices");
    ply.values("float", {0, 0, 0}).values("float", {1, 0, 0}).value("float", 0).value("float", x).value("float", 0);
    ply.value("uchar", 3).values("int", {0, 1, 2});
    return ply.text();
}

std::vector<Refusal> refusals() {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PlyWriter negativeList(Encoding::LittleEndian);
    negativeList.header("element vertex 3").header("property float x").header("property float y");
    negativeList.header("property float z").header("element face 1").header("property list char int vertex_indices");
    negativeList.values("float", {0, 0, 0, 1, 0, 0, 0, 1, 0}).value("char", -1).values("int", {0, 1, 2});
    PlyWriter nonFiniteNormal(Encoding::LittleEndian);
    nonFiniteNormal.header("element vertex 3").header("property float x").header("property float y");
    nonFiniteNormal.header("property float z").header("property float nx").header("property float ny");
    nonFiniteNormal.header("property float nz").header("element face 1");
    nonFiniteNormal.header("property list uchar int vertex_indices");
    nonFiniteNormal.values("float", {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, nan});
    nonFiniteNormal.value("uchar", 3).values("int", {0, 1, 2});
    return {
        {"BadMagic", "plyx\nformat ascii 1.0\nend_header\n",
         ": not a PLY file: it starts with 'plyx', not the line 'ply'"},
        {"ObjText", "v 0 0 0\n", ": not a PLY file: it starts with 'v 0 0 0', not the line 'ply'"},
        {"Empty", "", ": not a PLY file: it starts with '', not the line 'ply'"},
        {"UnknownFormat", "ply\nformat binary_middle_endian 1.0\n" + kHeader + "end_header\n",
         " line 2: unknown format 'binary_middle_endian' (ascii, binary_little_endian or binary_big_endian)"},
        {"UnknownVersion", "ply\nformat ascii 2.0\n" + kHeader + "end_header\n",
         " line 2: PLY version '2.0' (only 1.0 is read)"},
        {"NoFormat", "ply\n" + kHeader + "end_header\n" + kVertices + kFaces, ": the header has no 'format' line"},
        {"NoEndHeader", "ply\nformat ascii 1.0\n" + kHeader,
         ": the header ends without an 'end_header' line (truncated?)"},
        {"UnknownHeaderLine", asciiWith("elephant 4\n", ""), " line 3: unknown header line 'elephant 4'"},
        {"UnknownType", asciiWith("element vertex 4\nproperty float128 x\n", ""),
         " line 4: unknown property type 'float128' (char, int8, uchar, uint8, short, int16, ushort, uint16, int, "
         "int32, uint, uint32, float, float32, double, float64)"},
        {"PropertyBeforeElement", asciiWith("property float x\n", ""), " line 3: 'property' before any 'element'"},
        {"NegativeElementCount", asciiWith("element vertex -4\n", ""),
         " line 3: element 'vertex' has a negative count -4"},
        {"OverflowingElementCount", asciiWith("element face 18446744073709551616\n", ""),
         " line 3: element 'face' count 18446744073709551616 overflows 64 bits"},
        {"UnreadableElementCount", asciiWith("element face four\n", ""),
         " line 3: cannot read element 'face' count 'four'"},
        {"FloatListCount", asciiWith("element face 1\nproperty list float int vertex_indices\n", ""),
         " line 4: list 'vertex_indices' has a count of type 'float', not an integer type"},
        {"FloatIndices", asciiWith("element face 1\nproperty list uchar float vertex_indices\n", ""),
         " line 4: face list 'vertex_indices' has items of type 'float', not an integer type"},
        {"ScalarIndices", asciiWith("element face 1\nproperty int vertex_indices\n", ""),
         " line 4: face property 'vertex_indices' is not a list"},
        {"SecondVertexElement", asciiWith("element vertex 1\nelement vertex 2\n", ""),
         " line 4: a second 'vertex' element"},
        {"PointCloud", asciiWith("element vertex 4\nproperty float x\nproperty float y\nproperty float z\n", kVertices),
         ": no triangles: the file has no faces (a point cloud of 4 vertices)"},
        {"NoElements", asciiWith("", ""), ": no triangles: the file has no faces"},
        {"NoZ",
         asciiWith("element vertex 4\nproperty float x\nproperty float y\nelement face 1\n"
                   "property list uchar int vertex_indices\n",
                   ""),
         ": element 'vertex' has no property 'z'"},
        {"NoIndexList",
         asciiWith("element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int corners\n",
                   ""),
         ": element 'face' has no list property 'vertex_indices' (or 'vertex_index')"},
        {"AsciiIndexOutOfRange", asciiWith(kHeader, kVertices + "3 0 2 1\n3 0 1 4\n3 0 3 2\n3 1 2 3\n"),
         " line 15: face 1: vertex index 4 out of range (file has 4 vertices)"},
        {"AsciiNegativeIndex", asciiWith(kHeader, kVertices + "3 0 2 -1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
         " line 14: face 0: vertex index -1 out of range (file has 4 vertices)"},
        {"AsciiNegativeListCount", asciiWith(kHeader, kVertices + "-3 0 2 1\n"),
         " line 14: face 0: list 'vertex_indices' has a negative count -3"},
        {"AsciiTwoCorners", asciiWith(kHeader, kVertices + "3 0 2 1\n2 0 1\n"),
         " line 15: face 1 has 2 vertices (needs 3)"},
        {"AsciiNotANumber", asciiWith(kHeader, "0 0 0\n1 zero 0\n0 1 0\n0 0 1\n" + kFaces),
         " line 11: vertex 1: cannot read 'zero' as a number"},
        {"AsciiNotAnInteger", asciiWith(kHeader, kVertices + "3 0 2 1.5\n"),
         " line 14: face 0: cannot read '1.5' as an integer"},
        {"AsciiNaN", asciiWith(kHeader, "0 0 0\n1 nan 0\n0 1 0\n0 0 1\n" + kFaces),
         " line 11: vertex 1: non-finite vertex coordinate (nan)"},
        {"AsciiBeyondFloat", asciiWith(kHeader, "0 0 0\n1 0 0\n0 1e39 0\n0 0 1\n" + kFaces),
         " line 12: vertex 2: non-finite vertex coordinate in float (1e+39 is beyond float's range)"},
        {"AsciiBeyondDouble", asciiWith(kHeader, "0 0 0\n1 0 0\n0 1 0\n0 0 -1e999\n" + kFaces),
         " line 13: vertex 3: non-finite vertex coordinate (-inf)"},
        {"AsciiTruncated", asciiWith(kHeader, kVertices + "3 0 2 1\n3 0"),
         " line 15: truncated: the file ends in face 1 of 4"},
        {"AsciiCountBeyondTheFile", asciiWith(kHeader, "0 0 0\n"),
         " line 10: truncated: element 'vertex' declares 4 instances of 3 values or more, more than the 6 bytes after "
         "the header hold"},
        {"AsciiNulByte", asciiWith(kHeader, kVertices + std::string("3 0 2 1\n3 \0", 11)),
         " line 15: binary data (NUL byte) in an ASCII PLY body (is the file binary?)"},
        {"BinaryTruncatedInFaces", binaryCut(2), ": truncated: the file ends in face 3 of 4"},
        {"BinaryTruncatedInVertices", binaryCut(4 * 13 + 1), ": truncated: the file ends in vertex 3 of 4"},
        {"BinaryIndexOutOfRange",
         [] {
             std::string text = tetrahedron(Encoding::LittleEndian);
             text[text.size() - 4] = 9; // the last face's last index, little-endian
             return text;
         }(),
         ": face 3: vertex index 9 out of range (file has 4 vertices)"},
        {"BinaryNegativeListCount", negativeList.text(), ": face 0: list 'vertex_indices' has a negative count -1"},
        {"BinaryNaN", binaryWithVertex(float(nan)), ": vertex 2: non-finite vertex coordinate (nan)"},
        {"BinaryInfinity", binaryWithVertex(-std::numeric_limits<float>::infinity()),
         ": vertex 2: non-finite vertex coordinate (-inf)"},
        {"BinaryNonFiniteNormal", nonFiniteNormal.text(),
         ": vertex 2, which a face uses: non-finite normal (0, 0, nan)"},
        {"AsciiNonFiniteNormal",
         asciiWith("element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\n"
                   "property float ny\nproperty float nz\nelement face 4\nproperty list uchar int vertex_indices\n",
                   "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 nan 0 1\n0 0 1 0 0 1\n" + kFaces),
         " line 15: vertex 2, which a face uses: non-finite normal (nan, 0, 1)"},
        {"VertexCountBeyondIndices",
         "ply\nformat binary_little_endian 1.0\nelement vertex 4294967296\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
         ": element 'vertex' declares 4294967296 vertices, more than the 4294967295 a mesh can index"},
        {"BinaryCountBeyondTheFile",
         "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" +
             std::string(24, '\0'),
         ": truncated: the file ends in vertex 2 of 1000"},
    };
}

TEST(PlyReader, ANonFiniteNormalOfAVertexNoFaceUsesIsSetAside) {
    // Such a vertex is dropped with its normal; the file was refused for it.
    const std::string header = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                               "property float nx\nproperty float ny\nproperty float nz\nelement face 4\n"
                               "property list uchar int vertex_indices\n";
    const Scene scene =
        loadPly(asciiWith(header, "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0 0 1 0 0 1\n9 9 9 nan inf 1\n" + kFaces));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.vertexCount(), 4u);
    for (const glm::vec3& normal : scene.meshes[0].normals)
        EXPECT_TRUE(std::isfinite(normal.x) && std::isfinite(normal.y) && std::isfinite(normal.z));
}

TEST(PlyReader, BlanksAfterTheMagicWordLeaveItTheMagicWord) {
    for (const std::string magic : {"ply \n", "ply\t\n", "ply  \r\n"})
        EXPECT_EQ(worldTriangles(loadPly(magic + tetrahedron(Encoding::Ascii).substr(4))),
                  worldTriangles(loadPly(tetrahedron(Encoding::Ascii))))
            << magic;
}

TEST(PlyReader, AnUnderflowingCoordinateIsZero) {
    // 1e-400 is below double's range: read as 0, as OBJ reads it, not refused as out of range.
    const Scene scene = loadPly(asciiWith(kHeader, "0 0 1e-400\n1 0 0\n0 1 0\n0 0 1\n" + kFaces));
    EXPECT_EQ(worldTriangles(scene), worldTriangles(loadPly(tetrahedron(Encoding::Ascii))));
}

class PlyRefusal : public testing::TestWithParam<Refusal> {};

TEST_P(PlyRefusal, NamesTheFileAndTheProblem) {
    const TempFile file("bad.ply", GetParam().content);
    const std::string message = test::sceneErrorMessage([&] { loadScene(file.path()); });
    EXPECT_EQ(message, "loadScene(): '" + file.path() + "'" + GetParam().problem);
    // The same bytes from memory, as the fuzz target reads them.
    const std::string fromMemory =
        test::sceneErrorMessage([&] { loadSceneFromMemory("memory.ply", GetParam().content); });
    EXPECT_EQ(fromMemory, "loadScene(): 'memory.ply'" + GetParam().problem);
}

INSTANTIATE_TEST_SUITE_P(PlyReader, PlyRefusal, testing::ValuesIn(refusals()),
                         [](const testing::TestParamInfo<Refusal>& param) { return param.param.name; });

TEST(PlyReader, SkippedListsBeyondTheFileAreTruncation) {
    // An unknown list whose count runs past the end, in both encodings: refused, not read past the buffer.
    const std::string header = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "property list uint uchar skipped\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
    std::string binary = "ply\nformat binary_little_endian 1.0\n" + header;
    binary.append(12, '\0');
    binary.append("\xff\xff\xff\x7f", 4);
    EXPECT_EQ(test::sceneErrorMessage([&] { loadSceneFromMemory("m.ply", binary + std::string(40, '\0')); }),
              "loadScene(): 'm.ply': truncated: the file ends in vertex 0 of 3");
    const std::string ascii = "ply\nformat ascii 1.0\n" + header + "0 0 0 2147483647 1 2 3\n";
    EXPECT_EQ(test::sceneErrorMessage([&] { loadSceneFromMemory("m.ply", ascii); }),
              "loadScene(): 'm.ply' line 12: truncated: the file ends in vertex 0 of 3");
}

TEST(PlyReader, DeclaredCountsAreChargedToTheMemoryLimitBeforeReading) {
    // 100,000 vertices and faces and the file's 1.3 MB need about 16 MiB; with a limit of 4 MiB the header refuses the
    // file, before the body is read (a body as small as the counts allow: zero vertices and empty faces).
    const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 100000\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 100000\n"
                               "property list uchar int vertex_indices\nend_header\n";
    LoadOptions options;
    options.memoryLimitBytes = std::size_t(4) << 20;
    const std::string body(100000 * 12 + 100000, '\0');
    const std::string message =
        test::sceneErrorMessage([&] { loadSceneFromMemory("big.ply", header + body, options); });
    EXPECT_EQ(message.rfind("loadScene(): 'big.ply': the mesh would need about 16 MiB (100000 vertices, 100000 "
                            "triangles), above the memory limit of 4 MiB (--memory-limit)",
                            0),
              0u)
        << message;
    // A body too short for the counts is truncated whatever the limit: raising --memory-limit would not load it.
    EXPECT_EQ(test::sceneErrorMessage([&] { loadSceneFromMemory("big.ply", header + "\1\2\3", options); }),
              "loadScene(): 'big.ply': truncated: the file ends in vertex 0 of 100000");

    // Polygons charge their triangles beyond one per face as they are read: one face of 200,000 corners.
    PlyWriter ply(Encoding::LittleEndian);
    ply.header("element vertex 200000").header("property float x").header("property float y");
    ply.header("property float z").header("element face 1").header("property list int int vertex_indices");
    for (int i = 0; i < 200000; ++i) ply.values("float", {std::cos(i * 1e-5), std::sin(i * 1e-5), 0.0});
    ply.value("int", 200000);
    for (int i = 0; i < 200000; ++i) ply.value("int", i);
    options.memoryLimitBytes = std::size_t(30) << 20; // the file (3.2 MB) and its vertices (19 MB) fit
    const std::string fan = test::sceneErrorMessage([&] { loadSceneFromMemory("fan.ply", ply.text(), options); });
    EXPECT_NE(fan.find("above the memory limit of 30 MiB"), std::string::npos) << fan;
}

TEST(PlyReader, ReferencesNoOtherFile) {
    const TempFile file("tetra.ply", tetrahedron(Encoding::Ascii));
    EXPECT_TRUE(referencedFiles(file.path()).empty());
    const Scene scene = loadScene(file.path());
    EXPECT_EQ(scene.report.inputFiles, std::vector<std::string>{file.path()});
}

TEST(PlyReader, AnAnimationIsAWarning) {
    LoadOptions options;
    options.animation = "walk";
    const TempFile file("tetra.ply", tetrahedron(Encoding::BigEndian));
    const Scene scene = loadScene(file.path(), options);
    ASSERT_EQ(scene.report.warnings.size(), 1u);
    EXPECT_EQ(scene.report.warnings[0].message, "animation 'walk' ignored: ply-binary files have no animations");
}

} // namespace
} // namespace inkgraph
