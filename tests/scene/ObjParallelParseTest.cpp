// The OBJ reader's parallel parse of positions-and-faces files (issue 20) against its line-by-line parse: the same
// RawScene, or the same error, for every text, with chunks small enough that boundaries fall everywhere, including
// inside lines, between the two halves of a face's relative indices, and on files the parallel parse hands back
// (other statements, colours, slashes, bad lines) to the line-by-line parser.
#include "scene/FormatReaders.h"
#include "scene/Scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

using detail::ObjParallelism;

/** The reader's result or its error message. */
struct Outcome {
    std::optional<detail::RawScene> scene;
    std::string error;
};

Outcome read(const std::string& text, ObjParallelism parallelism, std::size_t memoryLimit) {
    detail::MeshBudget budget("/models/test.obj", memoryLimit);
    Outcome outcome;
    try {
        outcome.scene = detail::readObj("/models/test.obj", text, budget, parallelism);
    } catch (const SceneError& error) {
        outcome.error = error.what();
    }
    return outcome;
}

void expectSameOutcome(const std::string& text, const std::string& what,
                       std::size_t memoryLimit = std::numeric_limits<std::size_t>::max()) {
    const Outcome expected = read(text, {std::numeric_limits<std::size_t>::max(), 1}, memoryLimit);
    for (std::size_t chunkBytes : {std::size_t(1), std::size_t(5), std::size_t(17), std::size_t(64), text.size()}) {
        SCOPED_TRACE(what + ", chunks of " + std::to_string(chunkBytes) + " bytes");
        const Outcome actual = read(text, {0, chunkBytes}, memoryLimit);
        EXPECT_EQ(actual.error, expected.error);
        ASSERT_EQ(actual.scene.has_value(), expected.scene.has_value());
        if (!expected.scene) continue;
        const detail::RawScene &a = *actual.scene, &e = *expected.scene;
        EXPECT_EQ(a.origin, e.origin);
        EXPECT_EQ(a.warnings, e.warnings);
        EXPECT_EQ(a.inputFiles, e.inputFiles);
        ASSERT_EQ(a.meshes.size(), e.meshes.size());
        for (std::size_t mesh = 0; mesh < e.meshes.size(); ++mesh) {
            EXPECT_EQ(a.meshes[mesh].name, e.meshes[mesh].name);
            EXPECT_EQ(a.meshes[mesh].nodePath, e.meshes[mesh].nodePath);
            EXPECT_EQ(a.meshes[mesh].positions, e.meshes[mesh].positions);
            EXPECT_EQ(a.meshes[mesh].triangles, e.meshes[mesh].triangles);
            EXPECT_EQ(a.meshes[mesh].normals, e.meshes[mesh].normals);
            EXPECT_EQ(a.meshes[mesh].texcoords[0], e.meshes[mesh].texcoords[0]);
            EXPECT_EQ(a.meshes[mesh].colors, e.meshes[mesh].colors);
        }
    }
}

/** A bumpy grid as `v` and `f` lines: quads and triangles, absolute and relative indices, comments, `g` and `s`
 *  lines, blank lines and CRLF ends along the way. */
std::string gridObj(int side, bool crlf) {
    std::ostringstream obj;
    obj.precision(9);
    const char* end = crlf ? "\r\n" : "\n";
    obj << "# a grid" << end << "o  " << end << "o grid sheet  " << end << "o later" << end << "g part" << end;
    for (int y = 0; y <= side; ++y)
        for (int x = 0; x <= side; ++x)
            obj << (x % 7 == 3 ? "v\t" : "v ") << x * 0.25 << ' ' << y * -0.5 << "  " << 1e-3 * ((x * y) % 5) << end;
    obj << end << "s 1" << end;
    const auto index = [&](int x, int y) { return y * (side + 1) + x + 1; };
    const int count = (side + 1) * (side + 1);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            if ((x + y) % 3 == 0) {
                obj << "f " << index(x, y) << ' ' << index(x + 1, y) << ' ' << index(x + 1, y + 1) << ' '
                    << index(x, y + 1) << end;
            } else if ((x + y) % 3 == 1) { // relative indices count back from the last vertex
                obj << "f " << index(x, y) - count - 1 << ' ' << index(x + 1, y) - count - 1 << ' '
                    << index(x + 1, y + 1) - count - 1 << end << "f " << index(x, y) << ' ' << index(x + 1, y + 1)
                    << ' ' << index(x, y + 1) << end;
            } else {
                obj << "f  " << index(x, y) << "\t" << index(x + 1, y) << ' ' << index(x + 1, y + 1) << ' '
                    << index(x, y + 1) << ' ' << index(x, y + 1) << end;
            }
            if (x == 0) obj << "# row " << y << end;
        }
    return obj.str();
}

TEST(ObjParallelParse, PositionsAndFacesParseAsLineByLine) {
    expectSameOutcome(gridObj(12, false), "grid");
    expectSameOutcome(gridObj(12, true), "grid, CRLF");
    std::string noFinalBreak = gridObj(5, false);
    noFinalBreak.pop_back();
    expectSameOutcome(noFinalBreak, "no final line break");
    expectSameOutcome("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "byte-order mark");
    expectSameOutcome("v +1 -2 3e-2\nv 1e3 0 0\nv 0 1 +0\nf -3 -2 -1\n", "signs and exponents");
    // Faces before the vertices they name (forward references, legal when the vertices follow).
    expectSameOutcome("f 1 2 3\nf 3 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n", "forward references");
}

TEST(ObjParallelParse, BadLinesGiveTheLineByLineError) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const std::string& bad : {
             std::string("f 1 2\n"),              // too few corners
             std::string("f 1 2 0\n"),            // index 0
             std::string("f 1 2 9\n"),            // out of range (a forward reference never resolved)
             std::string("f 1 2 -9\n"),           // relative, out of range
             std::string("f 1 2 x\n"),            // not a number
             std::string("f 1 2 3x\n"),           // trailing character
             std::string("f 1 2 +3\n"),           // from_chars takes no plus sign for integers
             std::string("f 1 2 99999999999\n"),  // beyond 32 bits
             std::string("v 1 2\n"),              // too few coordinates
             std::string("v 1 2 x\n"),            // not a number
             std::string("v 1 2 1e39\n"),         // beyond float
             std::string("v 1 2 1e999\n"),        // beyond double
             std::string("v 1 2 1e-999\n"),       // underflow: read as 0 by the line-by-line parser
             std::string("v 1 2 nan\n"),          // not finite
             std::string("v\n"),                  // nothing
             std::string("f\n"),                  // nothing
             std::string("v 1 2 3 4\n"),          // w
             std::string("v 1 2 3 0.5 0.5 0.5\n") // a colour
         }) {
        expectSameOutcome(vertices + bad + "f 1 2 3\n", "bad line '" + bad + "'");
        expectSameOutcome(bad + vertices + "f 1 2 3\n", "bad first line '" + bad + "'");
    }
    expectSameOutcome("# nothing but comments\n\n", "no faces");
    expectSameOutcome("v 0 0 0\n", "no faces, one vertex");
    expectSameOutcome("", "empty");
}

TEST(ObjParallelParse, OtherStatementsGoToTheLineByLineParser) {
    const std::string base = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    for (const std::string& extra :
         {std::string("vt 0 0\nf 1/1 2/1 3/1\n"), std::string("vn 0 0 1\nf 1//1 2//1 3//1\n"),
          std::string("usemtl red\nf 1 2 3\n"), std::string("mtllib absent.mtl\nf 1 2 3\n"),
          std::string("l 1 2\nf 1 2 3\n"), std::string("p 1\nf 1 2 3\n"), std::string("f 1/1 2/2 3/3\n")})
        expectSameOutcome(base + "f 2 4 3\n" + extra, "with '" + extra + "'");
}

TEST(ObjParallelParse, MemoryLimitIsNamedAsLineByLine) {
    const std::string text = gridObj(40, false);
    for (std::size_t limit : {std::size_t(1) << 10, std::size_t(200) << 10, std::size_t(2) << 20})
        expectSameOutcome(text, "memory limit " + std::to_string(limit), limit);
}

TEST(ObjParallelParse, FuzzCorpusParsesAsLineByLine) {
    for (const char* folder : {"corpus/obj", "regressions/obj"})
        for (const auto& entry :
             std::filesystem::directory_iterator(std::string(INKGRAPH_SOURCE_ROOT) + "/tests/fuzz/" + folder)) {
            std::ifstream file(entry.path(), std::ios::binary);
            const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
            expectSameOutcome(text, entry.path().filename().string());
        }
    const std::string bunny = [] {
        std::ifstream file(std::string(INKGRAPH_SOURCE_ROOT) + "/models/bunny_c3d_70k.obj", std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    }();
    const Outcome sequential = read(bunny, {std::numeric_limits<std::size_t>::max(), 1}, ~std::size_t(0));
    const Outcome parallel = read(bunny, {0, 1 << 16}, ~std::size_t(0));
    ASSERT_TRUE(sequential.scene && parallel.scene);
    EXPECT_EQ(parallel.scene->meshes.at(0).positions, sequential.scene->meshes.at(0).positions);
    EXPECT_EQ(parallel.scene->meshes.at(0).triangles, sequential.scene->meshes.at(0).triangles);
}

} // namespace
} // namespace inkgraph
