// Numerical stability at the extremes (docs/stability.md): each case renders through the command line's own
// function (runCommandLine) with every G-buffer field requested, a broad set of line types and --dump, then checks
// that every float intermediate is finite everywhere, that every file the manifest lists exists, and what the case
// itself promises. Small images keep the suite fast on llvmpipe.
#include "render/ImageFiles.h"
#include "app/Cli.h"
#include "app/Render.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/Procedural.h"
#include "tests/scene/SceneTestSupport.h"
#include "tests/support/ImageCompare.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace inkgraph {
namespace {

namespace fs = std::filesystem;

/** Every line type that needs no extra flag, in the CLI's order. */
const std::string kAllLines =
    "outline,silhouette,normal-edge,depth-edge,crease,border,suggestive,contour,mesh-silhouette";
/** The types found in the G-buffer or on the mesh's edges (not drawn by GL at the output size). */
const std::vector<std::string> kImageAndEdgeLines = {"normal-edge", "depth-edge", "crease",         "border",
                                                     "suggestive",  "contour",    "mesh-silhouette"};

std::string readText(const fs::path& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

std::string number(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

/** One OBJ object per mesh: positions times `scale` (in double, then written with 9 significant digits, so a float
 *  that is an exact multiple reads back exactly) and the mesh's normals. `extraFaces` are appended as written. */
void writeObj(const fs::path& path, const std::vector<Mesh>& meshes, double scale = 1.0,
              const std::string& extraFaces = "") {
    std::ofstream file(path);
    std::size_t base = 1;
    for (const Mesh& mesh : meshes) {
        file << "o " << mesh.name << "\n";
        for (const glm::vec3& p : mesh.positions)
            file << "v " << number(p.x * scale) << ' ' << number(p.y * scale) << ' ' << number(p.z * scale) << "\n";
        for (const glm::vec3& n : mesh.normals)
            file << "vn " << number(n.x) << ' ' << number(n.y) << ' ' << number(n.z) << "\n";
        for (const glm::uvec3& t : mesh.triangles) {
            file << "f";
            for (int corner = 0; corner < 3; ++corner) file << ' ' << base + t[corner] << "//" << base + t[corner];
            file << "\n";
        }
        base += mesh.positions.size();
    }
    file << extraFaces;
    if (!file) throw std::runtime_error("writeObj(): cannot write '" + path.string() + "'");
}

/** A square of half-size `halfSize` in the z = 0 plane facing +z, `segments` x `segments` quads. */
Mesh makePlane(float halfSize, int segments, glm::vec3 center = glm::vec3(0.0f)) {
    Mesh mesh;
    mesh.name = "plane";
    for (int row = 0; row <= segments; ++row)
        for (int col = 0; col <= segments; ++col) {
            const float x = -halfSize + 2.0f * halfSize * float(col) / float(segments);
            const float y = -halfSize + 2.0f * halfSize * float(row) / float(segments);
            mesh.positions.push_back(center + glm::vec3(x, y, 0.0f));
            mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
        }
    const auto index = [&](int row, int col) { return std::uint32_t(row * (segments + 1) + col); };
    for (int row = 0; row < segments; ++row)
        for (int col = 0; col < segments; ++col) {
            mesh.triangles.emplace_back(index(row, col), index(row, col + 1), index(row + 1, col + 1));
            mesh.triangles.emplace_back(index(row, col), index(row + 1, col + 1), index(row + 1, col));
        }
    return mesh;
}

/** An axis-aligned box from `low` to `high` with per-face normals (makeCube's layout, stretched). */
Mesh makeBox(glm::vec3 low, glm::vec3 high) {
    Mesh mesh = makeCube(glm::vec3(0.0f), 1.0f);
    mesh.name = "box";
    for (glm::vec3& p : mesh.positions) p = low + (p + 1.0f) * 0.5f * (high - low);
    return mesh;
}

struct RunResult {
    int exitCode = -1;
    std::string err;
};

class Extremes : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        directory = test::testOutputDirectory(std::string("Extremes.") + info->name());
        fs::remove_all(directory);
        fs::create_directories(directory);
    }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(directory);
    }

    /** `inkgraph render ARGS -q` through the CLI's own entry point. */
    RunResult run(std::vector<std::string> arguments) {
        arguments.insert(arguments.begin(), {"inkgraph", "render"});
        arguments.push_back("-q");
        std::vector<const char*> argv;
        for (const std::string& argument : arguments) argv.push_back(argument.c_str());
        std::ostringstream out, err;
        RunResult result;
        result.exitCode = runCommandLine(int(argv.size()), argv.data(), out, err);
        result.err = err.str();
        return result;
    }

    /** Renders MODEL into dump folder `name` with every G-buffer field and `flags`; fails the test on a non-zero
     *  exit. Returns the folder. */
    fs::path render(const fs::path& model, const std::string& name, std::vector<std::string> flags) {
        const fs::path dump = directory / name;
        std::vector<std::string> arguments = {model.string(), "--dump", dump.string(), "--request", "gbuffer.*"};
        arguments.insert(arguments.end(), flags.begin(), flags.end());
        const RunResult result = run(arguments);
        EXPECT_EQ(result.exitCode, kExitOk) << name << ": " << result.err;
        return dump;
    }

    /** Every file the manifest lists, read back; each must exist, and every float image must be finite everywhere
     *  (cv::checkRange rejects NaN and both infinities). */
    std::map<std::string, cv::Mat> readDump(const fs::path& dump) {
        std::map<std::string, cv::Mat> files;
        const fs::path manifestPath = dump / "manifest.json";
        if (!fs::exists(manifestPath)) {
            ADD_FAILURE() << "no manifest in " << dump;
            return files;
        }
        const auto manifest = nlohmann::json::parse(readText(manifestPath));
        for (const auto& entry : manifest["files"]) {
            const std::string name = entry["file"];
            if (!fs::exists(dump / name)) {
                ADD_FAILURE() << dump.filename() << ": '" << name << "' is listed but missing";
                continue;
            }
            cv::Mat image = readImage(dump / name);
            if (image.depth() == CV_32F) {
                cv::Point where;
                EXPECT_TRUE(cv::checkRange(image, true, &where))
                    << dump.filename() << "/" << name << ": NaN or Inf at column " << where.x << ", row " << where.y;
            }
            files[name] = image;
        }
        for (const char* required : {"depth.exr", "normal.exr", "w.exr", "radial.exr", "coverage.png"})
            EXPECT_TRUE(files.count(required)) << dump.filename() << ": " << required << " not dumped";
        return files;
    }

    nlohmann::json manifestOf(const fs::path& dump) { return nlohmann::json::parse(readText(dump / "manifest.json")); }

    fs::path directory;
};

/** Pixels at least `margin` pixels inside the coverage: where no outline of the model's own can reach. */
cv::Mat interiorOf(const cv::Mat& coverage, int margin) {
    cv::Mat interior;
    cv::erode(coverage > 0, interior, cv::getStructuringElement(cv::MORPH_RECT, {2 * margin + 1, 2 * margin + 1}),
              {-1, -1}, 1, cv::BORDER_CONSTANT, 0);
    return interior;
}

int countInside(const cv::Mat& lines, const cv::Mat& zone) { return cv::countNonZero((lines > 0) & zone); }

/** Number of pixels where two 8-bit images differ, and a message listing the first few. */
int differingPixels(const cv::Mat& a, const cv::Mat& b) {
    if (a.size() != b.size() || a.type() != b.type()) return -1;
    cv::Mat difference;
    cv::absdiff(a, b, difference);
    return cv::countNonZero(difference.reshape(1) != 0);
}

// --- NaN and Inf in model files -----------------------------------------------------------------------------------

TEST_F(Extremes, NonFinitePositionsAndNormalsAreRejectedInEveryFormat) {
    const std::vector<glm::vec3> soup = test::cubeTriangleSoup();
    auto soupWith = [&](float bad) {
        std::vector<glm::vec3> copy = soup;
        copy[7].y = bad;
        return copy;
    };
    auto binaryStl = [](const std::vector<glm::vec3>& corners) {
        std::string out(80, ' ');
        const auto u32 = std::uint32_t(corners.size() / 3);
        out.append(reinterpret_cast<const char*>(&u32), 4); // little-endian test machines
        for (std::size_t i = 0; i < corners.size(); i += 3) {
            const float zero[3] = {0.0f, 0.0f, 0.0f};
            out.append(reinterpret_cast<const char*>(zero), 12);
            out.append(reinterpret_cast<const char*>(&corners[i]), 36);
            out.append(2, '\0');
        }
        return out;
    };
    auto gltf = [](const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals) {
        test::GltfWriter writer;
        const int p = writer.addVec3(positions);
        const int n = writer.addVec3(normals);
        return writer.gltf("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                           ", \"NORMAL\": " + std::to_string(n) +
                           "}}]}], \"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0");
    };
    const float nan = std::nanf("");
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<glm::vec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<glm::vec3> up = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    const std::string okTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"nan_position.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"},
        {"inf_position.obj", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n"},
        {"overflow_position.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n"}, // beyond float: infinity
        {"nan_normal.obj", okTriangle + "vn nan 0 1\nf 1//1 2//2 3//1\n"},
        {"nan_position.stl", binaryStl(soupWith(nan))},
        {"inf_position.stl", binaryStl(soupWith(inf))},
        {"nan_ascii.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 NaN 0\n"
                          "endloop\nendfacet\nendsolid s\n"},
        {"inf_ascii.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 inf 0\n"
                          "endloop\nendfacet\nendsolid s\n"},
        {"nan_position.gltf", gltf({{0, 0, 0}, {1, nan, 0}, {0, 1, 0}}, up)},
        {"inf_position.gltf", gltf({{0, 0, 0}, {1, 0, -inf}, {0, 1, 0}}, up)},
        {"nan_normal.gltf", gltf(triangle, {{0, 0, 1}, {nan, 0, 1}, {0, 0, 1}})},
    };
    for (const auto& [name, content] : cases) {
        const fs::path model = directory / name;
        std::ofstream(model, std::ios::binary) << content;
        const RunResult result = run({model.string(), "-o", (directory / "out.png").string(), "--size", "16x16"});
        EXPECT_EQ(result.exitCode, kExitBadInput) << name << ": " << result.err;
        EXPECT_NE(result.err.find("'" + model.string() + "'"), std::string::npos) << name << ": " << result.err;
        EXPECT_NE(result.err.find("non-finite"), std::string::npos) << name << ": " << result.err;
        EXPECT_FALSE(fs::exists(directory / "out.png")) << name << ": a failed run wrote its output";
    }
}

TEST_F(Extremes, NonFiniteDataTheRendererDoesNotUseIsIgnored) {
    // A non-finite OBJ texture coordinate reads as (0, 0) with a warning, and STL facet normals are never read (smooth
    // normals are computed), so NaN there cannot reach a buffer: the model renders, finite.
    const fs::path obj = directory / "nan_texcoord.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan inf\nvt 0 0\nf 1/1 2/2 3/1\n";
    readDump(render(obj, "obj", {"--size", "32x32", "--lines", "contour,depth-edge"}));
    const fs::path stl = directory / "nan_facet_normal.stl";
    std::ofstream(stl) << "solid s\nfacet normal nan inf -inf\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                          "endloop\nendfacet\nendsolid s\n";
    readDump(render(stl, "stl", {"--size", "32x32", "--lines", "contour,depth-edge"}));
}

// --- Degenerate and zero-area triangles ---------------------------------------------------------------------------

TEST_F(Extremes, DegenerateTrianglesChangeNothing) {
    // A smooth sphere (suggestive and contour lines) next to a hard-edged cube (creases), with exact normals.
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 48, 24);
    sphere.name = "sphere";
    Mesh cube = makeCube({2.2f, 0.0f, 0.0f}, 0.7f);
    cube.name = "cube";
    const fs::path clean = directory / "clean.obj";
    writeObj(clean, {sphere, cube});
    // Appended faces, every one of zero area: repeated indices; a spike out of the sphere's pole (0, 0, 1) through
    // (0, 0, 1.5) and (0, 0, 2), exactly collinear, which would stretch the bounds, the hull and the outline if it
    // survived; a copy of a cube corner under a new index (welding makes the index repeat); a triangle whose three
    // corners are one point.
    const std::size_t poleIndex = 1; // makeUvSphere's first vertex is the pole at polar angle 0
    ASSERT_EQ(sphere.positions[poleIndex - 1], glm::vec3(0.0f, 0.0f, 1.0f));
    const std::size_t next = sphere.positions.size() + cube.positions.size() + 1;
    const glm::vec3 corner = cube.positions[0];
    // Every face names normals (vertex i has normal i), as the clean file's do: one face without would make the
    // loader recompute every normal.
    auto face = [](std::size_t a, std::size_t b, std::size_t c) {
        return "f " + std::to_string(a) + "//" + std::to_string(a) + " " + std::to_string(b) + "//" +
               std::to_string(b) + " " + std::to_string(c) + "//" + std::to_string(c) + "\n";
    };
    std::ostringstream extra;
    extra << "o degenerate\n"
          << "v 0 0 1.5\nv 0 0 2\n"
          << "v " << number(corner.x) << ' ' << number(corner.y) << ' ' << number(corner.z) << "\n"
          << "v 0.25 0.5 0.75\n"
          << "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n"
          << face(5, 5, 6) << face(7, 8, 7)                                           // repeated indices
          << face(poleIndex, next, next + 1)                                          // collinear spike
          << face(sphere.positions.size() + 1, sphere.positions.size() + 2, next + 2) // two corners at one point
          << face(next + 3, next + 3, next + 3);                                      // a point
    const fs::path dirty = directory / "degenerate.obj";
    writeObj(dirty, {sphere, cube}, 1.0, extra.str());

    const std::vector<std::string> flags = {"--size", "160x96", "--lines", kAllLines, "--shading", "phong"};
    const auto reference = readDump(render(clean, "clean", flags));
    std::vector<std::string> withStats = flags;
    withStats.insert(withStats.end(), {"--stats", (directory / "stats.json").string()});
    const auto degenerate = readDump(render(dirty, "degenerate", withStats));
    const auto stats = nlohmann::json::parse(readText(directory / "stats.json"));
    EXPECT_EQ(stats["scene"]["degenerate_dropped"], 5);

    // Every buffer the same to the bit: the loader drops the zero-area faces and the vertices only they used, so the
    // renderer sees the clean mesh.
    ASSERT_EQ(reference.size(), degenerate.size());
    for (const auto& [name, image] : reference) {
        ASSERT_TRUE(degenerate.count(name)) << name;
        EXPECT_TRUE(test::imagesNear(degenerate.at(name), image, {0.0, 0.0, 0.0}, "Extremes.Degenerate", name)) << name;
    }
}

TEST_F(Extremes, DegenerateTrianglesGiveFiniteNormalsHullOffsetsAndAdjacency) {
    // The same mesh operations on a mesh that was not cleaned by a loader (an in-memory scene): zero-area faces add
    // nothing and produce no NaN.
    Mesh mesh = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 16, 8);
    const auto count = std::uint32_t(mesh.positions.size());
    mesh.positions.push_back({0.0f, 0.0f, 1.5f});
    mesh.positions.push_back({0.0f, 0.0f, 2.0f});
    mesh.positions.push_back(mesh.positions[5]);
    mesh.triangles.emplace_back(0, count, count + 1); // collinear
    mesh.triangles.emplace_back(3, 3, 4);             // repeated index
    mesh.triangles.emplace_back(5, count + 2, 6);     // two corners at one position
    mesh.triangles.emplace_back(count + 2, count + 2, count + 2);
    auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (const glm::vec3& n : computeSmoothNormals(mesh.positions, mesh.triangles)) {
        ASSERT_TRUE(finite(n));
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
    for (const glm::vec3& n : computePositionWeldedNormals(mesh.positions, mesh.triangles, 1e-6)) {
        ASSERT_TRUE(finite(n));
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    }
    EXPECT_EQ(degenerateTriangles(mesh.positions, mesh.triangles, 0.0).size(), 4u);
}

// --- Model scale ------------------------------------------------------------------------------------------------

/** The fandisk (creases, smooth patches, suggestive contours) with its positions times `scale`. */
fs::path scaledFandisk(const fs::path& folder, double scale) {
    const Scene scene = loadScene((test::sourceRoot() / "models" / "fandisk_c3d.obj").string());
    const fs::path path = folder / ("fandisk_" + number(scale) + ".obj");
    writeObj(path, scene.meshes, scale);
    return path;
}

const std::vector<std::string> kScaleFlags = {"--size", "128x128", "--lines", kAllLines, "--shading", "phong"};

TEST_F(Extremes, ExactScalesFrom1em9To1e12GiveIdenticalPictures) {
    // Powers of two scale every float exactly, so a renderer with no absolute length anywhere gives the same bits:
    // 2^-13 ~ 1.2e-4 and 2^17 ~ 1.3e5 (the range), and 2^-30 ~ 9e-10 and 2^40 ~ 1.1e12 beyond it.
    const auto reference = readDump(render(scaledFandisk(directory, 1.0), "scale1", kScaleFlags));
    for (const int exponent : {-13, 17, -30, 40}) {
        const double scale = std::ldexp(1.0, exponent);
        const std::string name = "scale2^" + std::to_string(exponent);
        const auto scaled = readDump(render(scaledFandisk(directory, scale), name, kScaleFlags));
        for (const auto& [file, image] : reference) {
            if (!scaled.count(file)) {
                ADD_FAILURE() << name << ": " << file << " missing";
                continue;
            }
            const cv::Mat& other = scaled.at(file);
            if (image.depth() == CV_8U) {
                EXPECT_EQ(differingPixels(other, image), 0) << name << ": " << file;
            } else if (file == "depth.exr") {
                // Linear depth is a length: exactly the scale times the reference.
                EXPECT_EQ(cv::norm(other, image * scale, cv::NORM_INF), 0.0) << name;
            } else if (file != "radial.exr") {
                // Normals, view and w vectors and n.v are directions: identical.
                EXPECT_EQ(cv::norm(other, image, cv::NORM_INF), 0.0) << name << ": " << file;
            }
        }
    }
}

TEST_F(Extremes, DecimalScalesGiveTheSameLinesUpToRounding) {
    // 1e-4 and 1e5 are not exact in binary: every coordinate rounds differently (relative 6e-8), so rasterisation
    // ties may flip. Measured: every mask equal except the suggestive contours, whose strength (a second difference
    // of n.v, thresholded) moves by as much when the model is scaled by 1 + 1e-7, shown here as the control.
    const auto reference = readDump(render(scaledFandisk(directory, 1.0), "scale1", kScaleFlags));
    const auto control = readDump(render(scaledFandisk(directory, 1.0 + 1e-7), "control", kScaleFlags));
    for (const double scale : {1e-4, 1e5}) {
        const std::string name = "scale" + number(scale);
        const auto scaled = readDump(render(scaledFandisk(directory, scale), name, kScaleFlags));
        for (const std::string& type : kImageAndEdgeLines) {
            const std::string file = "lines-" + type + ".png";
            ASSERT_TRUE(scaled.count(file) && reference.count(file)) << file;
            const int differing = differingPixels(scaled.at(file), reference.at(file));
            if (type != "suggestive") {
                EXPECT_EQ(differing, 0) << name << ": " << file;
                continue;
            }
            // Suggestive: the summed coverage difference stays below a quarter of the lines' own coverage, and no
            // differing pixel lies more than 2 px from a line of the reference (lines flicker, none appears).
            const cv::Mat& lines = reference.at(file);
            cv::Mat difference;
            cv::absdiff(scaled.at(file), lines, difference);
            EXPECT_LE(cv::sum(difference)[0], 0.25 * cv::sum(lines)[0]) << name;
            cv::Mat near;
            cv::dilate(lines > 0, near, cv::getStructuringElement(cv::MORPH_RECT, {5, 5}));
            EXPECT_EQ(cv::countNonZero((difference > 0) & ~near), 0) << name;
            RecordProperty("suggestive_pixels_differing_" + name, differing);
        }
        EXPECT_EQ(differingPixels(scaled.at("coverage.png"), reference.at("coverage.png")), 0) << name;
    }
    RecordProperty("suggestive_pixels_differing_control",
                   differingPixels(control.at("lines-suggestive.png"), reference.at("lines-suggestive.png")));
}

// --- Grazing views and w -> 0 -------------------------------------------------------------------------------------

TEST_F(Extremes, PlaneAndCubeSeenAt89_9DegreesFromTheirNormal) {
    const double angle = glm::radians(89.9);
    const fs::path plane = directory / "plane.obj";
    writeObj(plane, {makePlane(1.0f, 32)});
    // The plane z = 0 from 89.9 degrees off its normal: a sliver one or two pixels high across the picture.
    const std::string eye = number(0.0) + "," + number(-4.0 * std::sin(angle)) + "," + number(4.0 * std::cos(angle));
    const auto planeDump = readDump(render(plane, "plane",
                                           {"--size", "128x128", "--eye", eye, "--target", "0,0,0", "--up", "0,0,1",
                                            "--lines", kAllLines, "--shading", "phong"}));
    // Its depth extent projects to 2 sin(0.1 deg) f / 4 = 0.18 px: at most one row of pixel centres is covered.
    EXPECT_LE(cv::countNonZero(planeDump.at("coverage.png")), 128);
    // A plane has no suggestive contours, creases, mesh silhouette or normal edges, whatever the angle.
    for (const char* file :
         {"lines-suggestive.png", "lines-crease.png", "lines-mesh-silhouette.png", "lines-normal-edge.png"})
        EXPECT_EQ(cv::countNonZero(planeDump.at(file)), 0) << file;

    // A cube whose top face is seen at 89.9 degrees and whose front face is seen head on (w -> 0 there).
    const fs::path cube = directory / "cube.obj";
    writeObj(cube, {makeCube({0.0f, 0.0f, 0.0f}, 1.0f)});
    const std::string cubeEye = "0," + number(1.0 + 5.0 * std::cos(angle)) + "," + number(1.0 + 5.0 * std::sin(angle));
    const auto cubeDump = readDump(render(
        cube, "cube",
        {"--size", "128x128", "--eye", cubeEye, "--target", "0,1,1", "--lines", kAllLines, "--shading", "comic"}));
    // Inside the front face (3 px from every edge of the coverage) no line of any type: the grazing top face above it
    // makes no depth-edge, normal-edge or contour false positive, and w ~ 0 makes no suggestive contour.
    const cv::Mat interior = interiorOf(cubeDump.at("coverage.png"), 4);
    ASSERT_GT(cv::countNonZero(interior), 1000);
    for (const std::string& type : kImageAndEdgeLines)
        EXPECT_EQ(countInside(cubeDump.at("lines-" + type + ".png"), interior), 0) << type;
}

TEST_F(Extremes, FrontalPlaneHasNoSuggestiveContoursAndAFiniteW) {
    // The eye on the plane's normal through its centre: v is parallel to n there, so w = 0 exactly at the centre
    // pixel and normalize(w) would be NaN.
    const fs::path plane = directory / "plane.obj";
    writeObj(plane, {makePlane(1.0f, 16)});
    const auto dump = readDump(render(
        plane, "frontal",
        {"--size", "129x129", "--eye", "0,0,3", "--target", "0,0,0", "--lines", kAllLines, "--shading", "phong"}));
    const cv::Vec4f w = dump.at("w.exr").at<cv::Vec4f>(64, 64);
    EXPECT_LT(std::hypot(w[0], w[1], w[2]), 1e-3f);
    EXPECT_EQ(cv::countNonZero(dump.at("lines-suggestive.png")), 0);
    const cv::Mat interior = interiorOf(dump.at("coverage.png"), 4);
    ASSERT_GT(cv::countNonZero(interior), 2000);
    for (const std::string& type : kImageAndEdgeLines)
        EXPECT_EQ(countInside(dump.at("lines-" + type + ".png"), interior), 0) << type;
}

TEST_F(Extremes, SphereRimIsFiniteAndItsContourIsOnePixelWide) {
    // A finely tessellated sphere: n.v -> 0 at the rim, where contours and suggestive contours are decided.
    const fs::path sphere = directory / "sphere.obj";
    writeObj(sphere, {makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 128, 64)});
    const fs::path statsPath = directory / "stats.json";
    const auto dump = readDump(render(sphere, "sphere",
                                      {"--size", "128x128", "--eye", "0,0,4", "--target", "0,0,0", "--fov", "35",
                                       "--lines", kAllLines, "--stats", statsPath.string()}));
    EXPECT_EQ(cv::countNonZero(dump.at("lines-suggestive.png")), 0) << "a sphere has no suggestive contours";
    // The contour skeleton is one pixel wide: a closed digital curve around a disc of radius rho has between
    // 4 sqrt(2) rho (8-connected: rho / sqrt(2) pixels per octant) and 8 rho (4-connected) pixels; a band two pixels
    // wide would have about 11 rho or more.
    const double focal = 64.0 / std::tan(glm::radians(17.5));
    const double rho = focal * 1.0 / std::sqrt(16.0 - 1.0);
    const auto stats = nlohmann::json::parse(readText(statsPath));
    double skeleton = -1.0;
    for (const auto& layer : stats["post_stage"]["lines"])
        if (layer["type"] == "contour") skeleton = layer["skeleton_pixels"];
    EXPECT_GE(skeleton, 0.95 * 4.0 * std::sqrt(2.0) * rho);
    EXPECT_LE(skeleton, 1.03 * 8.0 * rho);
}

// --- Shininess 0 and 1e6 ------------------------------------------------------------------------------------------

TEST_F(Extremes, ShininessZeroAndAMillionInPhongAndComic) {
    const fs::path sphere = directory / "sphere.obj";
    writeObj(sphere, {makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 96, 48)});
    // A 2 x 2 comic map: bottom row (no highlight) black, top row (full highlight) white, so the shading says which
    // row every pixel used: t = max(r.v, 0)^n, the top row from t = 0.5 up. (White times the grey base colour 0.8 is
    // 231 in sRGB; black stays 0.)
    const fs::path map = directory / "map.png";
    cv::Mat mapImage(2, 2, CV_8UC4, cv::Scalar(255, 255, 255, 255));
    mapImage.row(1).setTo(cv::Scalar(0, 0, 0, 255));
    writeImage(map, mapImage);
    const std::vector<std::string> view = {"--size",   "96x96", "--eye",   "0,0,4",
                                           "--target", "0,0,0", "--light", "0.3,0.4,1"};
    auto flags = [&](std::vector<std::string> more) {
        more.insert(more.begin(), view.begin(), view.end());
        return more;
    };
    const auto lambert = readDump(render(sphere, "lambert", flags({"--shading", "lambert"})));
    const cv::Mat lit = lambert.at("coverage.png") > 0;
    for (const char* shininess : {"0", "1e6"}) {
        const auto phong = readDump(
            render(sphere, std::string("phong") + shininess, flags({"--shading", "phong", "--shininess", shininess})));
        const auto comic = readDump(render(sphere, std::string("comic") + shininess,
                                           flags({"--shading", "comic", "--shininess", shininess, "--shademap",
                                                  map.string(), "--lines", "suggestive,contour"})));
        cv::Mat comicGrey;
        cv::extractChannel(comic.at("shading.png"), comicGrey, 0);
        // Lit pixels: n.l > 0 where lambert is brighter than its ambient floor.
        cv::Mat lambertGrey, phongGrey;
        cv::extractChannel(lambert.at("shading.png"), lambertGrey, 0);
        cv::extractChannel(phong.at("shading.png"), phongGrey, 0);
        double ambientLevel = 0.0;
        cv::minMaxLoc(lambertGrey, &ambientLevel, nullptr, nullptr, nullptr, lit);
        const cv::Mat litByLight = lit & (lambertGrey > ambientLevel + 2);
        ASSERT_GT(cv::countNonZero(litByLight), 2000);
        if (std::string(shininess) == "0") {
            // n = 0: the specular term is 1 on every lit pixel (C's pow(0, 0) = 1 at r.v = 0 too), so comic reads
            // the top (white) row everywhere n.l > 0, and phong adds the same constant to lambert there.
            EXPECT_EQ(cv::countNonZero(litByLight & (comicGrey < 200)), 0);
            cv::Mat phongAboveLambert;
            cv::subtract(phongGrey, lambertGrey, phongAboveLambert, litByLight, CV_16S);
            double lowest = 0.0;
            cv::minMaxLoc(phongAboveLambert, &lowest, nullptr, nullptr, nullptr, litByLight);
            EXPECT_GT(lowest, 20) << "a uniform specular term on every lit pixel";
        } else {
            // n = 1e6: the highlight is a cone of 0.07 degrees, below a pixel: at most a couple of pixels reach the
            // top row or differ from lambert by more than 8-bit rounding.
            EXPECT_LE(cv::countNonZero(comicGrey > 100), 2);
            cv::Mat difference;
            cv::absdiff(phongGrey, lambertGrey, difference);
            EXPECT_LE(cv::countNonZero(difference > 1), 2);
        }
    }
}

// --- Camera inside the model and on its bounding sphere -----------------------------------------------------------

TEST_F(Extremes, CameraInsideTheModel) {
    // A room (a large sphere seen from inside) holding a small sphere: outline and silhouette would flood the
    // picture with the room's back faces, so they draw nothing; the image-space lines still outline the small one.
    Mesh room = makeUvSphere({0.0f, 0.0f, 0.0f}, 10.0f, 64, 32);
    room.name = "room";
    Mesh ball = makeUvSphere({0.0f, 0.0f, -4.0f}, 1.0f, 64, 32);
    ball.name = "ball";
    const fs::path model = directory / "room.obj";
    writeObj(model, {room, ball});
    const fs::path statsPath = directory / "stats.json";
    const fs::path dump = render(model, "inside",
                                 {"--size", "128x128", "--eye", "0,0,0", "--target", "0,0,-4", "--lines", kAllLines,
                                  "--stats", statsPath.string()});
    const auto files = readDump(dump);
    EXPECT_EQ(cv::countNonZero(files.at("lines-outline.png")), 0);
    EXPECT_EQ(cv::countNonZero(files.at("lines-silhouette.png")), 0);
    const auto stats = nlohmann::json::parse(readText(statsPath));
    for (const auto& line : stats["look"]["lines"])
        if (line["type"] == "outline" || line["type"] == "silhouette") {
            EXPECT_EQ(line["skipped_eye_inside"], true);
        }
    // The room covers every pixel; the ball's outline is a circle of radius f R / sqrt(d^2 - R^2) around the centre.
    EXPECT_EQ(cv::countNonZero(files.at("coverage.png")), 128 * 128);
    const double rho = (64.0 / std::tan(glm::radians(17.5))) / std::sqrt(15.0);
    for (const char* type : {"contour", "depth-edge", "mesh-silhouette"}) {
        const cv::Mat& lines = files.at(std::string("lines-") + type + ".png");
        int onCircle = 0, elsewhere = 0;
        for (int row = 0; row < 128; ++row)
            for (int col = 0; col < 128; ++col) {
                if (lines.at<uchar>(row, col) == 0) continue;
                const double r = std::hypot(col + 0.5 - 64.0, row + 0.5 - 64.0);
                (std::abs(r - rho) <= 3.0 ? onCircle : elsewhere) += 1;
            }
        EXPECT_GT(onCircle, int(2.0 * M_PI * rho)) << type;
        EXPECT_EQ(elsewhere, 0) << type;
    }
    // Near is far x 1e-4 at most inside: positive and sane.
    const auto camera = manifestOf(dump)["camera"];
    EXPECT_GT(double(camera["near"]), 0.0);
    EXPECT_LE(double(camera["far"]) / double(camera["near"]), 1.0001e4);
}

TEST_F(Extremes, CameraOnTheBoundingSphereAndOnAVertex) {
    // The eye exactly on the bounding sphere, on the sphere's vertex (0, 0, 1): one vertex has v = 0 (c - p = 0),
    // the near plane cuts the surface open around the eye.
    const fs::path sphere = directory / "sphere.obj";
    writeObj(sphere, {makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 48, 24)});
    for (const char* eye : {"0,0,1", "1,0,0", "0,0.70710678,0.70710678"}) {
        const fs::path dump = render(sphere, std::string("eye") + eye,
                                     {"--size", "64x64", "--eye", eye, "--target", "0,0,0", "--lines", kAllLines});
        const auto files = readDump(dump);
        const auto camera = manifestOf(dump)["camera"];
        const double near = camera["near"], far = camera["far"];
        EXPECT_GT(near, 0.0) << eye;
        EXPECT_LT(near, far) << eye;
        EXPECT_LE(far / near, 1.0001e4) << eye;
        // Looking in through the surface it stands on, the eye sees the far inner wall: covered.
        EXPECT_GT(cv::countNonZero(files.at("coverage.png")), 64 * 64 / 2) << eye;
    }
}

// --- far / near ---------------------------------------------------------------------------------------------------

TEST_F(Extremes, FarOverNearOfAMillionKeepsOcclusionAndLinearDepth) {
    // --clip 1e-3,1e3: far / near = 1e6. A plane at depth 900 (0.9 far) filling the view and, in front of it, a box
    // whose front face is at depth 899.1: 1e-3 of the distance nearer. With the standard [0, 1] depth mapping both
    // land on the same float near 1 (the window depths differ by 1e-9, the spacing there is 6e-8), so the plane,
    // drawn first, hid the box. Reversed-Z resolves about 1e-7 of the distance at every ratio.
    const float planeDepth = 900.0f, boxDepth = 899.1f, boxHalf = 100.0f;
    const fs::path model = directory / "far.obj";
    writeObj(model, {makePlane(400.0f, 4, {0.0f, 0.0f, -planeDepth}),
                     makeBox({-boxHalf, -boxHalf, -boxDepth - 0.45f}, {boxHalf, boxHalf, -boxDepth})});
    const fs::path statsPath = directory / "stats.json";
    const fs::path dump =
        render(model, "far",
               {"--size", "128x128", "--eye", "0,0,0", "--target", "0,0,-1", "--clip", "1e-3,1e3", "--lines",
                "depth-edge,crease,mesh-silhouette", "--depth-jump", "1e-4", "--stats", statsPath.string()});
    const auto files = readDump(dump);
    const auto stats = nlohmann::json::parse(readText(statsPath));
    EXPECT_EQ(stats["clip"]["far_over_near"], 1e6);
    EXPECT_EQ(stats["clip"]["source"], "flags");

    // Linear depth: the box's front face where the pixel's ray meets it more than a pixel inside its square, the
    // plane more than a pixel outside; both to a relative 1e-5.
    const double focal = 64.0 / std::tan(glm::radians(17.5));
    const cv::Mat& depth = files.at("depth.exr");
    cv::Mat square = cv::Mat::zeros(128, 128, CV_8UC1);
    int boxPixels = 0, planePixels = 0;
    double worstBox = 0.0, worstPlane = 0.0;
    for (int row = 0; row < 128; ++row)
        for (int col = 0; col < 128; ++col) {
            // Where the ray through the pixel centre meets the box's front plane, in pixels of the square's half-size.
            const double x = std::abs(col + 0.5 - 64.0) * boxDepth / focal;
            const double y = std::abs(row + 0.5 - 64.0) * boxDepth / focal;
            const double pixel = boxDepth / focal; // one pixel at that depth, in model units
            const double d = depth.at<float>(row, col);
            if (std::max(x, y) < boxHalf - pixel) {
                ++boxPixels;
                worstBox = std::max(worstBox, std::abs(d - boxDepth) / boxDepth);
            } else if (std::max(x, y) > boxHalf + pixel) {
                ++planePixels;
                worstPlane = std::max(worstPlane, std::abs(d - planeDepth) / planeDepth);
            } else {
                square.at<uchar>(row, col) = 255;
            }
        }
    ASSERT_GT(boxPixels, 1000);
    ASSERT_GT(planePixels, 5000);
    EXPECT_LT(worstBox, 1e-5) << "the box is hidden by the plane, or its depth is off";
    EXPECT_LT(worstPlane, 1e-5);
    // Occlusion in the depth-tested passes: the shading and the G-buffer saw the box (above); the mesh-edge pass
    // keeps the box's front edges (creases, and silhouettes: the side faces look away from the eye) in front of the
    // plane, and the depth edge (a 1e-3 jump, found at --depth-jump 1e-4) runs along the square and nowhere else.
    cv::Mat nearSquare;
    cv::dilate(square, nearSquare, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
    const int perimeter = int(8.0 * boxHalf * focal / boxDepth);
    for (const char* type : {"depth-edge", "crease", "mesh-silhouette"}) {
        const cv::Mat& lines = files.at(std::string("lines-") + type + ".png");
        EXPECT_GT(countInside(lines, nearSquare), perimeter) << type;
        EXPECT_EQ(countInside(lines, ~nearSquare), 0) << type;
    }
}

TEST_F(Extremes, NearOverFarFrom1em4To1e6KeepsEveryBufferFinite) {
    // The same sphere through clip ranges from the fitted one (far / near about 3) to 1e6, and a near plane that
    // cuts the sphere open: finite buffers, and the coverage of the uncut sphere identical at every ratio.
    const fs::path sphere = directory / "sphere.obj";
    writeObj(sphere, {makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 48, 24)});
    const std::vector<std::string> view = {"--size",   "64x64", "--eye",   "0,0,4",
                                           "--target", "0,0,0", "--lines", kAllLines};
    auto flags = [&](std::vector<std::string> more) {
        more.insert(more.begin(), view.begin(), view.end());
        return more;
    };
    const auto fitted = readDump(render(sphere, "fitted", flags({})));
    for (const char* clip : {"2.9,5.1", "0.5,50", "4e-4,4", "1e-5,10", "1e-6,1e6"}) {
        const auto files = readDump(render(sphere, std::string("clip") + clip, flags({"--clip", clip})));
        EXPECT_EQ(differingPixels(files.at("coverage.png"), fitted.at("coverage.png")), 0) << clip;
        EXPECT_EQ(differingPixels(files.at("lines-contour.png"), fitted.at("lines-contour.png")), 0) << clip;
        EXPECT_LT(cv::norm(files.at("depth.exr"), fitted.at("depth.exr"), cv::NORM_INF), 4e-6) << clip;
    }
    // Near 3.5 cuts the front cap away: the inside of the back half shows through, still finite.
    const auto cut = readDump(render(sphere, "cut", flags({"--clip", "3.5,5"})));
    EXPECT_GT(cv::countNonZero(cut.at("coverage.png")), 0);
}

// --- Float16 G-buffer ---------------------------------------------------------------------------------------------

TEST_F(Extremes, HalfFloatGBufferStaysFiniteAndKeepsDepthInFloat32) {
    // --gbuffer-precision half stores normal, view, w, n.v and radial in float16 (largest finite 65504, smallest
    // normal 6.1e-5). The fandisk at scale 2^17 puts every linear depth above 65504, where float16 would turn it to
    // Inf; depth stays float32, so it is the float32 run's depth to the bit. The radial field is in units of the
    // bounding radius, so its values stay near 1 at any scale. A frontal plane drives |w|^2 below float16's normal
    // range at its centre: it underflows toward 0, never to NaN.
    const fs::path fandisk = scaledFandisk(directory, std::ldexp(1.0, 17));
    const auto single = readDump(render(fandisk, "float", kScaleFlags));
    std::vector<std::string> halfFlags = kScaleFlags;
    halfFlags.insert(halfFlags.end(), {"--gbuffer-precision", "half"});
    const fs::path halfDump = render(fandisk, "half", halfFlags);
    const auto half = readDump(halfDump);
    double nearest = 0.0, farthest = 0.0;
    cv::minMaxLoc(single.at("depth.exr"), nullptr, &farthest);
    cv::minMaxLoc(single.at("depth.exr"), &nearest, nullptr, nullptr, nullptr, single.at("depth.exr") > 0);
    EXPECT_GT(nearest, 65504.0) << "the case must exceed float16's range";
    EXPECT_EQ(imageFilePixelType(halfDump / "depth.exr"), "float");
    EXPECT_EQ(cv::norm(half.at("depth.exr"), single.at("depth.exr"), cv::NORM_INF), 0.0);
    EXPECT_EQ(differingPixels(half.at("coverage.png"), single.at("coverage.png")), 0);

    const fs::path plane = directory / "plane.obj";
    writeObj(plane, {makePlane(1.0f, 16)});
    const auto frontal = readDump(render(plane, "frontal",
                                         {"--size", "129x129", "--eye", "0,0,3", "--target", "0,0,0", "--lines",
                                          kAllLines, "--gbuffer-precision", "half"}));
    EXPECT_EQ(cv::countNonZero(frontal.at("lines-suggestive.png")), 0);
}

} // namespace
} // namespace inkgraph
