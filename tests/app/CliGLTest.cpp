// The real `inkgraph` executable as a user runs it: dump and read back, stats, exit codes, messages, and no
// half-written files. Needs a GL context (llvmpipe in CI) for the rendering cases.
#include "app/Version.h"
#include "render/ImageFiles.h"
#include "scene/mesh/Procedural.h"
#include "CliTestSupport.h"
#include "GltfTestFiles.h"

#include "passes/lines/LineTypes.h"
#include "passes/shade/ShadingModel.h"

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

namespace inkgraph {
namespace {

/** Every line type's pass (one per registered type, passes/lines/LineTypes.h) and the mesh-edges pass they share. */
std::set<std::string> everyLinePass() {
    std::set<std::string> names = {"mesh-edges"};
    for (const LineType& type : lineTypes()) names.insert(type.name);
    return names;
}

using test::Cli;
using test::CliRun;
using test::readText;
namespace fs = std::filesystem;

TEST_F(Cli, DumpWritesEveryComputedBufferAndReadsBack) {
    const CliRun result =
        run("render " + model("spot_c3d.obj") +
            " -o final.png --size 96x64 --lines none --dump dump --request 'gbuffer.*' --stats stats.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;

    // float32 in the files themselves, not converted on reading.
    for (const char* file : {"normal.exr", "view.exr", "w.exr", "ndotv.exr", "depth.exr"})
        EXPECT_EQ(imageFilePixelType(directory / "dump" / file), "float") << file;
    EXPECT_EQ(imageFilePixelType(directory / "dump" / "coverage.png"), "uint8");
    const cv::Mat normal = readImage(directory / "dump" / "normal.exr");
    ASSERT_EQ(normal.type(), CV_32FC4);
    ASSERT_EQ(normal.size(), cv::Size(96, 64));
    const cv::Mat nDotV = readImage(directory / "dump" / "ndotv.exr");
    ASSERT_EQ(nDotV.type(), CV_32FC1);
    const cv::Mat depth = readImage(directory / "dump" / "depth.exr");
    ASSERT_EQ(depth.type(), CV_32FC1);
    const cv::Mat w = readImage(directory / "dump" / "w.exr");
    const cv::Mat view = readImage(directory / "dump" / "view.exr");
    const cv::Mat coverage = readImage(directory / "dump" / "coverage.png");
    ASSERT_EQ(coverage.type(), CV_8UC1);
    // The files agree with each other: covered pixels have unit normals, n.v = dot(n, v), |w|^2 + (n.v)^2 = 1 and a
    // positive depth; background pixels are zero.
    int covered = 0;
    for (int row = 0; row < 64; ++row) {
        for (int col = 0; col < 96; ++col) {
            const cv::Vec4f n = normal.at<cv::Vec4f>(row, col);
            const cv::Vec4f v = view.at<cv::Vec4f>(row, col);
            const cv::Vec4f wv = w.at<cv::Vec4f>(row, col);
            const float d = nDotV.at<float>(row, col);
            if (coverage.at<uchar>(row, col) == 0) {
                ASSERT_EQ(n[3], 0.0f);
                ASSERT_EQ(v[3], 0.0f);
                ASSERT_EQ(wv[3], 0.0f);
                ASSERT_EQ(depth.at<float>(row, col), 0.0f);
                continue;
            }
            ++covered;
            ASSERT_EQ(n[3], 1.0f) << "alpha carries coverage";
            ASSERT_EQ(v[3], 1.0f);
            ASSERT_EQ(wv[3], 1.0f);
            ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-4f);
            ASSERT_NEAR(n[0] * v[0] + n[1] * v[1] + n[2] * v[2], d, 1e-5f);
            ASSERT_NEAR(wv[0] * wv[0] + wv[1] * wv[1] + wv[2] * wv[2] + d * d, 1.0f, 1e-4f);
            ASSERT_GT(depth.at<float>(row, col), 0.0f);
        }
    }
    EXPECT_GT(covered, 500);

    const cv::Mat finalImage = readImage(directory / "final.png");
    EXPECT_EQ(finalImage.type(), CV_8UC4);
    EXPECT_EQ(cv::norm(finalImage, readImage(directory / "dump" / "final.png"), cv::NORM_INF), 0.0);
    EXPECT_TRUE(fs::exists(directory / "dump" / "shading.png"));

    const auto manifest = nlohmann::json::parse(readText(directory / "dump" / "manifest.json"));
    EXPECT_EQ(manifest["size"], nlohmann::json::array({96, 64}));
    EXPECT_EQ(manifest["camera"]["source"], "auto-framed");
    EXPECT_EQ(manifest["camera"]["view_matrix"].size(), 4u);
    // OpenCV's K: the focal length, and the centre half a pixel less (OpenCV puts pixel (0, 0)'s centre at (0, 0)).
    const auto& camera = manifest["camera"];
    const double focal = camera["focal_pixels"].get<double>();
    EXPECT_EQ(camera["intrinsics"], nlohmann::json::array({{focal, 0.0, 47.5}, {0.0, focal, 31.5}, {0.0, 0.0, 1.0}}))
        << camera["intrinsics"].dump();
    // [R|t] is the view matrix with y and z negated (OpenCV's y down, z forward).
    ASSERT_EQ(camera["extrinsics"].size(), 3u);
    for (int row = 0; row < 3; ++row) {
        ASSERT_EQ(camera["extrinsics"][row].size(), 4u);
        const double sign = row == 0 ? 1.0 : -1.0;
        for (int col = 0; col < 4; ++col)
            EXPECT_NEAR(camera["extrinsics"][row][col].get<double>(),
                        sign * camera["view_matrix"][row][col].get<double>(), 1e-12)
                << "row " << row << ", column " << col;
    }
    std::map<std::string, std::string> fileToResource;
    for (const auto& file : manifest["files"]) fileToResource[file["file"]] = file["resource"];
    EXPECT_EQ(fileToResource["normal.exr"], "gbuffer.normal");
    EXPECT_EQ(fileToResource["w.exr"], "gbuffer.wVec");
    EXPECT_EQ(fileToResource["shading.png"], "shade.color");
    EXPECT_EQ(fileToResource["final.png"], "composite.final");
    EXPECT_EQ(manifest["passes"].size(), 3u);

    const auto stats = nlohmann::json::parse(readText(directory / "stats.json"));
    EXPECT_EQ(stats["passes"][0]["name"], "gbuffer");
    EXPECT_GT(stats["passes"][0]["ms"].get<double>(), 0.0);
    EXPECT_EQ(stats["scene"]["triangles"], 5856);
    // The scene data the passes that ran imported, derived once before they prepared: the meshes alone here (no line
    // pass runs, so no edge adjacency or hull).
    ASSERT_TRUE(stats["imports_ms"].is_object());
    EXPECT_EQ(stats["imports_ms"].size(), 1u) << stats["imports_ms"].dump();
    EXPECT_TRUE(stats["imports_ms"].contains("scene.meshes")) << stats["imports_ms"].dump();
    // Only the line passes no --lines asked for are culled.
    std::set<std::string> culledNames;
    for (const auto& pass : stats["culled"]) culledNames.insert(pass["name"].get<std::string>());
    EXPECT_EQ(culledNames, everyLinePass());
    // No temporary or staging names left anywhere.
    for (const std::string& name : listFiles(directory / "dump")) EXPECT_NE(name.rfind(".inkgraph-", 0), 0u) << name;
    for (const std::string& name : listFiles(directory)) EXPECT_NE(name.rfind(".inkgraph-", 0), 0u) << name;
}

TEST_F(Cli, ALookSettingThatAutoLeavesUnusedOnTheModelIsAWarning) {
    // --shading auto settles per model: a plain OBJ is drawn cel-shaded, which has no ambient term, and a model whose
    // materials are all MToon reads no cel shade map. Both flags passed the flag checks and changed nothing, silently.
    const std::string spot = model("spot_c3d.obj");
    CliRun result = run("render " + spot + " -o x.png --size 32x32 --ambient 0.9");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("warning: --ambient changes nothing on this model: --shading auto draws it cel-shaded "
                              "(it has no MToon material), and cel has no ambient term"),
              std::string::npos)
        << result.err;
    EXPECT_EQ(run("render " + spot + " -o x.png --size 32x32 --ambient 0.9 --strict").exitCode, 3);
    const std::string mtoon = model("characters/mtoon-uv-animation-test.vrm");
    result = run("render " + mtoon + " -o x.png --size 32x32 --bands 2");
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.err.find("warning: --bands changes nothing on this model: --shading auto draws every material of "
                              "it as MToon, which has no cel shade map"),
              std::string::npos)
        << result.err;
    // Where they do change the picture, nothing is said.
    for (const std::string& used : {"render " + spot + " -o x.png --size 32x32 --bands 2",
                                    "render " + mtoon + " -o x.png --size 32x32 --ambient 0.9",
                                    "render " + spot + " -o x.png --size 32x32 --shading lambert --ambient 0.9"}) {
        result = run(used);
        EXPECT_EQ(result.exitCode, 0) << used << ": " << result.err;
        EXPECT_EQ(result.err.find("look-setting-unused"), std::string::npos) << used << ": " << result.err;
        EXPECT_EQ(result.err.find("changes nothing"), std::string::npos) << used << ": " << result.err;
    }
}

TEST_F(Cli, DumpingNeverChangesWhatRuns) {
    ASSERT_EQ(
        run("render " + model("spot_c3d.obj") + " -o a.png --size 48x48 --lines none --stats plain.json").exitCode, 0);
    ASSERT_EQ(
        run("render " + model("spot_c3d.obj") + " -o b.png --size 48x48 --lines none --stats dumped.json --dump d")
            .exitCode,
        0);
    const auto plain = nlohmann::json::parse(readText(directory / "plain.json"));
    const auto dumped = nlohmann::json::parse(readText(directory / "dumped.json"));
    ASSERT_EQ(plain["passes"].size(), dumped["passes"].size());
    for (std::size_t i = 0; i < plain["passes"].size(); ++i)
        EXPECT_EQ(plain["passes"][i]["name"], dumped["passes"][i]["name"]);
    // Shading draws the meshes itself: nothing of the G-buffer is computed or dumped unless requested.
    EXPECT_EQ(listFiles(directory / "d"), (std::vector<std::string>{"final.png", "manifest.json", "shading.png"}));
    EXPECT_EQ(cv::norm(readImage(directory / "a.png"), readImage(directory / "b.png"), cv::NORM_INF), 0.0);
}

TEST_F(Cli, DumpReplacesAnEarlierDumpWhole) {
    ASSERT_EQ(
        run("render " + model("spot_c3d.obj") + " --size 32x32 --lines none --dump d --request 'gbuffer.*'").exitCode,
        0);
    EXPECT_TRUE(fs::exists(directory / "d" / "w.exr"));
    const CliRun second = run("render " + model("spot_c3d.obj") + " --size 48x48 --lines none --dump d --shading none");
    ASSERT_EQ(second.exitCode, 0) << second.err;
    // Nothing of the first run is left beside the second run's files, and no staging folder either.
    EXPECT_EQ(listFiles(directory / "d"), (std::vector<std::string>{"final.png", "manifest.json"}));
    EXPECT_EQ(listFiles(directory), (std::vector<std::string>{"d"}));
    EXPECT_EQ(readImage(directory / "d" / "final.png").size(), cv::Size(48, 48));
}

TEST_F(Cli, DumpIntoAnExistingFolderKeepsTheFolder) {
    // "d/." and a folder given by a trailing slash both name the folder itself; it is filled in place.
    fs::create_directories(directory / "d");
    fs::permissions(directory / "d", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " --size 16x16 --lines none --dump d/.").exitCode, 0);
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " --size 16x16 --lines none --dump d/ --shading none").exitCode,
              0);
    EXPECT_EQ(listFiles(directory / "d"), (std::vector<std::string>{"final.png", "manifest.json"}));
    EXPECT_EQ(fs::status(directory / "d").permissions() & fs::perms::all,
              fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec)
        << "the folder's own permissions survive a dump";
}

TEST_F(Cli, CollidingOutputsAreRefusedBeforeAnyWork) {
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj", directory / "m.obj");
    const auto modelSize = fs::file_size(directory / "m.obj");
    CliRun statsOnModel = run("render m.obj -o a.png --size 16x16 --stats m.obj");
    EXPECT_EQ(statsOnModel.exitCode, 2);
    EXPECT_NE(statsOnModel.err.find("is the model itself"), std::string::npos) << statsOnModel.err;
    EXPECT_EQ(fs::file_size(directory / "m.obj"), modelSize);

    CliRun same = run("render m.obj -o a.png --size 16x16 --graphviz ./a.png");
    EXPECT_EQ(same.exitCode, 2);
    EXPECT_NE(same.err.find("name the same file"), std::string::npos) << same.err;

    CliRun inside = run("render m.obj -o d/a.png --size 16x16 --dump d");
    EXPECT_EQ(inside.exitCode, 2);
    EXPECT_NE(inside.err.find("lies inside --dump 'd'"), std::string::npos) << inside.err;
    EXPECT_EQ(listFiles(directory), (std::vector<std::string>{"m.obj"}));
}

TEST_F(Cli, AFailedWriteLeavesNothingBehind) {
    // A 2 KiB file-size limit: the picture cannot be written. The run must say so and leave no file, not even the
    // dump folder it created (earlier, libpng's error went unnoticed and a truncated PNG was renamed into place).
    const CliRun result = run("render " + model("spot_c3d.obj") + " -o a.png --size 256x256 --dump d --stats s.json",
                              "sh -c 'ulimit -f 4; exec \"$0\" \"$@\"'");
    EXPECT_EQ(result.exitCode, 5) << result.err;
    EXPECT_NE(result.err.find("File too large"), std::string::npos) << result.err;
    EXPECT_EQ(listFiles(directory), std::vector<std::string>{});
}

TEST_F(Cli, DumpRefusesAFolderOfOtherFiles) {
    fs::create_directories(directory / "mine");
    std::ofstream(directory / "mine" / "notes.txt") << "precious";
    const CliRun result = run("render " + model("spot_c3d.obj") + " --size 16x16 --dump mine");
    EXPECT_EQ(result.exitCode, 5);
    EXPECT_NE(result.err.find("--dump 'mine'"), std::string::npos) << result.err;
    EXPECT_EQ(listFiles(directory / "mine"), std::vector<std::string>{"notes.txt"});
}

TEST_F(Cli, AModelFarFromTheOriginRendersLikeTheSameModelAtIt) {
    // Georeferenced exports sit 1e7 units out. Positions stay in double until they are relative to the scene's
    // origin, so the picture is the same bit for bit (before, float32 positions rounded to 1 unit: a blocky
    // polyhedron).
    std::ifstream near(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj");
    std::ofstream far(directory / "far.obj");
    far.precision(17);
    for (std::string line; std::getline(near, line);) {
        std::istringstream fields(line);
        std::string tag;
        double x = 0, y = 0, z = 0;
        if (fields >> tag && tag == "v" && fields >> x >> y >> z)
            far << "v " << x + 1e7 << " " << y - 3e7 << " " << z + 2e7 << "\n";
        else
            far << line << "\n";
    }
    far.close();
    const std::string look = " --size 96x96 --lines contour,silhouette,suggestive";
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " -o near.png" + look).exitCode, 0);
    ASSERT_EQ(run("render far.obj -o far.png --dump d" + look).exitCode, 0);
    EXPECT_EQ(cv::norm(readImage(directory / "near.png"), readImage(directory / "far.png"), cv::NORM_INF), 0.0);
    // The manifest speaks world coordinates: an --eye given in them comes back as given.
    ASSERT_EQ(run("render far.obj --size 16x16 --dump e --eye 10000003,-30000000,20000000").exitCode, 0);
    const auto manifest = nlohmann::json::parse(readText(directory / "e" / "manifest.json"));
    EXPECT_EQ(manifest["camera"]["eye"], nlohmann::json::array({10000003.0, -30000000.0, 20000000.0}));
    // [R|t] takes that eye to the camera centre to double rounding of 3e7 (about 4e-9), not float's 2 units.
    const auto& extrinsics = manifest["camera"]["extrinsics"];
    const double eye[3] = {10000003.0, -30000000.0, 20000000.0};
    for (int row = 0; row < 3; ++row) {
        double centre = extrinsics[row][3].get<double>();
        for (int col = 0; col < 3; ++col) centre += extrinsics[row][col].get<double>() * eye[col];
        EXPECT_NEAR(centre, 0.0, 1e-7) << "row " << row;
    }
}

TEST_F(Cli, AByteOrderMarkOrAMissingSolidLineChangesNothing) {
    // Before: the BOM glued to the first 'v' lost that vertex and shifted every index; STL text without 'solid' was
    // called a truncated binary STL of 959328288 triangles.
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(directory / "plain.obj") << obj;
    std::ofstream(directory / "bom.obj") << "\xEF\xBB\xBF" << obj;
    const std::string facets = "facet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n"
                               " endloop\nendfacet\nfacet normal 0 0 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n"
                               "  vertex 0 0 1\n endloop\nendfacet\n";
    std::ofstream(directory / "solid.stl") << "solid t\n" << facets << "endsolid t\n";
    std::ofstream(directory / "bare.stl") << facets;
    for (const char* name : {"plain.obj", "bom.obj", "solid.stl", "bare.stl"}) {
        const CliRun result = run(std::string("render ") + name + " -o " + name + ".png --size 48x48 --lines contour");
        ASSERT_EQ(result.exitCode, 0) << name << ": " << result.err;
    }
    EXPECT_EQ(cv::norm(readImage(directory / "plain.obj.png"), readImage(directory / "bom.obj.png"), cv::NORM_INF),
              0.0);
    EXPECT_EQ(cv::norm(readImage(directory / "solid.stl.png"), readImage(directory / "bare.stl.png"), cv::NORM_INF),
              0.0);

    // A style file's mark was glued to its first setting's name: "'\xEF\xBB\xBFshading' is not a style setting".
    std::ofstream(directory / "plain.style") << "shading = comic\nlines = silhouette\n";
    std::ofstream(directory / "bom.style") << "\xEF\xBB\xBF"
                                           << "shading = comic\nlines = silhouette\n";
    for (const char* style : {"plain.style", "bom.style"}) {
        const CliRun result = run(std::string("render plain.obj -o ") + style + ".png --size 48x48 --style " + style);
        ASSERT_EQ(result.exitCode, 0) << style << ": " << result.err;
    }
    EXPECT_EQ(cv::norm(readImage(directory / "plain.style.png"), readImage(directory / "bom.style.png"), cv::NORM_INF),
              0.0);
}

TEST_F(Cli, APlyModelRendersLikeTheSameObj) {
    // A cube of six coloured quads as OBJ (`v x y z r g b`), ASCII PLY with float colours and big-endian binary PLY
    // with uchar colours (k/255, which OBJ's 17 digits give back exactly): the same picture, bit for bit.
    std::ostringstream obj;
    obj.precision(17);
    std::string ascii = "ply\nformat ascii 1.0\ncomment a cube\nelement vertex 8\nproperty float x\nproperty float y\n"
                        "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
                        "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
    std::string binary = "ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                         "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                         "element face 6\nproperty list uchar uint vertex_indices\nend_header\n";
    const auto bigEndian = [&](auto value) {
        char bytes[sizeof value];
        std::memcpy(bytes, &value, sizeof value);
        std::reverse(bytes, bytes + sizeof value); // the test machines are little-endian
        binary.append(bytes, sizeof value);
    };
    for (int i = 0; i < 8; ++i) {
        const float position[3] = {float(i & 1), float((i >> 1) & 1), float(i >> 2)};
        const int colour[3] = {30 * i, 255 - 30 * i, 51};
        obj << "v " << position[0] << " " << position[1] << " " << position[2];
        ascii += std::to_string(int(position[0])) + " " + std::to_string(int(position[1])) + " " +
                 std::to_string(int(position[2]));
        for (int c = 0; c < 3; ++c) {
            obj << " " << colour[c] / 255.0;
            std::ostringstream component;
            component.precision(17);
            component << colour[c] / 255.0;
            ascii.append(" ").append(component.str()); // not " " + ...: GCC 12's false -Wrestrict (bug 105329)
        }
        obj << "\n";
        ascii += "\n";
        for (const float p : position) bigEndian(p);
        for (const int c : colour) binary += char(c);
    }
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& quad : quads) {
        obj << "f " << quad[0] + 1 << " " << quad[1] + 1 << " " << quad[2] + 1 << " " << quad[3] + 1 << "\n";
        ascii += "4 " + std::to_string(quad[0]) + " " + std::to_string(quad[1]) + " " + std::to_string(quad[2]) + " " +
                 std::to_string(quad[3]) + "\n";
        binary += char(4);
        for (const int index : quad) bigEndian(std::uint32_t(index));
    }
    std::ofstream(directory / "cube.obj") << obj.str();
    std::ofstream(directory / "cube.ply") << ascii;
    std::ofstream(directory / "cube-binary.ply", std::ios::binary) << binary;
    for (const char* name : {"cube.obj", "cube.ply", "cube-binary.ply"}) {
        const CliRun result = run(std::string("render ") + name + " -o " + name + ".png --size 64x64 --orbit 30,25" +
                                  " --lines contour,silhouette --stats " + name + ".json");
        ASSERT_EQ(result.exitCode, 0) << name << ": " << result.err;
    }
    const cv::Mat reference = readImage(directory / "cube.obj.png");
    EXPECT_EQ(cv::norm(reference, readImage(directory / "cube.ply.png"), cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(reference, readImage(directory / "cube-binary.ply.png"), cv::NORM_INF), 0.0);
    const auto stats = nlohmann::json::parse(readText(directory / "cube-binary.ply.json"));
    EXPECT_EQ(stats["scene"]["format"], "ply-binary") << stats["scene"].dump();
    EXPECT_EQ(stats["scene"]["triangles"], 12) << stats["scene"].dump();
    // The colours are drawn: the picture is not the grey of a model without them.
    cv::Mat channels[4];
    cv::split(reference, channels);
    EXPECT_GT(cv::norm(channels[0], channels[1], cv::NORM_INF), 50.0);
}

TEST_F(Cli, AnInsideOutModelDrawsTheSilhouetteOfItsOutwardCopy) {
    // A closed OBJ wound clockwise seen from outside lost its whole hull silhouette (the hull shrank inside the model,
    // scene/mesh/OutwardWinding.h): it is turned outward at load, with a warning, and draws the outward copy's picture.
    const Mesh torus = makeTorus(1.0f, 0.4f, 64, 32);
    std::ostringstream vertices;
    vertices.precision(9);
    for (const glm::vec3& p : torus.positions) vertices << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
    std::ostringstream outward, insideOut;
    for (const glm::uvec3& t : torus.triangles) {
        outward << "f " << t.x + 1 << ' ' << t.y + 1 << ' ' << t.z + 1 << '\n';
        insideOut << "f " << t.x + 1 << ' ' << t.z + 1 << ' ' << t.y + 1 << '\n';
    }
    std::ofstream(directory / "outward.obj") << vertices.str() << outward.str();
    std::ofstream(directory / "inside-out.obj") << vertices.str() << insideOut.str();
    for (const char* name : {"outward.obj", "inside-out.obj"}) {
        const CliRun result =
            run(std::string("render ") + name + " -o " + name + ".png --size 160x160 --orbit 20,40 --lines silhouette");
        ASSERT_EQ(result.exitCode, 0) << name << ": " << result.err;
        EXPECT_EQ(result.err.find("inside out") != std::string::npos, std::string(name) == "inside-out.obj")
            << name << ": " << result.err;
    }
    const cv::Mat drawn = readImage(directory / "outward.obj.png");
    EXPECT_EQ(cv::norm(drawn, readImage(directory / "inside-out.obj.png"), cv::NORM_INF), 0.0);
}

TEST_F(Cli, SuggestiveClearanceKeepsLinesOffWhereTheSurfaceEnds) {
    // --suggestive-clearance 2 drops the crossings within two sigmas of the smoothing of where their surface ends
    // (Lucy has many lines beside her outlines and occlusions: 847 points at 512^2 without the band, 788 with it), and
    // only those: every skeleton pixel kept is one the run without the band marked too. --stats reports the setting.
    // (The textured box once served here, whose only lines lay beside its creases; those steps of its normals are now
    // no surface to differentiate, so it draws none either way.) Both runs at --suggestive-min-angle 0: the default
    // angle test already drops most of Lucy's crossings beside her outlines, which run nearly along w there (at
    // 512^2 the band then finds 19 of 703, not 59 of 847).
    // --stats reports that setting too.
    std::map<std::string, cv::Mat> skeletons;
    std::map<std::string, int> points;
    for (const char* clearance : {"0", "2"}) {
        const std::string name = std::string("clearance-") + clearance;
        const CliRun result = run("render " + model("lucy_blendify_15k.obj") + " -o " + name +
                                  ".png --size 512x512 --shading none --lines suggestive --suggestive-min-angle 0 "
                                  "--suggestive-clearance " +
                                  clearance + " --dump " + name + " --stats " + name + ".json");
        ASSERT_EQ(result.exitCode, 0) << result.err;
        skeletons[clearance] = readImage(directory / name / "skeleton-suggestive.png");
        const nlohmann::json stats = nlohmann::json::parse(readText(directory / (name + ".json")));
        bool reported = false;
        for (const nlohmann::json& layer : stats["look"]["lines"])
            if (layer.value("type", "") == "suggestive")
                reported = layer["clearance"] == std::stod(clearance) && layer["min_angle_to_w"] == 0.0;
        EXPECT_TRUE(reported) << name;
        points[clearance] = stats["post_stage"]["lines"][0]["points"].get<int>();
    }
    EXPECT_GT(points["0"], 500);
    EXPECT_LT(points["2"], points["0"] - 20) << "the band drops the crossings beside the outlines";
    EXPECT_GT(points["2"], points["0"] / 2) << "and only those";
    cv::Mat keptOnlyWithBand;
    cv::subtract(skeletons["2"], skeletons["0"], keptOnlyWithBand);
    EXPECT_EQ(cv::countNonZero(keptOnlyWithBand), 0) << "the band only drops marks";
}

TEST_F(Cli, AMeshoptCompressedGlbRendersLikeItsDecodedCopy) {
    // gltfpack's BoxMeshopt.glb, and the same file with each compressed view decoded here (by the library the reader
    // uses) into a plain binary chunk and the extension dropped: the reader's placeholder buffer, view redirection and
    // decoding must give the same picture, bit for bit.
    const fs::path packed = fs::path(INKGRAPH_SOURCE_ROOT) / "tests/scene/data/BoxMeshopt.glb";
    const std::string bytes = readText(packed);
    const std::uint32_t jsonLength = std::uint32_t(std::uint8_t(bytes[12])) |
                                     std::uint32_t(std::uint8_t(bytes[13])) << 8 |
                                     std::uint32_t(std::uint8_t(bytes[14])) << 16;
    const std::string compressed = bytes.substr(20 + jsonLength + 8);
    std::string plain;
    const std::string decoded = test::editedGlb(packed, [&](nlohmann::json& gltf) {
        for (nlohmann::json& view : gltf["bufferViews"]) {
            const nlohmann::json extension = view["extensions"]["EXT_meshopt_compression"];
            const std::size_t count = extension["count"], stride = extension["byteStride"];
            const std::size_t offset = extension["byteOffset"], length = extension["byteLength"];
            std::string out(count * stride, '\0');
            const auto* source = reinterpret_cast<const unsigned char*>(compressed.data() + offset);
            const int failed = extension["mode"] == "ATTRIBUTES"
                                   ? meshopt_decodeVertexBuffer(out.data(), count, stride, source, length)
                                   : meshopt_decodeIndexBuffer(out.data(), count, stride, source, length);
            ASSERT_EQ(failed, 0);
            view.erase("extensions");
            view["buffer"] = 0;
            view["byteOffset"] = plain.size();
            plain += out;
            while (plain.size() % 4 != 0) plain += '\0';
        }
        gltf["buffers"] = {{{"byteLength", plain.size()}}};
        gltf["extensionsUsed"] = gltf["extensionsRequired"] = {"KHR_mesh_quantization"};
    });
    // editedGlb() kept the compressed binary chunk; the decoded copy's is `plain`.
    const std::string decodedJson = decoded.substr(20, decoded.size() - 20 - 8 - compressed.size());
    std::ofstream(directory / "decoded.glb", std::ios::binary)
        << test::glb(decodedJson, test::u32(std::uint32_t(plain.size())) + std::string("BIN\0", 4) + plain);
    fs::copy_file(packed, directory / "packed.glb");
    for (const char* name : {"packed.glb", "decoded.glb"}) {
        const CliRun result = run(std::string("render ") + name + " -o " + name + ".png --size 64x64 --orbit 30,25" +
                                  " --lines contour,silhouette --stats " + name + ".json");
        ASSERT_EQ(result.exitCode, 0) << name << ": " << result.err;
    }
    const cv::Mat picture = readImage(directory / "packed.glb.png");
    EXPECT_EQ(cv::norm(picture, readImage(directory / "decoded.glb.png"), cv::NORM_INF), 0.0);
    EXPECT_EQ(nlohmann::json::parse(readText(directory / "packed.glb.json"))["scene"]["triangles"], 12);
    cv::Mat channels[4];
    cv::split(picture, channels);
    EXPECT_GT(cv::countNonZero(channels[0] > channels[1] + 100), 64 * 64 / 10); // the box's red covers the middle
}

TEST_F(Cli, AwkwardPathsAndFormats) {
    // A model path that is not UTF-8 still gives valid JSON (the bad bytes become U+FFFD).
    fs::copy_file(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "spot_c3d.obj", directory / "caf\xe9.obj");
    const CliRun latin1 = run("render 'caf\xe9.obj' -o a.png --size 16x16 --stats s.json");
    ASSERT_EQ(latin1.exitCode, 0) << latin1.err;
    EXPECT_NO_THROW(nlohmann::json::parse(readText(directory / "s.json")));

    // A long final name still has a valid temporary name.
    const std::string longName(240, 'n');
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " -o " + longName + ".png --size 16x16").exitCode, 0);
    EXPECT_TRUE(fs::exists(directory / (longName + ".png")));

    // JPEG has no alpha: the opaque picture is written as RGB.
    ASSERT_EQ(run("render " + model("spot_c3d.obj") + " -o a.jpg --size 16x16").exitCode, 0);
    EXPECT_EQ(readImage(directory / "a.jpg").channels(), 3);
}

TEST_F(Cli, OnlyFormatsOtherThanPngLoadTheImageModule) {
    // PNG is written in the process by libpng; OpenImageIO (~0.2 s of dynamic linking) only when a run needs it.
    const auto moduleState = [&](const std::string& outputs) {
        const CliRun result =
            run("render " + model("spot_c3d.obj") + " --size 16x16 --lines none --stats s.json " + outputs);
        EXPECT_EQ(result.exitCode, 0) << outputs << ": " << result.err;
        return nlohmann::json::parse(readText(directory / "s.json"))["image_io_module"].get<std::string>();
    };
    EXPECT_EQ(moduleState("-o a.png"), "not loaded");
    EXPECT_EQ(moduleState("-o A.PNG --contact-sheet sheet.png --graphviz a.dot"), "not loaded");
    EXPECT_EQ(moduleState("-o a.exr"), "loaded");
    EXPECT_EQ(moduleState("-o a.png --dump d"), "loaded") << "a dump's float buffers are EXR";
    EXPECT_EQ(imageFilePixelType(directory / "a.exr"), "float");
    EXPECT_EQ(imageFilePixelType(directory / "A.PNG"), "uint8");
}

TEST_F(Cli, TheCommandLineRunsWithHugePagesUnlessTheCallerSetsGlibcTunables) {
    // app/main.cpp starts the program again with its malloc tunables when GLIBC_TUNABLES is unset; a caller's own
    // value, even empty, is kept. --stats reports what the process ran with.
    const char* inherited = std::getenv("GLIBC_TUNABLES");
    const std::string saved = inherited ? inherited : "";
    unsetenv("GLIBC_TUNABLES");
    const auto tunablesOfRun = [&](const std::string& environment) {
        const CliRun result =
            run("render " + model("spot_c3d.obj") + " --size 16x16 --lines none -o a.png --stats s.json", environment);
        EXPECT_EQ(result.exitCode, 0) << environment << ": " << result.err;
        const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
        EXPECT_GE(stats["huge_pages_mib"].get<double>(), 0.0);
        return stats["glibc_tunables"].is_null() ? std::string("null") : stats["glibc_tunables"].get<std::string>();
    };
#if defined(__SANITIZE_ADDRESS__)
    EXPECT_EQ(tunablesOfRun(""), "null") << "the sanitizer's allocator has nothing to tune";
#else
    EXPECT_EQ(tunablesOfRun(""), "glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1");
#endif
    EXPECT_EQ(tunablesOfRun("GLIBC_TUNABLES="), "");
    EXPECT_EQ(tunablesOfRun("GLIBC_TUNABLES=glibc.malloc.arena_max=2"), "glibc.malloc.arena_max=2");
    if (inherited) setenv("GLIBC_TUNABLES", saved.c_str(), 1);
}

TEST_F(Cli, ShadingNoneCullsTheShadingPassWithAReason) {
    const CliRun result =
        run("render " + model("spot_c3d.obj") + " -o a.png --size 32x32 --shading none --lines none --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    ASSERT_EQ(stats["passes"].size(), 1u);
    EXPECT_EQ(stats["passes"][0]["name"], "composite");
    std::set<std::string> culled;
    for (const auto& pass : stats["culled"]) {
        culled.insert(pass["name"].get<std::string>());
        EXPECT_FALSE(pass["reason"].get<std::string>().empty());
    }
    std::set<std::string> expected = everyLinePass();
    expected.insert("gbuffer");
    EXPECT_EQ(culled, expected) << "--shading none registers no shading pass; the rest is culled";
    // Paper only: every pixel white.
    const cv::Mat image = readImage(directory / "a.png");
    EXPECT_EQ(cv::countNonZero(image.reshape(1) != 255), 0);
}

TEST_F(Cli, PrintPlanWithoutOutputNeedsNoGl) {
    // No EGL vendor at all: --print-plan alone still works, because no context is made.
    const CliRun result = run("render " + model("spot_c3d.obj") + " --print-plan",
                              "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("gbuffer"), std::string::npos);
    EXPECT_NE(result.out.find("shade"), std::string::npos);
    EXPECT_NE(result.out.find("composite"), std::string::npos);
}

TEST_F(Cli, NoEglDisplayIsAClearErrorNotACrash) {
    const CliRun result = run("render " + model("spot_c3d.obj") + " -o a.png --size 16x16",
                              "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl.json");
    EXPECT_EQ(result.exitCode, 4) << result.err;
    EXPECT_NE(result.err.find("libegl-mesa0"), std::string::npos) << result.err;
    EXPECT_NE(result.err.find("EGL_LOG_LEVEL=debug"), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(directory / "a.png"));
}

TEST_F(Cli, BadInputExitCodesAndMessages) {
    CliRun missing = run("render nowhere.obj -o a.png");
    EXPECT_EQ(missing.exitCode, 3);
    EXPECT_NE(missing.err.find("nowhere.obj"), std::string::npos) << missing.err;

    std::ofstream(directory / "nan.obj") << "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n";
    CliRun nan = run("render nan.obj -o a.png");
    EXPECT_EQ(nan.exitCode, 3);
    EXPECT_NE(nan.err.find("nan.obj"), std::string::npos) << nan.err;

    CliRun badSize = run("render " + model("spot_c3d.obj") + " -o a.png --size 0x5");
    EXPECT_EQ(badSize.exitCode, 2);
    EXPECT_NE(badSize.err.find("--size"), std::string::npos);

    CliRun noFolder = run("render " + model("spot_c3d.obj") + " -o missing/folder/a.png --size 16x16");
    EXPECT_EQ(noFolder.exitCode, 5);
    EXPECT_NE(noFolder.err.find("missing/folder/a.png"), std::string::npos) << noFolder.err;

    CliRun badExtension = run("render " + model("spot_c3d.obj") + " -o a.docx --size 16x16");
    EXPECT_EQ(badExtension.exitCode, 2);
    EXPECT_NE(badExtension.err.find("'a.docx'"), std::string::npos) << badExtension.err;

    // An output that cannot be written stops the run before anything is rendered or written.
    std::ofstream(directory / "blocker") << "a file where a folder is expected";
    CliRun badStats = run("render " + model("spot_c3d.obj") + " -o a.png --size 16x16 --stats blocker/s.json");
    EXPECT_EQ(badStats.exitCode, 5);
    EXPECT_NE(badStats.err.find("--stats 'blocker/s.json'"), std::string::npos) << badStats.err;
    EXPECT_FALSE(fs::exists(directory / "a.png")) << "-o must not be written when --stats cannot be";

    CliRun huge = run("render " + model("spot_c3d.obj") + " -o a.png --size 16384x16384 --request gbuffer.normal");
    EXPECT_EQ(huge.exitCode, 2);
    EXPECT_NE(huge.err.find("--size 16384x16384"), std::string::npos) << huge.err;

    CliRun badDump = run("render " + model("spot_c3d.obj") + " -o a.png --size 16x16 --dump blocker/sub");
    EXPECT_EQ(badDump.exitCode, 5);
    EXPECT_NE(badDump.err.find("blocker/sub"), std::string::npos) << badDump.err;

    CliRun badRequest = run("render " + model("spot_c3d.obj") + " -o a.png --size 16x16 --request gbuffer.nothing");
    EXPECT_EQ(badRequest.exitCode, 2);
    EXPECT_NE(badRequest.err.find("'gbuffer.nothing'"), std::string::npos) << badRequest.err;

    // Nothing was written by any failed run, not even under a temporary name.
    EXPECT_EQ(listFiles(directory), (std::vector<std::string>{"blocker", "nan.obj"}));
}

TEST_F(Cli, LineTypesDumpTheirMasksAndComposite) {
    const CliRun result = run("render " + model("spot_c3d.obj") +
                              " -o a.png --size 96x64 --lines outline,silhouette --silhouette-color 1,0,0"
                              " --outline-width 1.5 --dump d --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(listFiles(directory / "d"),
              (std::vector<std::string>{"band-outline.png", "band-silhouette.png", "final.png", "lines-outline.png",
                                        "lines-silhouette.png", "manifest.json", "shading.png"}));
    const cv::Mat silhouette = readImage(directory / "d" / "lines-silhouette.png");
    const cv::Mat shading = readImage(directory / "d" / "shading.png");
    const cv::Mat finalImage = readImage(directory / "a.png");
    ASSERT_EQ(silhouette.type(), CV_8UC1);
    int linePixels = 0;
    int outsideModel = 0;
    for (int row = 0; row < silhouette.rows; ++row)
        for (int col = 0; col < silhouette.cols; ++col) {
            if (silhouette.at<uchar>(row, col) != 255) continue;
            ++linePixels;
            // The silhouette is composited last, in its colour.
            ASSERT_EQ(finalImage.at<cv::Vec4b>(row, col), cv::Vec4b(255, 0, 0, 255)) << row << "," << col;
            if (shading.at<cv::Vec4b>(row, col)[3] == 0) ++outsideModel;
        }
    EXPECT_GT(linePixels, 100);
    // Most of the hull lies outside the model; the rest outlines parts in front of others (the head over the body).
    EXPECT_GT(outsideModel, linePixels * 3 / 4);
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    // The default look, auto, runs cel on a model without MToon materials, and says so.
    EXPECT_EQ(stats["look"]["shading"], "auto");
    EXPECT_EQ(stats["look"]["shading_model"], "cel");
    EXPECT_EQ(stats["look"]["shademap"], "builtin:bands-5");
    ASSERT_EQ(stats["look"]["lines"].size(), 2u);
    EXPECT_EQ(stats["look"]["lines"][0]["type"], "outline");
    EXPECT_EQ(stats["look"]["lines"][0]["width_pixels"], 1.5);
    EXPECT_EQ(stats["look"]["lines"][1]["color"], nlohmann::json::array({1.0, 0.0, 0.0, 1.0}));
    EXPECT_EQ(stats["look"]["lines"][1]["skipped_eye_inside"], false);
    EXPECT_FALSE(stats.contains("face_orientation")) << "reported for comic only";
    // Neither line type reads the G-buffer, so shading draws the meshes itself.
    EXPECT_EQ(stats["look"]["shading_mode"], "forward");
    EXPECT_EQ(stats["look"]["shading_forward_because"], "no line type reads the G-buffer");
}

TEST_F(Cli, OnlyThePassesTheRequestedLinesNeedRun) {
    auto passNames = [](const nlohmann::json& stats, const char* list) {
        std::set<std::string> names;
        for (const auto& pass : stats[list]) names.insert(pass["name"].get<std::string>());
        return names;
    };
    // depth-edge alone: the G-buffer runs for depth only, and every other line pass is culled with a reason.
    CliRun result = run("render " + model("spot_c3d.obj") +
                        " -o a.png --size 128x96 --lines depth-edge --stats s.json --print-plan");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    EXPECT_EQ(passNames(stats, "passes"),
              (std::set<std::string>{"gbuffer", "shade", "depth-edge", "strokes", "composite"}));
    for (const char* culled : {"contour", "suggestive", "suggestive-object", "normal-edge", "outline", "silhouette"})
        EXPECT_EQ(passNames(stats, "culled").count(culled), 1u) << culled;
    for (const auto& pass : stats["culled"]) EXPECT_FALSE(pass["reason"].get<std::string>().empty());
    ASSERT_EQ(stats["post_stage"]["lines"].size(), 1u);
    EXPECT_EQ(stats["post_stage"]["lines"][0]["type"], "depth-edge");
    EXPECT_GT(stats["post_stage"]["lines"][0]["points"].get<int>(), 100);
    // The G-buffer computes depth for the lines and the normal for shading, which shades it (deferred) instead of
    // drawing the meshes again; the plan's last line says so.
    EXPECT_TRUE(
        std::regex_search(result.out, std::regex("writes: gbuffer\\.normal\\(rgba32f\\) gbuffer\\.depth\\(r32f\\) "
                                                 "gbuffer\\.zBuffer\\(depth32f\\) +not computed:")))
        << "the G-buffer computes depth and the normal alone, and keeps its z-buffer for the shading\n"
        << result.out;
    EXPECT_TRUE(std::regex_search(result.out, std::regex("shade +reads: gbuffer\\.normal gbuffer\\.zBuffer +writes:")))
        << result.out;
    EXPECT_NE(result.out.find("\nshading: deferred\n"), std::string::npos) << result.out;
    EXPECT_EQ(stats["look"]["shading_mode"], "deferred");
    EXPECT_FALSE(stats["look"].contains("shading_forward_because"));

    // contour and suggestive with shading off: G-buffer, the two line passes and the composite, nothing else.
    result = run("render " + model("spot_c3d.obj") +
                 " -o b.png --size 128x96 --shading none --lines contour,suggestive --stats t.json --dump d");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    stats = nlohmann::json::parse(readText(directory / "t.json"));
    EXPECT_EQ(passNames(stats, "passes"),
              (std::set<std::string>{"gbuffer", "contour", "suggestive", "strokes", "composite"}));
    // The dump holds every buffer the plan computed: the G-buffer fields the two kernels read, their skeletons and
    // the lines the stroke stage drew from them.
    EXPECT_EQ(listFiles(directory / "d"),
              (std::vector<std::string>{"depth.exr", "final.png", "lines-contour.png", "lines-suggestive.png",
                                        "manifest.json", "ndotv.exr", "radial.exr", "skeleton-contour.png",
                                        "skeleton-suggestive.png"}));
    const cv::Mat contour = readImage(directory / "d" / "lines-contour.png");
    ASSERT_EQ(contour.type(), CV_8UC1);
    ASSERT_EQ(contour.size(), cv::Size(128, 96));
    // Anti-aliased: the stroke has partial-coverage pixels as well as full ones.
    int full = 0, partial = 0;
    for (int row = 0; row < contour.rows; ++row)
        for (int col = 0; col < contour.cols; ++col) {
            const int value = contour.at<uchar>(row, col);
            full += value == 255;
            partial += value > 0 && value < 255;
        }
    EXPECT_GT(full, 100);
    EXPECT_GT(partial, 50);
}

TEST_F(Cli, ObjectSpaceSuggestiveContoursAreDumpedAndReported) {
    const CliRun result = run("render " + model("spot_c3d.obj") +
                              " -o a.png --size 160x160 --shading none --lines suggestive-object"
                              " --suggestive-object-color 0,0,1 --dump d --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    // Only the depth is read from the G-buffer: the lines come from the mesh.
    EXPECT_EQ(listFiles(directory / "d"),
              (std::vector<std::string>{"depth.exr", "final.png", "lines-suggestive-object.png", "manifest.json",
                                        "skeleton-suggestive-object.png"}));
    const cv::Mat lines = readImage(directory / "d" / "lines-suggestive-object.png");
    ASSERT_EQ(lines.size(), cv::Size(160, 160));
    EXPECT_GT(cv::countNonZero(lines), 50) << "spot has suggestive contours (neck, legs, ears)";
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    ASSERT_EQ(stats["post_stage"]["lines"].size(), 1u);
    const auto& layer = stats["post_stage"]["lines"][0];
    EXPECT_EQ(layer["type"], "suggestive-object");
    EXPECT_GT(layer["segments"].get<int>(), 10);
    EXPECT_GT(layer["points"].get<int>(), 10);
    EXPECT_EQ(layer["curvature_derived"], true);
    EXPECT_GT(layer["curvature_ms"].get<double>(), 0.0);
    EXPECT_GE(layer["kernel_ms"].get<double>(), 0.0);
    ASSERT_EQ(stats["look"]["lines"].size(), 1u);
    EXPECT_NEAR(stats["look"]["lines"][0]["threshold"].get<double>(), 0.01, 1e-6) << "the default";
    EXPECT_EQ(stats["look"]["lines"][0]["color"], nlohmann::json::array({0.0, 0.0, 1.0, 1.0}));

    // A run without it culls the pass, so the curvature is never derived.
    ASSERT_EQ(
        run("render " + model("spot_c3d.obj") + " -o b.png --size 64x64 --lines suggestive --stats t.json").exitCode,
        0);
    const auto without = nlohmann::json::parse(readText(directory / "t.json"));
    bool culled = false;
    for (const auto& pass : without["culled"]) culled = culled || pass["name"] == "suggestive-object";
    EXPECT_TRUE(culled);
    for (const auto& other : without["post_stage"]["lines"]) EXPECT_FALSE(other.contains("curvature_ms"));
}

TEST_F(Cli, ImageSpaceSuggestiveContoursStayOnOneSmoothPatch) {
    // The fox is flat-shaded: every facet is a smooth patch of its own, flat, so no suggestive contour lies on it.
    // Differentiated across the facets' normal steps, n.v made scribbles along their edges (hundreds of points at this
    // size before the patches were read).
    const std::string fox = test::shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "fox.glb");
    ASSERT_EQ(run("render " + fox + " -o a.png --size 256x256 --lines suggestive --stats s.json --dump d").exitCode, 0);
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    ASSERT_EQ(stats["post_stage"]["lines"].size(), 1u);
    const auto& layer = stats["post_stage"]["lines"][0];
    EXPECT_EQ(layer["type"], "suggestive");
    EXPECT_EQ(layer["surface_ids"], true);
    EXPECT_GT(layer["seam_edges"].get<int>(), 500) << "every edge of a flat-shaded mesh is a seam";
    EXPECT_EQ(layer["points"], 0);
    EXPECT_TRUE(fs::exists(directory / "d" / "triangleid.exr")) << "the triangle ids are read";

    // Spot is one smooth, connected mesh: the depth alone parts its surfaces, so nothing more is read or derived, and
    // its lines are there.
    ASSERT_EQ(
        run("render " + model("spot_c3d.obj") + " -o b.png --size 256x256 --lines suggestive --stats t.json --dump e")
            .exitCode,
        0);
    const auto spot = nlohmann::json::parse(readText(directory / "t.json"));
    EXPECT_EQ(spot["post_stage"]["lines"][0]["surface_ids"], false);
    EXPECT_FALSE(spot["post_stage"]["lines"][0].contains("seam_edges"));
    EXPECT_GT(spot["post_stage"]["lines"][0]["points"].get<int>(), 20);
    EXPECT_FALSE(fs::exists(directory / "e" / "triangleid.exr"));
}

TEST_F(Cli, MeshEdgeLinesSupersampled) {
    const CliRun result = run("render " + model("fandisk_c3d.obj") +
                              " -o a.png --size 120x90 --lines crease,border,mesh-silhouette --crease-angle 40"
                              " --supersample 2 --crease-color 1,0,0 --dump d --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    std::set<std::string> ran;
    for (const auto& pass : stats["passes"]) ran.insert(pass["name"].get<std::string>());
    EXPECT_EQ(ran, (std::set<std::string>{"shade", "mesh-edges", "crease", "border", "mesh-silhouette", "strokes",
                                          "composite"}))
        << "no G-buffer: every requested type is drawn from the mesh's edges";
    ASSERT_EQ(stats["look"]["lines"].size(), 3u);
    for (const auto& line : stats["look"]["lines"]) {
        EXPECT_EQ(line["supersample"], 2);
        if (line["type"] != "border") {
            EXPECT_GT(line["edges_drawn"].get<int>(), 10) << line["type"];
        }
    }
    EXPECT_EQ(stats["look"]["lines"][0]["crease_angle_degrees"], 40.0);
    // The skeletons are drawn at twice the size; the stroked layers are the frame's size.
    EXPECT_EQ(readImage(directory / "d" / "mesh-edges-crease.png").size(), cv::Size(240, 180));
    const cv::Mat crease = readImage(directory / "d" / "lines-crease.png");
    ASSERT_EQ(crease.size(), cv::Size(120, 90));
    EXPECT_GT(cv::countNonZero(crease), 100);
    // Where the crease layer is full and no later layer covers it, the final picture is the crease colour.
    const cv::Mat finalImage = readImage(directory / "a.png");
    const cv::Mat silhouette = readImage(directory / "d" / "lines-mesh-silhouette.png");
    const cv::Mat border = readImage(directory / "d" / "lines-border.png");
    int full = 0;
    for (int row = 0; row < crease.rows; ++row)
        for (int col = 0; col < crease.cols; ++col) {
            if (crease.at<uchar>(row, col) != 255 || silhouette.at<uchar>(row, col) || border.at<uchar>(row, col))
                continue;
            ++full;
            EXPECT_EQ(finalImage.at<cv::Vec4b>(row, col), cv::Vec4b(255, 0, 0, 255)) << col << "," << row;
        }
    EXPECT_GT(full, 5);
}

TEST_F(Cli, ComicStatsReportTheFaceOrientationMethod) {
    const CliRun result = run("render " + model("spot_c3d.obj") +
                              " -o a.png --size 64x64 --shading comic --view-vector constant"
                              " --face-orientation during-vertices --front-rule 2 --lines outline --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    const auto& orientation = stats["face_orientation"];
    EXPECT_EQ(orientation["method"], "during-vertices");
    EXPECT_EQ(orientation["view_vector"], "constant") << "the auto-framed eye is far enough for V_c";
    EXPECT_EQ(orientation["fell_back_to_exact"], false);
    EXPECT_EQ(orientation["missed_triangles"], 0);
    EXPECT_EQ(orientation["triangles"], 5856);
    EXPECT_GE(orientation["front_triangles"].get<int>(), orientation["exact_front_triangles"].get<int>());
    EXPECT_GT(orientation["front_triangle_share"].get<double>(), 0.3);
    EXPECT_LT(orientation["front_triangle_share"].get<double>(), 1.0);
    EXPECT_GE(orientation["mark_ms"].get<double>(), 0.0);

    // Inside the bounding sphere the constant view vector would be NaN: exact vectors, and the stats say why.
    const CliRun close = run("render " + model("spot_c3d.obj") +
                             " -o b.png --size 32x32 --shading comic --view-vector constant --eye 0.3,0.2,0.3"
                             " --target 0,0,0 --stats close.json");
    ASSERT_EQ(close.exitCode, 0) << close.err;
    const auto closeStats = nlohmann::json::parse(readText(directory / "close.json"));
    EXPECT_EQ(closeStats["face_orientation"]["view_vector"], "exact");
    EXPECT_EQ(closeStats["face_orientation"]["fell_back_to_exact"], true);
    EXPECT_NE(closeStats["face_orientation"]["fall_back_reason"].get<std::string>().find("inside"), std::string::npos);
}

TEST_F(Cli, ShadeMapFilesAreReadAndCheckedBeforeAnyWork) {
    const std::string shadeMaps = (fs::path(INKGRAPH_SOURCE_ROOT) / "shademaps").string();
    CliRun comic =
        run("render " + model("spot_c3d.obj") + " -o a.png --size 32x32 --lines none --shading comic --shademap '" +
            shadeMaps + "/noir.png' --stats s.json");
    ASSERT_EQ(comic.exitCode, 0) << comic.err;
    EXPECT_NE(readText(directory / "s.json").find("noir.png"), std::string::npos);
    // Noir has two tones (x the default grey material): every covered pixel is one of them.
    const cv::Mat picture = readImage(directory / "a.png");
    std::set<int> reds;
    for (int row = 0; row < picture.rows; ++row)
        for (int col = 0; col < picture.cols; ++col) reds.insert(picture.at<cv::Vec4b>(row, col)[0]);
    EXPECT_LE(reds.size(), 3u) << "paper and the two tones";

    CliRun missing = run("render " + model("spot_c3d.obj") + " -o b.png --size 16x16 --shademap nowhere.png");
    EXPECT_EQ(missing.exitCode, 3);
    EXPECT_NE(missing.err.find("--shademap"), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("nowhere.png"), std::string::npos) << missing.err;

    std::ofstream(directory / "corrupt.png") << "not a png at all";
    CliRun corrupt = run("render " + model("spot_c3d.obj") + " -o b.png --size 16x16 --shademap corrupt.png");
    EXPECT_EQ(corrupt.exitCode, 3);
    EXPECT_NE(corrupt.err.find("corrupt.png"), std::string::npos) << corrupt.err;

    CliRun twoDimensionalForCel =
        run("render " + model("spot_c3d.obj") + " -o b.png --size 16x16 --shademap '" + shadeMaps + "/metallic.png'");
    EXPECT_EQ(twoDimensionalForCel.exitCode, 3);
    EXPECT_NE(twoDimensionalForCel.err.find("metallic.png"), std::string::npos) << twoDimensionalForCel.err;

    CliRun onItself =
        run("render " + model("spot_c3d.obj") + " -o m.png --size 16x16 --shading comic --shademap m.png");
    EXPECT_EQ(onItself.exitCode, 2);
    EXPECT_NE(onItself.err.find("is the --shademap itself"), std::string::npos) << onItself.err;

    EXPECT_EQ(listFiles(directory), (std::vector<std::string>{"a.png", "corrupt.png", "s.json"}))
        << "failed runs leave nothing behind";
}

TEST_F(Cli, EyeInsideTheModelDrawsNoSilhouettes) {
    const CliRun result = run("render " + model("spot_c3d.obj") +
                              " -o a.png --size 32x32 --eye 0,0.1,0 --target 1,0.1,0 --lines outline,silhouette"
                              " --dump d --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(cv::countNonZero(readImage(directory / "d" / "lines-outline.png")), 0);
    EXPECT_EQ(cv::countNonZero(readImage(directory / "d" / "lines-silhouette.png")), 0);
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    EXPECT_EQ(stats["look"]["lines"][0]["skipped_eye_inside"], true);
    EXPECT_EQ(stats["look"]["lines"][1]["skipped_eye_inside"], true);
    // Said, not only left out: the lines asked for were missing with exit 0 and no word, even under --strict.
    EXPECT_NE(
        result.err.find("warning: the outline lines are not drawn: the eye is inside the model, where their bands "
                        "would cover the whole picture"),
        std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("warning: the silhouette lines are not drawn: the eye is inside the model or the "
                              "silhouette's hull"),
              std::string::npos)
        << result.err;
    const CliRun strict = run("render " + model("spot_c3d.obj") +
                              " -o b.png --size 32x32 --eye 0,0.1,0 --target 1,0.1,0 --lines outline --strict");
    EXPECT_EQ(strict.exitCode, 3) << strict.err;
    EXPECT_FALSE(fs::exists(directory / "b.png"));
    // Outside the model nothing is said.
    const CliRun outside = run("render " + model("spot_c3d.obj") + " -o c.png --size 32x32 --lines outline --strict");
    EXPECT_EQ(outside.exitCode, 0) << outside.err;
}

TEST_F(Cli, LinesTheSettingsGivenLeaveInvisibleAreSaid) {
    // A threshold past every line's strength, or a transparent colour, left the type's lines out of the picture with
    // exit 0 and no word, even under --strict.
    const std::string spot = model("spot_c3d.obj");
    CliRun result = run("render " + spot +
                        " -o a.png --size 96x96 --lines contour,suggestive --suggestive-threshold 1e6"
                        " --contour-color 0,0,0,0 --dump d");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(cv::countNonZero(readImage(directory / "d" / "lines-suggestive.png")), 0);
    EXPECT_NE(result.err.find("warning: the suggestive lines found none in this view at --suggestive-threshold "
                              "1e+06 (default 0.01)\n"),
              std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("warning: the contour lines are drawn transparent: --contour-color has alpha 0"),
              std::string::npos)
        << result.err;

    // Every line dropped by the length rule, and in a batch whose post stage runs on a worker (--jobs 2): each still
    // says it in its place. The views are the seed's (unseeded, a view whose creases chain longer than the height
    // keeps a stroke: the test failed once in CI).
    result =
        run("render " + spot + " --views 2 --seed 7 -o 'v{view}.png' --size 64x64 --lines crease --crease-angle 10 " +
            "--min-stroke-length 1 --jobs 2");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const std::string dropped =
        "the crease lines drew nothing in this view: --min-stroke-length 1 (default 0.01) dropped all ";
    const std::size_t first = result.err.find(dropped);
    ASSERT_NE(first, std::string::npos) << result.err;
    EXPECT_NE(result.err.find(dropped, first + 1), std::string::npos) << result.err;

    // A seed no stroke reaches (hysteresis).
    const CliRun seeded = run("render " + spot + " -o s.png --size 96x96 --lines suggestive --suggestive-seed 50");
    EXPECT_NE(seeded.err.find("warning: the suggestive lines drew nothing in this view: at --suggestive-seed 50 "
                              "(default 0.04) none of their "),
              std::string::npos)
        << seeded.err;

    const CliRun strict =
        run("render " + spot + " -o b.png --size 64x64 --lines contour --contour-color 0,0,0,0 --strict");
    EXPECT_EQ(strict.exitCode, 3) << strict.err;
    EXPECT_FALSE(fs::exists(directory / "b.png"));
    // A type empty at its defaults is the model's, not the user's: a flat square has no crease and no suggestive
    // contour, and nothing is said; nor for a hidden-lines type with nothing hidden.
    std::ofstream(directory / "flat.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n";
    const CliRun flat = run("render flat.obj -o c.png --size 64x64 --lines suggestive,crease --strict");
    EXPECT_EQ(flat.exitCode, 0) << flat.err;
    // A roof seen from above: its ridge is a crease at --crease-angle 30, and none of it is hidden.
    std::ofstream(directory / "roof.obj") << "v -1 0 -1\nv -1 0 1\nv 0 0.6 -1\nv 0 0.6 1\nv 1 0 -1\nv 1 0 1\n"
                                             "f 1 2 4 3\nf 3 4 6 5\n";
    const CliRun hidden =
        run("render roof.obj -o h.png --size 64x64 --lines crease --hidden-lines crease --crease-angle 30 --strict");
    EXPECT_EQ(hidden.exitCode, 0) << hidden.err;
    EXPECT_EQ(flat.exitCode, 0) << flat.err;
    EXPECT_TRUE(fs::exists(directory / "c.png"));
}

TEST_F(Cli, EveryShadingModeRendersWithoutNaN) {
    // Every model of the registry (passes/shade/ShadingModel.h), with extreme shininess on the specular ones and two
    // bands on the banded ones. The colours are 8-bit (shade.color and composite.final are RGBA8, and an EXR picture
    // is that converted), so a NaN cannot survive there: the float buffers are checked too, every EXR the dump's
    // manifest names (the G-buffer fields the deferred models shade from, the z-buffer).
    int floatBuffersChecked = 0;
    for (const ShadingModelTraits& traits : shadingModels()) {
        std::vector<std::string> settings = {""};
        if (traits.specular) settings = {" --shininess 0", " --shininess 1e6"};
        if (traits.bands) settings = {" --bands 2"};
        for (const std::string& setting : settings) {
            const std::string flags = std::string("--shading ") + traits.name + setting;
            SCOPED_TRACE(flags);
            const CliRun result = run("render " + model("spot_c3d.obj") +
                                      " -o a.exr --size 64x64 --dump d --request 'gbuffer.*' " + flags);
            ASSERT_EQ(result.exitCode, 0) << flags << ": " << result.err;
            const cv::Mat picture = readImage(directory / "a.exr");
            ASSERT_EQ(picture.depth(), CV_32F);
            EXPECT_TRUE(cv::checkRange(picture)) << flags << " wrote a NaN or Inf";
            const auto manifest = nlohmann::json::parse(readText(directory / "d" / "manifest.json"));
            int floatFiles = 0;
            for (const nlohmann::json& entry : manifest.at("files")) {
                const std::string file = entry.at("file").get<std::string>();
                if (fs::path(file).extension() != ".exr") continue;
                const cv::Mat buffer = readImage(directory / "d" / file);
                ASSERT_EQ(buffer.depth(), CV_32F) << file;
                cv::Point at;
                EXPECT_TRUE(cv::checkRange(buffer, true, &at))
                    << flags << ": " << file << " holds a NaN or Inf at " << at;
                ++floatFiles;
            }
            // normal, view, w, ndotv, depth, radial, materialid and the z-buffer.
            EXPECT_GE(floatFiles, 8) << manifest.dump();
            floatBuffersChecked += floatFiles;
            fs::remove(directory / "a.exr");
            fs::remove_all(directory / "d");
        }
    }
    EXPECT_GE(floatBuffersChecked, 8 * int(shadingModels().size()));
}

/** Pixels just off the model: not covered in `coverage` (255 on the model), with a covered 4-neighbour. */
std::vector<cv::Point> pixelsAroundCoverage(const cv::Mat& coverage) {
    std::vector<cv::Point> around;
    for (int row = 1; row + 1 < coverage.rows; ++row)
        for (int col = 1; col + 1 < coverage.cols; ++col) {
            if (coverage.at<uchar>(row, col) == 255) continue;
            bool touches = false;
            for (const cv::Point step : {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)})
                touches = touches || coverage.at<uchar>(cv::Point(col, row) + step) == 255;
            if (touches) around.emplace_back(col, row);
        }
    return around;
}

TEST_F(Cli, DefaultLookIsNeverWhiteOnWhite) {
    // A pure white OBJ cube, a textured glTF box and a white card seen face-on (no hull width there: the contour
    // edges it): the default look (cel, paper white, silhouette) must set
    // each model apart from the paper all around, where its lit band is the paper's colour.
    auto writeText = [](const fs::path& path, const std::string& text) { std::ofstream(path) << text; };
    // A closed white cube: every face counter-clockwise from outside.
    writeText(directory / "white.obj", "mtllib white.mtl\nusemtl White\n"
                                       "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                       "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                       "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
    writeText(directory / "white.mtl", "newmtl White\nKd 1 1 1\n");
    writeText(directory / "card.obj", "mtllib white.mtl\nusemtl White\n"
                                      "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    const std::string box =
        test::shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "box-textured.glb");
    for (const std::string& input : {std::string("white.obj"), box, std::string("card.obj")}) {
        fs::remove_all(directory / "d");
        const CliRun result =
            run("render " + input + " -o look.png --size 96x96 --camera auto --dump d --request gbuffer.coverage");
        ASSERT_EQ(result.exitCode, 0) << result.err;
        const cv::Mat picture = readImage(directory / "look.png");
        const cv::Mat coverage = readImage(directory / "d" / "coverage.png");
        const std::vector<cv::Point> boundary = pixelsAroundCoverage(coverage);
        ASSERT_GT(boundary.size(), 100u) << input;
        // A dark pixel at or next to each place just off the model (the silhouette lies outside the coverage, the
        // contour on its edge).
        std::size_t darkened = 0;
        for (const cv::Point& pixel : boundary) {
            bool dark = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const cv::Vec4b color = picture.at<cv::Vec4b>(pixel + cv::Point(dx, dy));
                    dark = dark || (color[0] < 128 && color[1] < 128 && color[2] < 128);
                }
            if (dark) ++darkened;
        }
        EXPECT_GE(double(darkened), 0.95 * double(boundary.size())) << input << ": the outline encloses the model";
    }
}

TEST_F(Cli, StatsListMaterialsAndTextures) {
    const std::string fox = test::shellQuoted(fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "fox.glb");
    const CliRun result = run("render " + fox + " -o fox.png --size 48x48 --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    const auto& materials = stats["scene"]["materials"];
    ASSERT_EQ(materials.size(), 1u);
    EXPECT_EQ(materials[0]["name"], "fox_material");
    EXPECT_EQ(materials[0]["alpha_mode"], "opaque");
    EXPECT_FALSE(materials[0]["base_color_texture"].is_null());
    EXPECT_EQ(materials[0]["metallic_factor"], 0.0); // the file's
    EXPECT_NEAR(materials[0]["roughness_factor"].get<double>(), 0.58, 1e-6);
    EXPECT_TRUE(materials[0]["metallic_roughness_texture"].is_null());
    EXPECT_EQ(stats["scene"]["images"]["count"], 1);
    EXPECT_EQ(stats["scene"]["images"]["decoded"], 1) << "the cel shading samples the texture";
    EXPECT_GT(stats["scene"]["images"]["decoded_bytes"].get<double>(), 0.0);

    // --shading none samples no colour: nothing is decoded.
    ASSERT_EQ(run("render " + fox + " -o none.png --size 48x48 --shading none --stats n.json").exitCode, 0);
    const auto none = nlohmann::json::parse(readText(directory / "n.json"));
    EXPECT_EQ(none["scene"]["images"]["decoded"], 0);
}

/** The pixels of `picture` (8-bit BGR) that are clearly of one primary: channel `channel` (0 blue, 2 red) above 100 and
 *  the other two below 60. */
int pixelsOf(const cv::Mat& picture, int channel) {
    int count = 0;
    for (int y = 0; y < picture.rows; ++y)
        for (int x = 0; x < picture.cols; ++x) {
            const cv::Vec3b bgr = picture.at<cv::Vec3b>(y, x);
            bool primary = bgr[channel] > 100;
            for (int other = 0; other < 3; ++other)
                if (other != channel) primary = primary && bgr[other] < 60;
            count += primary ? 1 : 0;
        }
    return count;
}

TEST_F(Cli, AnUndecodableTextureIsAWarningAndStrictMakesItBadInput) {
    // The texture is decoded only while rendering (the pass that samples it). Without --strict the material is drawn
    // without it and the warning names the model and the image; with --strict the still fails like a model that
    // cannot be read (exit 3, nothing written) and a batch's other model renders.
    auto writeText = [](const fs::path& path, const std::string& text) { std::ofstream(path) << text; };
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    writeText(directory / "bad.mtl", "newmtl skin\nKd 1 0 0\nmap_Kd bad.png\n");
    writeText(directory / "bad.png", "this is not a PNG");
    writeText(directory / "bad.obj", "mtllib bad.mtl\nusemtl skin\n" + triangle);
    writeText(directory / "good.obj", triangle);
    const CliRun lenient = run("render bad.obj -o lenient.png --size 32x32 --stats lenient.json");
    EXPECT_EQ(lenient.exitCode, 0) << lenient.err;
    EXPECT_NE(lenient.err.find("inkgraph: warning: image 0 'bad.png': cannot be decoded"), std::string::npos)
        << lenient.err;
    EXPECT_NE(lenient.err.find("drawn without it"), std::string::npos) << lenient.err;
    const auto stats = nlohmann::json::parse(readText(directory / "lenient.json"));
    EXPECT_EQ(stats["scene"]["images"]["unusable"][0]["reason"], "undecodable") << stats["scene"]["images"];
    // Drawn with its Kd alone: the triangle's pixels are red (the default comic look shades it, red stays ahead).
    EXPECT_GT(pixelsOf(readImage(directory / "lenient.png"), 2), 20)
        << "the material keeps its colour without the texture";

    const CliRun single = run("render bad.obj -o bad.png.out.png --size 32x32 --strict");
    EXPECT_EQ(single.exitCode, 3) << single.err;
    EXPECT_NE(single.err.find("inkgraph: --strict: '"), std::string::npos) << single.err;
    EXPECT_NE(single.err.find("bad.obj': image 0 'bad.png': cannot be decoded"), std::string::npos) << single.err;
    EXPECT_EQ(single.err.find("internal error"), std::string::npos) << single.err;
    EXPECT_FALSE(fs::exists(directory / "bad.png.out.png"));

    fs::create_directories(directory / "out");
    const CliRun batch = run("render bad.obj good.obj -o 'out/{name}.png' --size 32x32 --strict");
    EXPECT_EQ(batch.exitCode, 3) << batch.err;
    EXPECT_TRUE(fs::exists(directory / "out" / "good.png")) << batch.err;
    EXPECT_FALSE(fs::exists(directory / "out" / "bad.png"));
    EXPECT_EQ(readText(directory / "bad.png"), "this is not a PNG") << "the model's own texture is untouched";
}

TEST_F(Cli, AnObjectSmoothingTooCostlyForTheModelFailsItsStillAtOnce) {
    // The bunny smoothed over its whole radius: minutes of flooding, refused before any (exit 3, naming the flag and
    // a smoothing that fits); in a batch the next model is drawn.
    const std::string flags = " --size 64x64 --lines suggestive-object --suggestive-object-smoothing 1";
    const CliRun single = run("render " + model("bunny_c3d_70k.obj") + " -o b.png" + flags);
    EXPECT_EQ(single.exitCode, 3) << single.err;
    EXPECT_NE(single.err.find("--suggestive-object-smoothing 1 is too wide for this model"), std::string::npos)
        << single.err;
    EXPECT_NE(single.err.find(" or less fits, or 0 for none"), std::string::npos) << single.err;
    EXPECT_FALSE(fs::exists(directory / "b.png"));
    const CliRun batch =
        run("render " + model("bunny_c3d_70k.obj") + " " + model("suzanne_npm_4k.obj") + " -o '{name}.png'" + flags);
    EXPECT_EQ(batch.exitCode, 3) << batch.err;
    EXPECT_FALSE(fs::exists(directory / "bunny_c3d_70k.png"));
    EXPECT_TRUE(fs::exists(directory / "suzanne_npm_4k.png")) << batch.err;
}

TEST_F(Cli, WeldDistanceJoinsFacesWrittenApartAndKeepsTinyDetails) {
    // A square of two triangles whose shared diagonal is written twice, 1e-4 apart in depth (7e-5 of the model's
    // size), and with texture coordinates of their own on each side, so only the weld of positions (the edges'
    // adjacency, derived after the load) can join them: by default the diagonal is two border edges, with
    // --weld-distance 1e-3 it is none.
    auto writeText = [](const fs::path& path, const std::string& text) { std::ofstream(path) << text; };
    writeText(directory / "crack.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0.0001\nv 1 1 0.0001\nv 0 1 0\n"
                                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0\nvt 0.5 0.5\nvt 0 1\n"
                                       "f 1/1 2/2 3/3\nf 4/4 5/5 6/6\n");
    const auto borderEdges = [&](const std::string& flags) {
        const CliRun result = run("render crack.obj -o c.png --size 64x64 --lines border --stats c.json" + flags);
        EXPECT_EQ(result.exitCode, 0) << result.err;
        const auto stats = nlohmann::json::parse(readText(directory / "c.json"));
        return std::make_pair(stats["look"]["lines"][0]["edges_drawn"].get<int>(),
                              stats["scene"]["weld_distance"].get<double>());
    };
    EXPECT_EQ(borderEdges(""), std::make_pair(6, 1e-6));
    EXPECT_EQ(borderEdges(" --weld-distance 1e-3"), std::make_pair(4, 1e-3));

    // Triangles of 3.5e-7 of the model's size (5e-4 units, some 30 float steps at 500) beside a large one: merged
    // away by default (the weld distance is 1e-6 x 1414 units), kept with --weld-distance 0.
    writeText(directory / "tiny.obj", "v 0 0 0\nv 1000 0 0\nv 0 1000 0\nv 10 10 0\nv 10.0005 10 0\nv 10 10.0005 0\n"
                                      "f 1 2 3\nf 4 5 6\ng apart\nv 500 400 0\nv 500.0005 400 0\nv 500 400.0005 0\n"
                                      "f 7 8 9\n");
    const auto triangles = [&](const std::string& flags) {
        const CliRun result = run("render tiny.obj -o t.png --size 32x32 --stats t.json" + flags);
        EXPECT_EQ(result.exitCode, 0) << result.err;
        return nlohmann::json::parse(readText(directory / "t.json"))["scene"]["triangles"].get<int>();
    };
    EXPECT_EQ(triangles(""), 1);
    EXPECT_EQ(triangles(" --weld-distance 0"), 3);

    for (const std::string value : {"-1e-6", "0.02", "nan", "x"}) {
        const CliRun refused = run("render crack.obj -o r.png --size 16x16 --weld-distance " + value);
        EXPECT_EQ(refused.exitCode, 2) << value;
        EXPECT_NE(refused.err.find("--weld-distance: "), std::string::npos) << refused.err;
        EXPECT_FALSE(fs::exists(directory / "r.png"));
    }
}

TEST_F(Cli, AnObjsMissingMapIsListedAmongTheUnusableImagesOnce) {
    // The MTL reader finds the map missing at load (its warning names the library and the line); --stats lists it
    // with the images that cannot be used, by its name as written and without an index (the model holds no image of
    // it), once however many materials name it.
    auto writeText = [](const fs::path& path, const std::string& text) { std::ofstream(path) << text; };
    writeText(directory / "gone.mtl", "newmtl skin\nKd 1 0 0\nmap_Kd textures/skin.png\n"
                                      "newmtl cloth\nKd 0 1 0\nmap_Kd textures/skin.png\n");
    writeText(directory / "gone.obj", "mtllib gone.mtl\nusemtl skin\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                                      "vt 0 1\nf 1/1 2/2 3/3\n");
    const CliRun lenient = run("render gone.obj -o gone.png --size 32x32 --stats gone.json");
    EXPECT_EQ(lenient.exitCode, 0) << lenient.err;
    EXPECT_NE(lenient.err.find("gone.mtl' line 3: map_Kd 'textures/skin.png'"), std::string::npos) << lenient.err;
    const auto images = nlohmann::json::parse(readText(directory / "gone.json"))["scene"]["images"];
    ASSERT_EQ(images["unusable"].size(), 1u) << images;
    EXPECT_TRUE(images["unusable"][0]["image"].is_null()) << images;
    EXPECT_EQ(images["unusable"][0]["name"], "textures/skin.png") << images;
    EXPECT_EQ(images["unusable"][0]["reason"], "missing") << images;
    EXPECT_EQ(images["count"], 0) << images;
}

TEST_F(Cli, AnEmissiveImageThatCannotBeDecodedTakesTheEmissionWithIt) {
    // map_Ke without Ke multiplies the image by 1; an undecodable image left that factor alone and drew the triangle
    // white (unseen on the white paper). Now it is drawn as without the map_Ke line; --stats names the image.
    auto writeText = [](const fs::path& path, const std::string& text) { std::ofstream(path) << text; };
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
    writeText(directory / "glow.mtl", "newmtl skin\nKd 0.2 0.2 0.2\nmap_Ke glow.png\n");
    writeText(directory / "plain.mtl", "newmtl skin\nKd 0.2 0.2 0.2\n");
    writeText(directory / "glow.png", "this is not a PNG");
    writeText(directory / "glow.obj", "mtllib glow.mtl\nusemtl skin\n" + triangle);
    writeText(directory / "plain.obj", "mtllib plain.mtl\nusemtl skin\n" + triangle);
    const std::string flags = " --size 32x32 --shading flat --lines none";
    const CliRun glow = run("render glow.obj -o glow-out.png --stats glow.json" + flags);
    EXPECT_EQ(glow.exitCode, 0) << glow.err;
    EXPECT_NE(glow.err.find("image 0 'glow.png': cannot be decoded"), std::string::npos) << glow.err;
    ASSERT_EQ(run("render plain.obj -o plain-out.png" + flags).exitCode, 0);
    const cv::Mat drawn = readImage(directory / "glow-out.png");
    EXPECT_EQ(cv::norm(drawn, readImage(directory / "plain-out.png"), cv::NORM_INF), 0.0);
    std::vector<cv::Mat> channels;
    cv::split(drawn, channels);
    EXPECT_GT(cv::countNonZero(channels[1] < 128), 20) << "the dark grey triangle is drawn, not white";
    const auto stats = nlohmann::json::parse(readText(directory / "glow.json"));
    EXPECT_EQ(stats["scene"]["materials"][0]["emissive_texture"], "glow.png") << stats["scene"]["materials"];
    EXPECT_FALSE(stats["scene"]["materials"][0].contains("emissive_factor")) << "no emission is drawn";

    // `Kd 0 0 0` beside a map_Kd draws the map as it is; an undecodable map leaves the Kd as written, not white.
    writeText(directory / "black.mtl", "newmtl skin\nKd 0 0 0\nmap_Kd glow.png\n");
    writeText(directory / "black.obj", "mtllib black.mtl\nusemtl skin\n" + triangle);
    ASSERT_EQ(run("render black.obj -o black-out.png" + flags).exitCode, 0);
    std::vector<cv::Mat> black;
    cv::split(readImage(directory / "black-out.png"), black);
    EXPECT_GT(cv::countNonZero(black[1] < 60), 20) << "the triangle is drawn black";
}

TEST_F(Cli, AMissingGltfTextureIsAWarningAsAnObjOneIs) {
    // The Khronos textured box with its image made an external file that is not there and its base colour factor
    // blue: drawn with the factor alone, with a texture-missing warning naming the image; --strict refuses it with
    // exit 3 and writes nothing.
    std::ofstream(directory / "missing.glb", std::ios::binary) << test::editedGlb(
        fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "box-textured.glb", [](nlohmann::json& gltf) {
            gltf["images"][0] = {{"uri", "gone.png"}};
            gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.0, 0.0, 1.0, 1.0};
        });
    const CliRun lenient = run("render missing.glb -o lenient.png --size 32x32 --stats lenient.json --orbit 30,30");
    EXPECT_EQ(lenient.exitCode, 0) << lenient.err;
    EXPECT_NE(lenient.err.find("warning: image 0 'gone.png': its file '"), std::string::npos) << lenient.err;
    const auto stats = nlohmann::json::parse(readText(directory / "lenient.json"));
    EXPECT_EQ(stats["scene"]["images"]["unusable"][0]["reason"], "missing") << stats["scene"]["images"];
    EXPECT_GT(pixelsOf(readImage(directory / "lenient.png"), 0), 20) << "drawn with its base colour factor";

    const CliRun strict = run("render missing.glb -o strict.png --size 32x32 --orbit 30,30 --strict");
    EXPECT_EQ(strict.exitCode, 3) << strict.err;
    EXPECT_NE(strict.err.find("inkgraph: --strict: '"), std::string::npos) << strict.err;
    EXPECT_FALSE(fs::exists(directory / "strict.png"));
}

TEST_F(Cli, TheDumpManifestNamesTheObjects) {
    // Issue 36: the Khronos textured box instanced by two nodes under one unnamed root, touching face to face at
    // x = 0: a node named "left" and an unnamed one (its object is named by its mesh, "Mesh"). objectid.exr holds
    // exactly 0, 1 and 2, the manifest maps 1 and 2 to the nodes in the order their meshes come, --stats counts two
    // objects, and the object-boundary line is drawn between them (one material: material-boundary draws nothing).
    std::ofstream(directory / "two.glb", std::ios::binary) << test::editedGlb(
        fs::path(INKGRAPH_SOURCE_ROOT) / "models" / "characters" / "box-textured.glb", [](nlohmann::json& gltf) {
            gltf["nodes"][0]["children"] = {1, 2};
            gltf["nodes"][1] = {{"mesh", 0}, {"name", "left"}, {"translation", {-0.5, 0.0, 0.0}}};
            gltf["nodes"][2] = {{"mesh", 0}, {"translation", {0.5, 0.0, 0.0}}};
        });
    const CliRun result = run("render two.glb -o two.png --size 64x64 --orbit 30,30 --lines "
                              "object-boundary,material-boundary --dump d --request gbuffer.objectId --stats s.json");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto manifest = nlohmann::json::parse(readText(directory / "d" / "manifest.json"));
    const auto expected = nlohmann::json::parse(R"([
        {"id": 1, "name": "left", "node_path": ["", "left"], "meshes": ["left"]},
        {"id": 2, "name": "Mesh", "node_path": ["", ""], "meshes": ["Mesh"]}])");
    EXPECT_EQ(manifest["objects"], expected) << manifest["objects"].dump();
    const cv::Mat ids = readImage(directory / "d" / "objectid.exr");
    ASSERT_EQ(ids.type(), CV_32FC1);
    std::map<float, int> pixelsOfId;
    for (int row = 0; row < ids.rows; ++row)
        for (int col = 0; col < ids.cols; ++col) ++pixelsOfId[ids.at<float>(row, col)];
    ASSERT_EQ(pixelsOfId.size(), 3u) << "ids other than 0, 1 and 2";
    EXPECT_GT(pixelsOfId[1.0f], 100);
    EXPECT_GT(pixelsOfId[2.0f], 100);
    const auto stats = nlohmann::json::parse(readText(directory / "s.json"));
    EXPECT_EQ(stats["scene"]["objects"], 2);
    EXPECT_EQ(stats["scene"]["meshes"], 2);
    EXPECT_GT(cv::countNonZero(readImage(directory / "d" / "skeleton-object-boundary.png")), 10);
    EXPECT_EQ(cv::countNonZero(readImage(directory / "d" / "skeleton-material-boundary.png")), 0);

    // Without objectId in the dump, no list.
    const CliRun depthOnly =
        run("render two.glb -o two.png --size 32x32 --lines none --dump e --request gbuffer.depth");
    ASSERT_EQ(depthOnly.exitCode, 0) << depthOnly.err;
    EXPECT_FALSE(nlohmann::json::parse(readText(directory / "e" / "manifest.json")).contains("objects"));
}

TEST_F(Cli, TheDumpManifestNamesTheMeshesAndMaterialsOfTheLabels) {
    // Issue 37: two quads of two triangles each, OBJ objects with materials "paint" and "metal"; the second lies
    // behind the first and half of it is hidden. `--request gbuffer.*` dumps the labels (meshid.exr, triangleid.exr,
    // barycentric.exr), the manifest's meshes give each mesh's id, object, material and triangle range, its materials
    // the names; the hidden border has its own mask beside the visible one.
    std::ofstream(directory / "two.mtl") << "newmtl paint\nKd 0.8 0.2 0.2\nnewmtl metal\nKd 0.2 0.2 0.8\n";
    std::ofstream(directory / "two.obj") << "mtllib two.mtl\n"
                                            "v -2.2 -1 0.5\nv -0.2 -1 0.5\nv -0.2 1 0.5\nv -2.2 1 0.5\n"
                                            "v -1 -0.6 -0.5\nv 1 -0.6 -0.5\nv 1 0.6 -0.5\nv -1 0.6 -0.5\n"
                                            "o front\nusemtl paint\nf 1 2 3\nf 1 3 4\n"
                                            "o back\nusemtl metal\nf 5 6 7\nf 5 7 8\n";
    const CliRun result = run("render two.obj -o two.png --size 96x96 --eye 0,0,7 --target -0.4,0,0 --lines border "
                              "--hidden-lines border --hidden-dash none --dump d --request 'gbuffer.*'");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const auto manifest = nlohmann::json::parse(readText(directory / "d" / "manifest.json"));
    const auto meshes = nlohmann::json::parse(R"([
        {"id": 1, "drawn": true, "name": "front", "node_path": ["front"], "object_id": 1, "material_id": 1,
         "material": "paint", "first_triangle": 0, "triangle_count": 2},
        {"id": 2, "drawn": true, "name": "back", "node_path": ["back"], "object_id": 2, "material_id": 2,
         "material": "metal", "first_triangle": 2, "triangle_count": 2}])");
    EXPECT_EQ(manifest["meshes"], meshes) << manifest["meshes"].dump();
    EXPECT_EQ(manifest["materials"],
              nlohmann::json::parse(R"([{"id": 1, "name": "paint"}, {"id": 2, "name": "metal"}])"))
        << manifest["materials"].dump();
    // The ids in the files are the ones the manifest lists: triangles 1 and 2 on mesh 1, 3 and 4 on mesh 2.
    const cv::Mat triangles = readImage(directory / "d" / "triangleid.exr");
    const cv::Mat meshIds = readImage(directory / "d" / "meshid.exr");
    const cv::Mat weights = readImage(directory / "d" / "barycentric.exr");
    ASSERT_EQ(triangles.type(), CV_32FC1);
    ASSERT_EQ(meshIds.type(), CV_32FC1);
    ASSERT_EQ(weights.channels(), 4);
    std::map<float, int> pixelsOfTriangle;
    int wrongMesh = 0;
    for (int row = 0; row < triangles.rows; ++row)
        for (int col = 0; col < triangles.cols; ++col) {
            const float triangle = triangles.at<float>(row, col);
            ++pixelsOfTriangle[triangle];
            const float mesh = triangle == 0.0f ? 0.0f : triangle <= 2.0f ? 1.0f : 2.0f;
            wrongMesh += meshIds.at<float>(row, col) != mesh;
        }
    ASSERT_EQ(pixelsOfTriangle.size(), 5u) << "ids other than 0 to 4";
    for (const float id : {1.0f, 2.0f, 3.0f, 4.0f}) EXPECT_GT(pixelsOfTriangle[id], 50) << id;
    EXPECT_EQ(wrongMesh, 0) << "pixels whose meshId is not their triangle's mesh";
    // The hidden part of the back quad's border has a mask of its own, solid with --hidden-dash none.
    EXPECT_GT(cv::countNonZero(readImage(directory / "d" / "lines-border.png")), 50);
    EXPECT_GT(cv::countNonZero(readImage(directory / "d" / "lines-hidden-border.png")), 20);

    // Without an id field in the dump, neither list.
    const CliRun depthOnly =
        run("render two.obj -o two.png --size 32x32 --lines none --dump e --request gbuffer.depth");
    ASSERT_EQ(depthOnly.exitCode, 0) << depthOnly.err;
    const auto plain = nlohmann::json::parse(readText(directory / "e" / "manifest.json"));
    EXPECT_FALSE(plain.contains("meshes"));
    EXPECT_FALSE(plain.contains("materials"));
}

TEST_F(Cli, MsaaShadesForwardSaysSoAndIsCappedAtTheDriversSamples) {
    const std::string suzanne = model("suzanne_npm_4k.obj");
    ASSERT_EQ(run("render " + suzanne + " -o four.png --size 48x48 --msaa 4 --stats four.json").exitCode, 0);
    const auto stats = nlohmann::json::parse(readText(directory / "four.json"));
    EXPECT_EQ(stats["look"]["msaa"], 4);
    EXPECT_EQ(stats["look"]["shading_mode"], "forward");
    EXPECT_EQ(stats["look"]["shading_forward_because"],
              "the shading is multisampled (--msaa 4) and the G-buffer holds one sample per pixel");
    ASSERT_EQ(run("render " + suzanne + " -o one.png --size 48x48 --stats one.json").exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(readText(directory / "one.json"))["look"]["msaa"], 1);
    ASSERT_EQ(run("render " + suzanne + " -o none.png --size 48x48 --shading none --stats none.json").exitCode, 0);
    EXPECT_FALSE(nlohmann::json::parse(readText(directory / "none.json"))["look"].contains("msaa"));

    // What the driver draws is known once there is a context: beyond it, a usage error that names the limit, and no
    // picture. llvmpipe draws 4; a driver that draws 8 renders.
    const CliRun eight = run("render " + suzanne + " -o eight.png --size 48x48 --msaa 8");
    if (eight.exitCode == 0) {
        EXPECT_TRUE(fs::exists(directory / "eight.png"));
    } else {
        EXPECT_EQ(eight.exitCode, 2) << eight.err;
        const std::regex refusal("inkgraph: --msaa 8: this driver \\('[^']+'\\) draws at most [124] samples per pixel "
                                 "\\(GL_MAX_SAMPLES\\)\n");
        EXPECT_TRUE(std::regex_search(eight.err, refusal)) << eight.err;
        EXPECT_FALSE(fs::exists(directory / "eight.png"));
    }
}

TEST_F(Cli, ACrashTellsTheSignalTheBuildAndTheStackThenEndsByTheSignal) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "a sanitized build reports crashes through its sanitizer: app/main.cpp installs no report there";
#endif
    // No input crashes the program (tests/fuzz, the bad-input matrix), so the signal is sent as a fault would raise
    // it, while the run waits for its --list on a FIFO: main() has installed the report before it reads anything.
    ASSERT_EQ(::mkfifo((directory / "list").c_str(), 0600), 0);
    for (const auto& [signal, name] :
         {std::pair{"SEGV", "SIGSEGV (segmentation fault)"}, std::pair{"ABRT", "SIGABRT (aborted)"}}) {
        SCOPED_TRACE(name);
        // Opening the FIFO to write waits until the run has opened it to read. No core file (ulimit): the test
        // checks that the run left nothing in its folder.
        std::ofstream(directory / "crash.sh")
            << "ulimit -c 0\nLP_NUM_THREADS=1 " << test::shellQuoted(INKGRAPH_EXECUTABLE)
            << " render --list list -o '{name}.png' 2> err.txt &\npid=$!\nexec 3> list\nkill -" << signal
            << " $pid\nwait $pid\necho $? > status.txt\n";
        double peakMib = 0.0;
        ASSERT_EQ(test::runShell("cd " + test::shellQuoted(directory) + " && timeout 120 bash crash.sh", peakMib), 0);
        const int expectedStatus = 128 + (std::string(signal) == "SEGV" ? SIGSEGV : SIGABRT);
        EXPECT_EQ(readText(directory / "status.txt"), std::to_string(expectedStatus) + "\n");
        const std::string err = readText(directory / "err.txt");
        EXPECT_NE(err.find("inkgraph: internal error: " + std::string(name) + " in " + versionLine() +
                           ". This is a bug: please report it with the command that caused it and the lines below.\n"),
                  std::string::npos)
            << err;
        // The stack, as FILE(+OFFSET)[ADDRESS] lines: the handler's frame in the executable, and libc's below it.
        const std::regex frame(R"(\n[^\n]*inkgraph\(\+0x[0-9a-f]+\)\[0x[0-9a-f]+\]\n)");
        EXPECT_TRUE(std::regex_search(err, frame)) << err;
        EXPECT_NE(err.find("libc.so"), std::string::npos) << err;
        EXPECT_NE(err.find("`addr2line -Cfe FILE OFFSET` names its function)\n"), std::string::npos) << err;
        EXPECT_EQ(listFiles(directory), (std::vector<std::string>{"crash.sh", "err.txt", "list", "status.txt"}));
    }
}

} // namespace
} // namespace inkgraph
