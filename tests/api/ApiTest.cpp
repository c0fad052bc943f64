// The public C++ API through libinkgraph.so, everything that fails or finishes before a GL context is needed: loading
// scenes, describing looks and frames, buffer names, images written and read back (app/ImageFiles), error kinds.
#include <inkgraph/inkgraph.h>

#include "render/ImageFiles.h"
#include "tests/api/ApiTestSupport.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>

#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

namespace ig = inkgraph::api;

namespace inkgraph::test {
namespace {

const std::string kModels = std::string(INKGRAPH_SOURCE_ROOT) + "/models/";

class ApiScene : public TestFolder {
protected:
    /** One triangle mesh "tri" instanced by a node "a" and by an unnamed child (moved 2 along x) of a node "group". */
    std::filesystem::path writeTwoInstanceGltf() const {
        const std::filesystem::path gltf = directory / "two.gltf";
        writeText(gltf, R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"name": "a", "mesh": 0}, {"name": "group", "children": [2]},
                      {"mesh": 0, "translation": [2, 0, 0]}],
            "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}}]}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 0]}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}],
            "buffers": [{"byteLength": 36,
                         "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})");
        return gltf;
    }
};

TEST_F(ApiScene, MissingFileIsAnInputErrorNamingTheFile) {
    const ig::Error error = errorOf([&] { ig::Scene::load((directory / "absent.obj").string()); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Input) << error.what();
    EXPECT_EQ(error.exitCode(), 3);
    EXPECT_NE(std::string(error.what()).find("absent.obj"), std::string::npos) << error.what();
}

TEST_F(ApiScene, UnreadableFileIsAnInputErrorNamingTheFile) {
    const std::filesystem::path broken = directory / "broken.glb";
    writeText(broken, "this is not a binary glTF file");
    const ig::Error error = errorOf([&] { ig::Scene::load(broken.string()); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Input) << error.what();
    EXPECT_NE(std::string(error.what()).find("broken.glb"), std::string::npos) << error.what();
}

TEST_F(ApiScene, CountsWhatTheFileHolds) {
    // A unit square as two triangles over four vertices, one object.
    const std::filesystem::path square = directory / "square.obj";
    writeText(square, "o Square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    const ig::Scene scene = ig::Scene::load(square.string());
    EXPECT_EQ(scene.path(), square.string());
    EXPECT_EQ(scene.triangleCount(), 2u);
    EXPECT_EQ(scene.vertexCount(), 4u);
    EXPECT_EQ(scene.meshCount(), 1u);
    EXPECT_TRUE(scene.warnings().empty());
}

TEST_F(ApiScene, AMovedFromSceneIsStillTheScene) {
    // A move left the source empty, and every later call on it crashed (triangleCount(), rendering it).
    const std::filesystem::path square = directory / "square.obj";
    writeText(square, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
    ig::Scene scene = ig::Scene::load(square.string());
    const ig::Scene moved = std::move(scene);
    EXPECT_EQ(moved.triangleCount(), 2u);
    EXPECT_EQ(scene.triangleCount(), 2u); // NOLINT(bugprone-use-after-move): what is tested
    EXPECT_EQ(scene.path(), square.string());
    ig::Scene assigned = ig::Scene::load(square.string());
    assigned = std::move(scene);
    EXPECT_EQ(scene.meshCount(), 1u); // NOLINT(bugprone-use-after-move)
}

TEST_F(ApiScene, MeshesGiveTheirIdsAndTriangleRanges) {
    // Issue 37: the same two-instance glTF as below, one triangle each: meshes 1 and 2, triangle ids 1 and 2, one
    // unnamed material (id 1, no name) and the two objects.
    const std::filesystem::path gltf = writeTwoInstanceGltf();
    const std::vector<ig::SceneMesh> meshes = ig::Scene::load(gltf.string()).meshes();
    ASSERT_EQ(meshes.size(), 2u);
    for (std::size_t index = 0; index < 2; ++index) {
        SCOPED_TRACE(index);
        EXPECT_EQ(meshes[index].id, index + 1);
        EXPECT_EQ(meshes[index].objectId, index + 1);
        EXPECT_EQ(meshes[index].materialId, 1u);
        EXPECT_EQ(meshes[index].material, "");
        EXPECT_EQ(meshes[index].firstTriangle, index);
        EXPECT_EQ(meshes[index].triangleCount, 1u);
    }
    EXPECT_EQ(meshes[0].name, "a");
    EXPECT_EQ(meshes[1].nodePath, (std::vector<std::string>{"group", ""}));
}

TEST_F(ApiScene, ObjectsAreTheNodeInstancesInOrder) {
    // One triangle mesh "tri" instanced by a node "a" and by an unnamed child of node "group": two objects, ids in
    // the order their meshes come, the unnamed one named by its mesh (issue 36: the "objectId" buffer's values).
    const std::filesystem::path gltf = writeTwoInstanceGltf();
    const std::vector<ig::SceneObject> objects = ig::Scene::load(gltf.string()).objects();
    ASSERT_EQ(objects.size(), 2u);
    EXPECT_EQ(objects[0].id, 1u);
    EXPECT_EQ(objects[0].name, "a");
    EXPECT_EQ(objects[0].nodePath, std::vector<std::string>{"a"});
    EXPECT_EQ(objects[0].meshes, std::vector<std::string>{"a"}) << "a mesh is named by its node";
    EXPECT_EQ(objects[1].id, 2u);
    EXPECT_EQ(objects[1].name, "tri");
    EXPECT_EQ(objects[1].nodePath, (std::vector<std::string>{"group", ""}));
    EXPECT_EQ(objects[1].meshes, std::vector<std::string>{"tri"});
    // A file without nodes is one object, named by its mesh.
    const std::filesystem::path stl = directory / "one.stl";
    writeText(stl, "solid one\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                   "endfacet\nendsolid one\n");
    const std::vector<ig::SceneObject> single = ig::Scene::load(stl.string()).objects();
    ASSERT_EQ(single.size(), 1u);
    EXPECT_EQ(single[0].id, 1u);
    EXPECT_TRUE(single[0].nodePath.empty());
}

TEST_F(ApiScene, PoseOptionsAreCheckedAsTheirFlags) {
    ig::SceneOptions options;
    options.time = 1.5; // without an animation
    const ig::Error error = errorOf([&] { ig::Scene::load(kModels + "suzanne_npm_4k.obj", options); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
    EXPECT_STREQ(error.what(), "Scene::load(): --time has no effect without --animation");
    options.animation = "Walk";
    options.time = -1.0;
    EXPECT_STREQ(errorOf([&] { ig::Scene::load(kModels + "suzanne_npm_4k.obj", options); }).what(),
                 "Scene::load(): --time: expected seconds >= 0, got '-1'");
}

TEST_F(ApiScene, FaceOptionsAreCheckedAsTheirFlags) {
    ig::SceneOptions options;
    options.expressions = {{"blink", 1.5}};
    const ig::Error weight = errorOf([&] { ig::Scene::load(kModels + "suzanne_npm_4k.obj", options); });
    EXPECT_EQ(weight.kind(), ig::Error::Kind::Usage);
    EXPECT_STREQ(weight.what(), "Scene::load(): SceneOptions::expressions: the weight of 'blink' must lie in [0, 1], "
                                "got 1.5");
    options.expressions = {{"blink", 1.0}};
    const ig::Error obj = errorOf([&] { ig::Scene::load(kModels + "suzanne_npm_4k.obj", options); });
    EXPECT_EQ(obj.kind(), ig::Error::Kind::Input) << obj.what();
    EXPECT_NE(std::string(obj.what()).find("--expression: obj files have no VRM expressions or look-at"),
              std::string::npos)
        << obj.what();
    options.expressions.clear();
    options.lookAt = ig::Vec3{0.0, std::nan(""), 0.0};
    EXPECT_STREQ(errorOf([&] { ig::Scene::load(kModels + "suzanne_npm_4k.obj", options); }).what(),
                 "Scene::load(): SceneOptions::lookAt: --look-at: 'nan' is not a finite number");
}

TEST_F(ApiScene, WeldDistanceIsTheLoadsAndCheckedAsItsFlag) {
    // Triangles of 5e-4 units beside one of 1000: merged away at the default distance (1e-6 x 1414 units), kept at 0,
    // from a file and from arrays alike.
    const std::filesystem::path obj = directory / "tiny.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1000 0 0\nv 0 1000 0\nv 10 10 0\nv 10.0005 10 0\nv 10 10.0005 0\n"
                          "f 1 2 3\nf 4 5 6\n";
    ig::SceneOptions exact;
    exact.weldDistance = 0.0;
    EXPECT_EQ(ig::Scene::load(obj.string()).triangleCount(), 1u);
    EXPECT_EQ(ig::Scene::load(obj.string(), exact).triangleCount(), 2u);
    const float vertices[] = {0, 0, 0, 1000, 0, 0, 0, 1000, 0, 10, 10, 0, 10.0005f, 10, 0, 10, 10.0005f, 0};
    const std::uint32_t faces[] = {0, 1, 2, 3, 4, 5};
    ig::MeshArrays arrays;
    arrays.vertices = vertices;
    arrays.vertexCount = 6;
    arrays.faces = faces;
    arrays.faceCount = 2;
    EXPECT_EQ(ig::Scene::fromArrays(arrays, "tiny", exact).triangleCount(), 2u);
    EXPECT_EQ(ig::Scene::fromArrays(arrays, "tiny").triangleCount(), 1u);

    ig::SceneOptions coarse;
    coarse.weldDistance = 0.02;
    const ig::Error error = errorOf([&] { ig::Scene::load(obj.string(), coarse); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
    EXPECT_STREQ(error.what(), "Scene::load(): SceneOptions::weldDistance: --weld-distance: expected 0 to 0.01, got "
                               "'0.02'");
    coarse.weldDistance = std::nan("");
    EXPECT_STREQ(errorOf([&] { ig::Scene::fromArrays(arrays, "tiny", coarse); }).what(),
                 "Scene::fromArrays(): SceneOptions::weldDistance: --weld-distance: 'nan' is not a finite number");
    const ig::Error look = errorOf([] { ig::Look::fromArguments({"--weld-distance", "0"}); });
    EXPECT_NE(std::string(look.what()).find("give SceneOptions::weldDistance to Scene::load()"), std::string::npos)
        << look.what();
}

TEST(ApiLook, RefusesAFlagThatIsNotTheLooksNamingItsPlace) {
    const ig::Error camera = errorOf([] { ig::Look::fromArguments({"--shading", "cel", "--eye", "0,0,5"}); });
    EXPECT_EQ(camera.kind(), ig::Error::Kind::Usage);
    EXPECT_EQ(camera.exitCode(), 2);
    EXPECT_STREQ(camera.what(), "Look::fromArguments(): '--eye' is not a look flag (give it to the Frame)");
    EXPECT_STREQ(errorOf([] { ig::Look().set("--size", "64x64"); }).what(),
                 "Look::set(): '--size' is not a look flag (give Frame::width and height)");
    EXPECT_STREQ(errorOf([] { ig::Look().set("--animation", "Walk"); }).what(),
                 "Look::set(): '--animation' is not a look flag (give it to the Frame)");
    EXPECT_STREQ(errorOf([] { ig::Look::fromArguments({"--frobnicate"}); }).what(),
                 "Look::fromArguments(): unknown option '--frobnicate'");
    EXPECT_STREQ(errorOf([] { ig::Look::fromArguments({"bunny.obj"}); }).what(),
                 "Look::fromArguments(): 'bunny.obj' is not a flag");
    EXPECT_STREQ(errorOf([] { ig::Look().set("shading", "comic"); }).what(),
                 "Look::set(): 'shading' is not a flag (did you mean '--shading'?)");
    // The command line's "--NAME=VALUE" is the same flag, refused in the same place.
    EXPECT_STREQ(errorOf([] {
                     ig::Look::fromArguments({"--shading=cel", "--eye=0,0,5"});
                 }).what(),
                 "Look::fromArguments(): '--eye' is not a look flag (give it to the Frame)");
    EXPECT_STREQ(errorOf([] {
                     ig::Frame::fromArguments({"--orbit=30,10", "--lines=contour"});
                 }).what(),
                 "Frame::fromArguments(): '--lines' is not a frame flag (give it to the Look)");
    EXPECT_EQ(ig::Look::fromArguments({"--shading=cel"}).arguments(), (std::vector<std::string>{"--shading", "cel"}));
    EXPECT_EQ(ig::Frame::fromArguments({"--orbit=30,10"}).orbit->azimuth, 30.0);
}

TEST(ApiLook, RefusesABadValueInTheCommandLinesWords) {
    const ig::Error error = errorOf([] { ig::Look::fromArguments({"--bands", "many"}); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
    EXPECT_STREQ(error.what(), "Look::fromArguments(): --bands: expected a whole number from 2 to 256, got 'many'");
    const std::string lines = errorOf([] { ig::Look().set("--lines", "contour,sketchy"); }).what();
    EXPECT_EQ(lines.rfind("Look::set(): --lines: unknown line type 'sketchy' (available: ", 0), 0u) << lines;
    EXPECT_STREQ(errorOf([] { ig::Look().set("--bands", ""); }).what(), "Look::set(): --bands: empty value");
    // A misspelt flag with a value is named as unknown, not as one that takes no value.
    EXPECT_STREQ(errorOf([] { ig::Look().set("--shadin", "cel"); }).what(), "Look::set(): unknown option '--shadin'");
}

TEST(ApiLook, AValueOfMegabytesIsQuotedByItsStart) {
    // The library takes strings of any length; a megabyte value made a megabyte message.
    const std::string huge(1 << 20, '7');
    const std::string bands = errorOf([&] { ig::Look().set("--bands", huge); }).what();
    EXPECT_EQ(bands, "Look::set(): --bands: '" + huge.substr(0, 60) +
                         "... (1048576 bytes)' lies beyond a double's range (about 1e-308 to 1e308)");
    const std::string choice = errorOf([&] { ig::Look().setLineChoice("suggestive-stencil", huge); }).what();
    EXPECT_LT(choice.size(), 1000u) << choice.substr(0, 1000);
    EXPECT_NE(choice.find("... (1048576 bytes)"), std::string::npos) << choice.substr(0, 1000);
    const std::string flag = errorOf([&] { ig::Look().set("--" + huge, "1"); }).what();
    EXPECT_LT(flag.size(), 1000u) << flag.substr(0, 1000);
}

TEST(ApiLook, RulesBetweenFlagsWaitForTheWholeLook) {
    // fromArguments() has the whole look: a flag without effect is refused at once.
    EXPECT_STREQ(errorOf([] {
                     ig::Look::fromArguments({"--shading", "phong", "--bands", "4"});
                 }).what(),
                 "Look::fromArguments(): --bands has no effect with --shading phong (it applies to cel and auto)");
    // set() checks one flag; the shading that makes --shininess count may come next.
    ig::Look look;
    look.set("--shininess", "8").set("--shading", "phong");
    EXPECT_EQ(look.arguments(), (std::vector<std::string>{"--shininess", "8", "--shading", "phong"}));
}

TEST(ApiLook, ATypedSetterOfSeveralFlagsIsAllOrNothing) {
    // setLineStyle() gives the width, then the colour: a refused colour left the width set.
    ig::Look look;
    const ig::LineStyle before = look.lineStyle(ig::LineType::Contour);
    EXPECT_STREQ(errorOf([&] {
                     look.setLineStyle(ig::LineType::Contour, {5.0, {2.0, 0.0, 0.0, 1.0}});
                 }).what(),
                 "Look::setLineStyle(): --contour-color: channels must lie in [0, 1], got '2,0,0,1'");
    EXPECT_TRUE(look.arguments().empty());
    EXPECT_EQ(look.lineStyle(ig::LineType::Contour).width, before.width);
    // setStrokes() gives the length first and the dash last.
    ig::StrokeSettings strokes = look.strokes();
    strokes.minLength = strokes.minLength + 2.0;
    strokes.hiddenDashOn = 0.5; // under a pixel
    EXPECT_THROW(look.setStrokes(strokes), ig::Error);
    EXPECT_TRUE(look.arguments().empty());
    // What is accepted is set whole.
    look.setLineStyle(ig::LineType::Contour, {5.0, {1.0, 0.0, 0.0, 1.0}});
    EXPECT_EQ(look.arguments(), (std::vector<std::string>{"--contour-width", "5", "--contour-color", "1,0,0,1"}));
}

using ApiStyle = TestFolder;

TEST_F(ApiStyle, AStyleFileIsTheLooksFlags) {
    const std::filesystem::path style = directory / "house.style";
    writeText(style, "# house style\nshading = comic\nlines = contour, suggestive\n");
    const ig::Look look = ig::Look::fromStyleFile(style.string());
    EXPECT_EQ(look.arguments(), (std::vector<std::string>{"--shading", "comic", "--lines", "contour,suggestive",
                                                          "--style", style.string()}));
}

TEST_F(ApiStyle, AFrameSettingInAStyleFileIsRefusedWithItsLine) {
    const std::filesystem::path style = directory / "sized.style";
    writeText(style, "shading = comic\nsize = 640x480\n");
    const ig::Error error = errorOf([&] { ig::Look::fromStyleFile(style.string()); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
    EXPECT_EQ(std::string(error.what()), "Look::fromStyleFile(): --style '" + style.string() +
                                             "' line 2: '--size' is not a look flag (give Frame::width and height)");
}

TEST_F(ApiStyle, AMissingStyleFileIsNamed) {
    const ig::Error error = errorOf([&] { ig::Look::fromStyleFile((directory / "absent.style").string()); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
    EXPECT_NE(std::string(error.what()).find("absent.style"), std::string::npos) << error.what();
}

/** The names a flag's refusal of `value` lists as available, in its order. */
std::vector<std::string> availableNames(const std::string& flag) {
    const std::string message = errorOf([&] { ig::Look().set(flag, "bogus"); }).what();
    const std::size_t start = message.find("(available: ");
    const std::size_t end = message.find_first_of(";)", start);
    std::vector<std::string> names;
    std::string list = message.substr(start + 12, end - start - 12);
    for (std::size_t comma; (comma = list.find(", ")) != std::string::npos; list.erase(0, comma + 2))
        names.push_back(list.substr(0, comma));
    names.push_back(list);
    return names;
}

// The public enums are written out in the header, which includes nothing of the registries: their names, in order,
// must be the registries' (a line type or shading model added there and not here fails this).
TEST(ApiNames, TheEnumsAreTheRegistriesInTheirOrder) {
    std::vector<std::string> lineTypes;
    for (int type = 0; type <= int(ig::LineType::MeshSilhouette); ++type)
        lineTypes.push_back(ig::nameOf(static_cast<ig::LineType>(type)));
    EXPECT_EQ(lineTypes, availableNames("--lines"));
    std::vector<std::string> shadings;
    for (int shading = 0; shading <= int(ig::Shading::Auto); ++shading)
        shadings.push_back(ig::nameOf(static_cast<ig::Shading>(shading)));
    EXPECT_EQ(shadings, availableNames("--shading"));
    std::vector<std::string> orientations;
    for (int method = 0; method <= int(ig::FaceOrientation::AfterVertices); ++method)
        orientations.push_back(ig::nameOf(static_cast<ig::FaceOrientation>(method)));
    EXPECT_EQ(orientations, availableNames("--face-orientation"));
    for (const std::string& name : lineTypes) EXPECT_EQ(ig::nameOf(ig::lineTypeNamed(name)), name);
    EXPECT_STREQ(
        errorOf([] { ig::lineTypeNamed("sketchy"); }).what(),
        "lineTypeNamed(): no line type 'sketchy' (there are: hidden-mesh-silhouette, hidden-crease, hidden-border, "
        "hidden-intersection, hidden-suggestive-object, outline, silhouette, normal-edge, depth-edge, crease, border, "
        "intersection, material-boundary, object-boundary, suggestive, suggestive-object, contour, mesh-silhouette)");
}

TEST(ApiBufferNames, AreTheLooksWithoutTheGraphsNames) {
    const std::vector<std::string> names =
        ig::bufferNames(ig::Look().setLines({ig::LineType::Contour, ig::LineType::Crease}));
    for (const std::string name :
         {"normal", "nDotV", "depth", "materialId", "gbuffer.*", "lines.contour", "lines.crease", "lines.*", "picture"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    for (const std::string& name : names) {
        EXPECT_EQ(name.find("strokes"), std::string::npos) << name;
        EXPECT_EQ(name.find("composite"), std::string::npos) << name;
    }
    EXPECT_EQ(std::find(names.begin(), names.end(), "lines.silhouette"), names.end());
    // Without lines there is no layer for "lines.*" to stand for: render() refused the name bufferNames() offered.
    const std::vector<std::string> lineless = ig::bufferNames(ig::Look().setLines({}));
    EXPECT_EQ(std::find(lineless.begin(), lineless.end(), "lines.*"), lineless.end());
}

/** What fails before a still executes needs no GL: the frame, the buffer names, the look's files. */
class ApiRenderRefusal : public TestFolder {
protected:
    ig::Error renderError(const ig::Look& look, const ig::Frame& frame, const std::vector<std::string>& buffers = {}) {
        return errorOf([&] { ig::Renderer().render(scene, look, frame, buffers); });
    }
    const ig::Scene scene = ig::Scene::load(kModels + "suzanne_npm_4k.obj");
};

TEST_F(ApiRenderRefusal, AFrameIsCheckedByItsFlagsRules) {
    EXPECT_STREQ(errorOf([] {
                     ig::Frame::fromArguments({"--orbit", "30,10", "--lines", "contour"});
                 }).what(),
                 "Frame::fromArguments(): '--lines' is not a frame flag (give it to the Look)");
    EXPECT_STREQ(errorOf([] { ig::Frame::fromArguments({"--orbit"}); }).what(),
                 "Frame::fromArguments(): --orbit: missing value");
    ig::Frame frame;
    frame.orbit = ig::Orbit{30.0, 95.0};
    const ig::Error elevation = renderError({}, frame);
    EXPECT_EQ(elevation.kind(), ig::Error::Kind::Usage);
    EXPECT_EQ(std::string(elevation.what())
                  .rfind("Renderer::render(): Frame::orbit: --orbit: the elevation must lie "
                         "in [-89.9, 89.9]",
                         0),
              0u)
        << elevation.what();
    frame.orbit = ig::Orbit{30.0, 10.0};
    frame.eye = ig::Vec3{0.0, 0.0, 5.0};
    EXPECT_STREQ(renderError({}, frame).what(), "Renderer::render(): --orbit and --eye both place the eye: give one");
    // A distance and a scale of the auto-framing distance: the scale was ignored without a word.
    frame = {};
    frame.orbit = ig::Orbit{30.0, 10.0, 3.0, 2.0};
    EXPECT_STREQ(renderError({}, frame).what(),
                 "Renderer::render(): Frame::orbit: a distance and a distanceScale (2) are given; the scale is of the "
                 "auto-framing distance, so give one of them");
    frame = {};
    frame.fov = 180.0;
    EXPECT_STREQ(renderError({}, frame).what(),
                 "Renderer::render(): Frame::fov: --fov: degrees must lie in [0.01, 179], got 180");
}

TEST(ApiFrame, FromArgumentsFillsTheTypedFields) {
    const ig::Frame frame =
        ig::Frame::fromArguments({"--size", "640x480", "--orbit", "30,10,4", "--target", "1,2,3", "--fov", "40",
                                  "--clip", "0.5,50", "--camera", "auto", "--up", "0,0,2"});
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
    ASSERT_TRUE(frame.orbit.has_value());
    EXPECT_EQ(frame.orbit->azimuth, 30.0);
    EXPECT_EQ(frame.orbit->elevation, 10.0);
    EXPECT_EQ(frame.orbit->distance, 4.0);
    ASSERT_TRUE(frame.target.has_value());
    EXPECT_EQ(frame.target->z, 3.0);
    ASSERT_TRUE(frame.up.has_value());
    EXPECT_EQ(frame.up->z, 1.0) << "--up is a direction, made unit length";
    EXPECT_EQ(frame.fov, 40.0);
    ASSERT_TRUE(frame.clip.has_value());
    EXPECT_EQ(frame.clip->near, 0.5);
    EXPECT_EQ(frame.clip->far, 50.0);
    EXPECT_EQ(frame.placement, ig::CameraPlacement::Auto);
    EXPECT_EQ(ig::Frame::fromArguments({"--frame", "Head,Hand"}).frameNodes,
              (std::vector<std::string>{"Head", "Hand"}));
    const ig::Frame eye = ig::Frame::fromArguments({"--eye", "0,1,5", "--animation", "Walk", "--time", "0"});
    ASSERT_TRUE(eye.eye.has_value());
    EXPECT_EQ(eye.eye->y, 1.0);
    EXPECT_EQ(eye.animation, "Walk");
    EXPECT_EQ(eye.time, 0.0) << "--time given as 0 stays given";
    EXPECT_EQ(ig::Frame::fromArguments({"--pose", "a-pose"}).pose, "a-pose");
    EXPECT_FALSE(frame.eye.has_value());
    EXPECT_FALSE(frame.time.has_value());
}

TEST_F(ApiRenderRefusal, AFrameSizeIsCheckedAsSize) {
    ig::Frame frame;
    frame.width = 0;
    EXPECT_STREQ(renderError({}, frame).what(),
                 "Renderer::render(): Frame::width and height: --size: width and height must be whole numbers from 1 "
                 "to 16384, got '0x1024'");
    frame.width = 4096;
    frame.height = 4096;
    EXPECT_STREQ(renderError(ig::Look().setSupersample(8), frame).what(),
                 "Renderer::render(): --supersample: 8 x --size 4096x4096 exceeds the largest buffer side, 16384");
}

TEST_F(ApiRenderRefusal, AnUnknownBufferNamesTheLooksBuffers) {
    const ig::Look look = ig::Look::fromArguments({"--lines", "contour"});
    const ig::Error undrawn = renderError(look, {}, {"normal", "lines.crease"});
    EXPECT_EQ(undrawn.kind(), ig::Error::Kind::Usage);
    const std::string message = undrawn.what();
    // The look's buffers by their public names (bufferNames()): the graph's own names of every line type's passes,
    // drawn or not, ran to 2 KB.
    EXPECT_EQ(message, "Renderer::render(): no buffer 'lines.crease' in this look ('crease' is not in the look's "
                       "--lines); it has: normal, view, wVec, nDotV, depth, coverage, baseColor, radial, materialId, "
                       "objectId, meshId, triangleId, barycentric, gbuffer.*, lines.contour, lines.*, picture, and the "
                       "images the graph computes for it, by the names `inkgraph render --print-plan` shows");
    const ig::Error unknown = renderError(look, {}, {"gbuffer.sheen"});
    EXPECT_EQ(
        std::string(unknown.what()).rfind("Renderer::render(): no buffer 'gbuffer.sheen' in this look; it has: ", 0),
        0u)
        << unknown.what();
}

TEST_F(ApiRenderRefusal, AMissingShadeMapIsAnInputError) {
    const std::string map = (directory / "absent.png").string();
    const ig::Error error = renderError(ig::Look().set("--shademap", map), {});
    EXPECT_EQ(error.kind(), ig::Error::Kind::Input) << error.what();
    EXPECT_EQ(error.exitCode(), 3);
    EXPECT_NE(std::string(error.what()).find("--shademap: "), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find(map), std::string::npos) << error.what();
}

using ApiImage = TestFolder;

/** A `width` x `height` image of `channels` whose every byte differs from its neighbours'. */
ig::Image patterned(int width, int height, int channels, ig::Image::Type type) {
    const std::size_t values = std::size_t(width) * height * channels;
    std::vector<std::uint8_t> bytes(values * (type == ig::Image::Type::Float32 ? 4 : 1));
    for (std::size_t i = 0; i < values; ++i) {
        if (type == ig::Image::Type::UInt8) {
            bytes[i] = std::uint8_t((i * 37 + 11) % 256);
        } else {
            const float value = float(i) * 0.125f - 3.0f;
            std::memcpy(bytes.data() + 4 * i, &value, 4);
        }
    }
    return ig::Image(width, height, channels, type, std::move(bytes));
}

/** The image's bytes as written, read back by the command line's own reader. */
std::vector<std::uint8_t> bytesReadBack(const std::filesystem::path& path) {
    const cv::Mat read = readImage(path);
    const cv::Mat continuous = read.isContinuous() ? read : read.clone();
    return {continuous.data, continuous.data + continuous.total() * continuous.elemSize()};
}

TEST_F(ApiImage, WritesPngThatReadsBackTheSame) {
    for (const int channels : {1, 4}) {
        const ig::Image image = patterned(5, 3, channels, ig::Image::Type::UInt8);
        const std::filesystem::path path = directory / ("image-" + std::to_string(channels) + ".png");
        image.write(path.string());
        const cv::Mat read = readImage(path);
        EXPECT_EQ(read.cols, 5);
        EXPECT_EQ(read.rows, 3);
        EXPECT_EQ(read.channels(), channels);
        EXPECT_EQ(bytesReadBack(path), bytesOf(image)) << channels << " channels";
    }
}

TEST_F(ApiImage, WritesFloatsToExrExactly) {
    const ig::Image image = patterned(4, 2, 4, ig::Image::Type::Float32);
    const std::filesystem::path path = directory / "image.exr";
    image.write(path.string());
    EXPECT_EQ(readImage(path).type(), CV_32FC4);
    EXPECT_EQ(bytesReadBack(path), bytesOf(image));
    EXPECT_EQ(image.floats()[5], 5 * 0.125f - 3.0f);
}

TEST_F(ApiImage, FailuresNameTheFile) {
    const ig::Image image = patterned(2, 2, 4, ig::Image::Type::UInt8);
    const std::string unwritable = (directory / "no-such-folder" / "x.png").string();
    const ig::Error output = errorOf([&] { image.write(unwritable); });
    EXPECT_EQ(output.kind(), ig::Error::Kind::Output) << output.what();
    EXPECT_EQ(output.exitCode(), 5);
    EXPECT_NE(std::string(output.what()).find(unwritable), std::string::npos) << output.what();

    EXPECT_STREQ(errorOf([&] { ig::Image(2, 2, 4, ig::Image::Type::UInt8, std::vector<std::uint8_t>(15)); }).what(),
                 "Image(): the image holds 15 bytes; 2x2x4 pixels need 16");
    EXPECT_STREQ(errorOf([&] { ig::Image(2, 0, 4, ig::Image::Type::UInt8, {}); }).what(),
                 "Image(): an image of 2x0 pixels and 4 channels (at least 1x1, 1 or 4 channels)");
    EXPECT_STREQ(errorOf([&] { ig::Image(2, 2, 1, ig::Image::Type(7), std::vector<std::uint8_t>(4)); }).what(),
                 "Image(): an image of 2x2 pixels and 1 channels of type 7 (Image::Type::UInt8 or Float32)");
    EXPECT_EQ(errorOf([&] { image.floats(); }).kind(), ig::Error::Kind::Usage);
    // Wider than JPEG holds: libjpeg ended the process (exit 1) in Image::write().
    const ig::Image wide = patterned(65501, 1, 1, ig::Image::Type::UInt8);
    const std::string jpeg = (directory / "wide.JPG").string();
    const ig::Error tooWide = errorOf([&] { wide.write(jpeg); });
    EXPECT_EQ(tooWide.kind(), ig::Error::Kind::Output) << tooWide.what();
    EXPECT_NE(std::string(tooWide.what()).find("JPEG holds at most 65500 pixels a side, the image is 65501x1"),
              std::string::npos)
        << tooWide.what();
    EXPECT_FALSE(std::filesystem::exists(jpeg));
}

/** lstat's file type of `path` (links not followed), or 0 when it does not exist. */
mode_t fileTypeOf(const std::filesystem::path& path) {
    struct stat status {};
    return ::lstat(path.c_str(), &status) == 0 ? status.st_mode & S_IFMT : 0;
}

/** The names in `folder`, sorted. */
std::vector<std::string> namesIn(const std::filesystem::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
}

const std::string kReplaceTail = "; outputs are written as new files and renamed into place, which would replace it, "
                                 "so give the name of a regular file or a new one";

// Image::write() writes beside its place and renames over it: before, a FIFO, a device or a link to one named *.png
// was replaced by a regular file (as root, a `mknod x.png c 1 3` became a file). It follows the command line's rule.
TEST_F(ApiImage, RefusesToReplaceAFifoALinkToADeviceOrAFolder) {
    const ig::Image image = patterned(2, 2, 4, ig::Image::Type::UInt8);
    const std::filesystem::path fifo = directory / "fifo.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    const ig::Error fifoError = errorOf([&] { image.write(fifo.string()); });
    EXPECT_EQ(fifoError.kind(), ig::Error::Kind::Output);
    EXPECT_EQ(fifoError.exitCode(), 5);
    EXPECT_EQ(fifoError.what(), "writeImage(): '" + fifo.string() + "' is a FIFO" + kReplaceTail);
    EXPECT_EQ(fileTypeOf(fifo), mode_t(S_IFIFO));

    const std::filesystem::path toNull = directory / "null.png";
    std::filesystem::create_symlink("/dev/null", toNull);
    const ig::Error deviceError = errorOf([&] { image.write(toNull.string()); });
    EXPECT_EQ(deviceError.kind(), ig::Error::Kind::Output);
    EXPECT_EQ(deviceError.what(), "writeImage(): '" + toNull.string() + "' is a character device" + kReplaceTail);
    EXPECT_EQ(fileTypeOf(toNull), mode_t(S_IFLNK));
    EXPECT_EQ(fileTypeOf("/dev/null"), mode_t(S_IFCHR));

    const std::filesystem::path folder = directory / "folder.png";
    std::filesystem::create_directory(folder);
    EXPECT_STREQ(errorOf([&] { image.write(folder.string()); }).what(),
                 ("writeImage(): '" + folder.string() + "' is a folder; give a file name").c_str());
    EXPECT_EQ(fileTypeOf(folder), mode_t(S_IFDIR));
    EXPECT_EQ(namesIn(directory), (std::vector<std::string>{"fifo.png", "folder.png", "null.png"}))
        << "no temporary file is left";

    // A link to nothing is a new name, as on the command line: the picture replaces the link.
    const std::filesystem::path dangling = directory / "dangling.png";
    std::filesystem::create_symlink(directory / "nowhere.png", dangling);
    image.write(dangling.string());
    EXPECT_EQ(fileTypeOf(dangling), mode_t(S_IFREG));
    EXPECT_EQ(bytesReadBack(dangling), bytesOf(image));
}

TEST_F(ApiImage, RefusesToReplaceACharacterDevice) {
    if (::geteuid() != 0) GTEST_SKIP() << "mknod needs root";
    const ig::Image image = patterned(2, 2, 4, ig::Image::Type::UInt8);
    const std::filesystem::path device = directory / "x.png";
    ASSERT_EQ(::mknod(device.c_str(), S_IFCHR | 0666, ::makedev(1, 3)), 0) << std::strerror(errno);
    const ig::Error error = errorOf([&] { image.write(device.string()); });
    EXPECT_EQ(error.kind(), ig::Error::Kind::Output);
    EXPECT_EQ(error.what(), "writeImage(): '" + device.string() + "' is a character device" + kReplaceTail);
    EXPECT_EQ(fileTypeOf(device), mode_t(S_IFCHR)) << "the device was replaced";
}

TEST(ApiErrors, KindsKeepTheCommandLinesExitCodes) {
    EXPECT_EQ(ig::Error(ig::Error::Kind::Usage, "").exitCode(), 2);
    EXPECT_EQ(ig::Error(ig::Error::Kind::Input, "").exitCode(), 3);
    EXPECT_EQ(ig::Error(ig::Error::Kind::Context, "").exitCode(), 4);
    EXPECT_EQ(ig::Error(ig::Error::Kind::Output, "").exitCode(), 5);
    EXPECT_EQ(ig::Error(ig::Error::Kind::Render, "").exitCode(), 1);
}

TEST(ApiVersion, IsTheProjects) {
    EXPECT_EQ(ig::version(), INKGRAPH_PROJECT_VERSION);
    EXPECT_FALSE(ig::gitCommit().empty());
}

TEST(ApiVersion, TheHeadersMacrosAreTheLibrarysVersion) {
    EXPECT_EQ(ig::version(), std::to_string(INKGRAPH_VERSION_MAJOR) + "." + std::to_string(INKGRAPH_VERSION_MINOR) +
                                 "." + std::to_string(INKGRAPH_VERSION_PATCH));
    // The ABI namespace is the minor's: v<MAJOR>_<MINOR>.
#define INKGRAPH_TEST_STRING(x) #x
#define INKGRAPH_TEST_EXPANDED(x) INKGRAPH_TEST_STRING(x)
    EXPECT_EQ(std::string(INKGRAPH_TEST_EXPANDED(INKGRAPH_ABI_NAMESPACE)),
              "v" + std::to_string(INKGRAPH_VERSION_MAJOR) + "_" + std::to_string(INKGRAPH_VERSION_MINOR));
}

// The library's views are the command line's (scene/ViewSampling.h): the golden of tests/scene/ViewSamplingTest.cpp,
// the choices as given, and the flags' refusals.
TEST(ApiViews, SampleViewsDrawsTheCommandLinesViews) {
    ig::ViewSampling sampling;
    sampling.distanceJitter = 0.1;
    sampling.expressions = {"none", "happy=1", "sad=1"};
    sampling.poses = {"rest", "a-pose"};
    const std::vector<ig::ViewSample> views = ig::sampleViews(3, 1, "models/suzanne_npm_4k.obj", sampling);
    ASSERT_EQ(views.size(), 3u);
    EXPECT_EQ(views[0].azimuth, 47.862973);
    EXPECT_EQ(views[0].elevation, -7.00786);
    EXPECT_EQ(views[0].distanceScale, 0.952946094);
    EXPECT_EQ(views[2].azimuth, 153.337869);
    EXPECT_EQ(views[0].expression, "happy=1");
    EXPECT_EQ(views[2].expression, "sad=1");
    EXPECT_EQ(views[2].pose, "a-pose");
    EXPECT_FALSE(views[0].light);
    const ig::Orbit orbit = views[1].orbit();
    EXPECT_EQ(orbit.azimuth, views[1].azimuth);
    EXPECT_FALSE(orbit.distance);
    EXPECT_EQ(orbit.distanceScale, views[1].distanceScale);

    sampling = {};
    sampling.lightJitter = 30.0;
    const ig::Error noLight = errorOf([&] { ig::sampleViews(2, 0, "a.obj", sampling); });
    EXPECT_EQ(noLight.kind(), ig::Error::Kind::Usage);
    EXPECT_EQ(std::string(noLight.what()).rfind("sampleViews(): --light-jitter turns --light's direction", 0), 0u)
        << noLight.what();
    sampling.light = ig::Vec3{0.0, 2.0, 0.0};
    const std::vector<ig::ViewSample> lit = ig::sampleViews(2, 0, "a.obj", sampling);
    ASSERT_TRUE(lit[0].light);
    const double length = std::sqrt(lit[0].light->x * lit[0].light->x + lit[0].light->y * lit[0].light->y +
                                    lit[0].light->z * lit[0].light->z);
    EXPECT_NEAR(length, 1.0, 2e-9);
    EXPECT_GE(lit[0].light->y, std::cos(30.0 * 3.14159265358979 / 180.0) - 1e-9) << "within the cap about +y";
    sampling.elevationLow = 70.0; // above the default high, 60
    const ig::Error elevation = errorOf([&] { ig::sampleViews(2, 0, "a.obj", sampling); });
    EXPECT_NE(std::string(elevation.what()).find("--view-elevation: LOW must not exceed HIGH"), std::string::npos)
        << elevation.what();
    // --views is the command line's loop; a Frame takes one view.
    const ig::Error inFrame = errorOf([] { ig::Frame::fromArguments({"--views", "3"}); });
    EXPECT_EQ(inFrame.kind(), ig::Error::Kind::Usage);
    EXPECT_NE(std::string(inFrame.what()).find("sampleViews() (Python: sample_views()) draws the views"),
              std::string::npos)
        << inFrame.what();
}

} // namespace
} // namespace inkgraph::test
