// The typed API through libinkgraph.so (issue 33): every typed field draws what its flag draws, byte for byte; the
// camera a still returns recovers the surface from the depth buffer; meshes from arrays render as their OBJ; warnings
// come as records; images view the render's pixels and renderInto() fills a caller's buffer.
#include <inkgraph/inkgraph.h>

#include "tests/api/ApiTestSupport.h"
#include "tests/support/TestFolder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>

namespace ig = inkgraph::api;

namespace inkgraph::test::api_typed_gl_test {
namespace {

const std::string kRoot = std::string(INKGRAPH_SOURCE_ROOT) + "/";
const std::string kSuzanne = kRoot + "models/suzanne_npm_4k.obj";
const std::string kStillLife = kRoot + "examples/still-life/still-life.gltf";
const std::string kFox = kRoot + "models/characters/fox.glb";
const std::string kGodette = kRoot + "models/characters/godette.vrm";

/** The renderer every test of this file shares: one GL context for the binary. */
ig::Renderer& renderer() {
    static ig::Renderer shared;
    return shared;
}

ig::Frame frameOf(int width, int height) {
    ig::Frame frame;
    frame.width = width;
    frame.height = height;
    return frame;
}

/** One typed setting and the flags that say the same. */
struct TypedLook {
    std::string name;
    std::function<void(ig::Look&)> set;
    std::vector<std::string> flags;
    /** The picture differs from the default look's; half-precision normals move nothing a cel still shows. */
    bool changesThePicture = true;
};

TEST(ApiTyped, EveryLookFieldDrawsWhatItsFlagDraws) {
    const ig::Scene scene = ig::Scene::load(kSuzanne);
    const std::vector<TypedLook> cases = {
        {"shading", [](ig::Look& look) { look.setShading(ig::Shading::Phong); }, {"--shading", "phong"}},
        {"shininess",
         [](ig::Look& look) { look.setShading(ig::Shading::Phong).setShininess(4.5); },
         {"--shading", "phong", "--shininess", "4.5"}},
        {"bands", [](ig::Look& look) { look.setBands(3); }, {"--bands", "3"}},
        {"shade map",
         [](ig::Look& look) { look.setShadeMap(kRoot + "shademaps/cel-two-band.png"); },
         {"--shademap", kRoot + "shademaps/cel-two-band.png"}},
        {"view vector",
         [](ig::Look& look) { look.setShading(ig::Shading::Comic).setViewVector(ig::ViewVector::Constant); },
         {"--shading", "comic", "--view-vector", "constant"}},
        {"face orientation and front rule",
         [](ig::Look& look) {
             look.setShading(ig::Shading::Comic)
                 .setFaceOrientation(ig::FaceOrientation::DuringVertices)
                 .setFrontRule(1);
         },
         {"--shading", "comic", "--face-orientation", "during-vertices", "--front-rule", "1"}},
        {"light",
         [](ig::Look& look) {
             look.setLight({1.0, 0.25, 0.5});
         },
         {"--light", "1,0.25,0.5"}},
        {"ambient",
         [](ig::Look& look) {
             look.setShading(ig::Shading::Lambert).setAmbient({0.3, 0.2, 0.1, 1.0});
         },
         {"--shading", "lambert", "--ambient", "0.3,0.2,0.1"}},
        {"paper",
         [](ig::Look& look) {
             look.setPaper({0.9, 0.85, 0.7, 1.0});
         },
         {"--background", "0.9,0.85,0.7"}},
        {"supersample", [](ig::Look& look) { look.setSupersample(2); }, {"--supersample", "2"}},
        {"msaa", [](ig::Look& look) { look.setMsaa(4); }, {"--msaa", "4"}},
        {"precision",
         [](ig::Look& look) { look.setGbufferPrecision(ig::Precision::Float16); },
         {"--gbuffer-precision", "half"},
         false},
        {"lines",
         [](ig::Look& look) {
             look.setLines({ig::LineType::Crease, ig::LineType::Contour});
         },
         {"--lines", "crease,contour"}},
        {"no lines", [](ig::Look& look) { look.setLines({}); }, {"--lines", "none"}},
        {"line style",
         [](ig::Look& look) {
             look.setLineStyle(ig::LineType::Contour, {3.5, {0.8, 0.1, 0.2, 0.75}});
         },
         {"--contour-width", "3.5", "--contour-color", "0.8,0.1,0.2,0.75"}},
        {"line parameter",
         [](ig::Look& look) { look.setLines({ig::LineType::Crease}).setLineParameter("crease-angle", 25.0); },
         {"--lines", "crease", "--crease-angle", "25"}},
        {"line choice",
         [](ig::Look& look) { look.setLines({ig::LineType::Suggestive}).setLineChoice("suggestive-stencil", "5"); },
         {"--lines", "suggestive", "--suggestive-stencil", "5"}},
        {"strokes",
         [](ig::Look& look) {
             ig::StrokeSettings strokes = look.strokes();
             strokes.minLength = 0.05;
             strokes.weightByDepth = true;
             strokes.taperEnds = true;
             strokes.mergeOverlaps = true;
             look.setStrokes(strokes);
         },
         {"--min-stroke-length", "0.05", "--line-weight", "depth,taper", "--overlapping-lines", "merge"}},
        {"hidden lines",
         [](ig::Look& look) {
             look.setLines({ig::LineType::Crease, ig::LineType::HiddenCrease});
             ig::StrokeSettings strokes = look.strokes();
             strokes.hiddenDashOn = 3.0;
             strokes.hiddenDashOff = 2.0;
             look.setStrokes(strokes);
         },
         {"--lines", "crease", "--hidden-lines", "crease", "--hidden-dash", "3,2"}},
    };
    const ig::Image plain = renderer().render(scene, ig::Look(), frameOf(72, 64)).picture();
    for (const TypedLook& typed : cases) {
        ig::Look look;
        typed.set(look);
        const ig::Still byType = renderer().render(scene, look, frameOf(72, 64));
        const ig::Still byFlag = renderer().render(scene, ig::Look::fromArguments(typed.flags), frameOf(72, 64));
        EXPECT_EQ(bytesOf(byType.picture()), bytesOf(byFlag.picture())) << typed.name;
        if (typed.changesThePicture) {
            EXPECT_NE(bytesOf(byType.picture()), bytesOf(plain)) << typed.name << " changes nothing: it tests nothing";
        }
        // The look reads back what was set, and its flags are the same look again.
        EXPECT_EQ(
            bytesOf(renderer().render(scene, ig::Look::fromArguments(look.arguments()), frameOf(72, 64)).picture()),
            bytesOf(byType.picture()))
            << typed.name;
    }
}

TEST(ApiTyped, TheLookReadsBackItsFields) {
    ig::Look look;
    EXPECT_EQ(look.shading(), ig::Shading::Auto);
    EXPECT_FALSE(look.ambient().has_value());
    EXPECT_EQ(look.lines(), (std::vector<ig::LineType>{ig::LineType::Silhouette, ig::LineType::Contour}));
    EXPECT_FALSE(look.bands().has_value());
    look.setShading(ig::Shading::Comic).setShininess(8).setLineStyle(ig::LineType::Contour, {1.5, {0, 0, 1, 1}});
    EXPECT_EQ(look.shading(), ig::Shading::Comic);
    EXPECT_EQ(look.shininess(), 8.0);
    EXPECT_EQ(look.lineStyle(ig::LineType::Contour).width, 1.5);
    EXPECT_EQ(look.lineStyle(ig::LineType::Contour).color.b, 1.0);
    EXPECT_EQ(look.lineStyle(ig::LineType::Silhouette).width, 2.0) << "a type without a style has the default";
    EXPECT_EQ(look.lineParameter("depth-jump"), ig::Look::fromArguments({}).lineParameter("depth-jump"));
    EXPECT_EQ(look.lineChoice("suggestive-stencil"), "3");
    const std::vector<std::string> crease = ig::Look::lineParameterNames(ig::LineType::Crease);
    EXPECT_NE(std::find(crease.begin(), crease.end(), "crease-angle"), crease.end());
    look.setAmbient({0.25, 0.5, 0.75, 1.0});
    EXPECT_EQ(look.ambient()->g, 0.5);
    EXPECT_STREQ(errorOf([&] {
                     look.setAmbient({0.1, 0.1, 0.1, 0.5});
                 }).what(),
                 "Look::setAmbient(): a light has no alpha: alpha must be 1, got 0.5");
    EXPECT_STREQ(errorOf([&] {
                     look.setAmbient({1.5, 0.1, 0.1, 1.0});
                 }).what(),
                 "Look::setAmbient(): --ambient: channels must lie in [0, 1], got '1.5,0.1,0.1'");
    // A setter's value is checked at once, with its flag's message after the setter's name.
    EXPECT_STREQ(errorOf([&] { look.setBands(1); }).what(),
                 "Look::setBands(): --bands: expected a whole number from 2 to 256, got '1'");
    EXPECT_STREQ(errorOf([&] {
                     look.setLineStyle(ig::LineType::Contour, {0.0, {}});
                 }).what(),
                 "Look::setLineStyle(): --contour-width: pixels must be from 0.001 to 256, got '0'");
    EXPECT_EQ(errorOf([&] { look.setLineParameter("crease-angle", 400); }).kind(), ig::Error::Kind::Usage);
    const std::string sheen = errorOf([&] { look.lineParameter("sheen"); }).what();
    EXPECT_EQ(sheen.rfind("Look::lineParameter(): no line parameter 'sheen' (there are: ", 0), 0u) << sheen;
    EXPECT_NE(sheen.find("crease-angle"), std::string::npos) << sheen;
    EXPECT_EQ(look.msaa(), 1);
    EXPECT_EQ(look.setMsaa(4).msaa(), 4);
    EXPECT_STREQ(errorOf([&] { look.setMsaa(3); }).what(),
                 "Look::setMsaa(): --msaa: expected 1 (off), 2, 4 or 8 samples per pixel, got '3'");
    EXPECT_EQ(look.msaa(), 4) << "a refused value changes nothing";
    EXPECT_EQ(look.shading(), ig::Shading::Comic) << "a refused value changes nothing";
    for (const ig::LineType type : look.lines()) EXPECT_EQ(ig::lineTypeNamed(ig::nameOf(type)), type);
}

TEST(ApiTyped, EveryFrameFieldDrawsWhatItsFlagDraws) {
    const ig::Scene suzanne = ig::Scene::load(kSuzanne);
    const ig::Scene stillLife = ig::Scene::load(kStillLife);
    const ig::Scene fox = ig::Scene::load(kFox);
    const ig::Scene godette = ig::Scene::load(kGodette);
    struct TypedFrame {
        std::string name;
        const ig::Scene* scene;
        std::function<void(ig::Frame&)> set;
        std::vector<std::string> flags;
    };
    const std::vector<TypedFrame> cases = {
        {"eye and target",
         &suzanne,
         [](ig::Frame& frame) {
             frame.eye = ig::Vec3{1.5, 1.0, 2.5};
             frame.target = ig::Vec3{0.1, 0.0, 0.0};
         },
         {"--eye", "1.5,1,2.5", "--target", "0.1,0,0"}},
        {"orbit",
         &suzanne,
         [](ig::Frame& frame) {
             frame.orbit = ig::Orbit{40.0, -15.0, 4.0};
         },
         {"--orbit", "40,-15,4"}},
        {"up and fov",
         &suzanne,
         [](ig::Frame& frame) {
             frame.up = ig::Vec3{0.2, 1.0, 0.0};
             frame.fov = 60.0;
         },
         {"--up", "0.2,1,0", "--fov", "60"}},
        {"clip",
         &suzanne,
         [](ig::Frame& frame) {
             frame.clip = ig::Clip{3.3, 3.9};
         },
         {"--clip", "3.3,3.9"}},
        {"placement",
         &stillLife,
         [](ig::Frame& frame) { frame.placement = ig::CameraPlacement::Auto; },
         {"--camera", "auto"}},
        {"frame nodes", &stillLife, [](ig::Frame& frame) { frame.frameNodes = {"Teapot"}; }, {"--frame", "Teapot"}},
        {"animation and time",
         &fox,
         [](ig::Frame& frame) {
             frame.animation = "Run";
             frame.time = 0.4;
         },
         {"--animation", "Run", "--time", "0.4"}},
        {"pose", &godette, [](ig::Frame& frame) { frame.pose = "a-pose"; }, {"--pose", "a-pose"}},
        {"frame by bone", &godette, [](ig::Frame& frame) { frame.frameNodes = {"head"}; }, {"--frame", "head"}},
        {"expressions and look-at",
         &godette,
         [](ig::Frame& frame) {
             frame.expressions = {{"blink", 1.0}, {"aa", 0.5}};
             frame.lookAt = ig::Vec3{-5.0, 1.3, -2.0};
         },
         {"--expression", "blink=1,aa=0.5", "--look-at", "-5,1.3,-2"}},
    };
    for (const TypedFrame& typed : cases) {
        ig::Frame frame = frameOf(80, 60);
        typed.set(frame);
        std::vector<std::string> flags = typed.flags;
        flags.insert(flags.end(), {"--size", "80x60"});
        // The still life's materials name 2-D shade maps, which comic shading takes.
        const ig::Look look = typed.scene == &stillLife ? ig::Look().setShading(ig::Shading::Comic) : ig::Look();
        const ig::Still byType = renderer().render(*typed.scene, look, frame);
        const ig::Still byFlag = renderer().render(*typed.scene, look, ig::Frame::fromArguments(flags));
        const ig::Still plain = renderer().render(*typed.scene, look, frameOf(80, 60));
        EXPECT_EQ(bytesOf(byType.picture()), bytesOf(byFlag.picture())) << typed.name;
        EXPECT_NE(bytesOf(byType.picture()), bytesOf(plain.picture())) << typed.name << " changes nothing";
    }
    // A scene loaded in a pose draws as a frame that poses it.
    ig::SceneOptions posed;
    posed.pose = "a-pose";
    ig::Frame frame = frameOf(80, 60);
    const ig::Still loadedPosed = renderer().render(ig::Scene::load(kGodette, posed), ig::Look(), frame);
    frame.pose = "a-pose";
    EXPECT_EQ(bytesOf(loadedPosed.picture()), bytesOf(renderer().render(godette, ig::Look(), frame).picture()));
}

/** A UV sphere of `rings` x `segments` quads about `centre`, counter-clockwise from outside. */
struct Sphere {
    std::vector<float> vertices;
    std::vector<std::uint32_t> faces;
};

Sphere uvSphere(const ig::Vec3& centre, double radius, int rings, int segments) {
    Sphere sphere;
    for (int ring = 0; ring <= rings; ++ring) {
        const double polar = M_PI * ring / rings;
        for (int segment = 0; segment <= segments; ++segment) {
            const double azimuth = 2.0 * M_PI * segment / segments;
            sphere.vertices.push_back(float(centre.x + radius * std::sin(polar) * std::cos(azimuth)));
            sphere.vertices.push_back(float(centre.y + radius * std::cos(polar)));
            sphere.vertices.push_back(float(centre.z - radius * std::sin(polar) * std::sin(azimuth)));
        }
    }
    const auto at = [&](int ring, int segment) { return std::uint32_t(ring * (segments + 1) + segment); };
    for (int ring = 0; ring < rings; ++ring)
        for (int segment = 0; segment < segments; ++segment) {
            sphere.faces.insert(sphere.faces.end(),
                                {at(ring, segment), at(ring + 1, segment), at(ring + 1, segment + 1)});
            sphere.faces.insert(sphere.faces.end(),
                                {at(ring, segment), at(ring + 1, segment + 1), at(ring, segment + 1)});
        }
    return sphere;
}

ig::MeshArrays arraysOf(const Sphere& sphere) {
    ig::MeshArrays arrays;
    arrays.vertices = sphere.vertices.data();
    arrays.vertexCount = sphere.vertices.size() / 3;
    arrays.faces = sphere.faces.data();
    arrays.faceCount = sphere.faces.size() / 3;
    return arrays;
}

// The acceptance test of the camera out: an off-centre sphere seen from an orbit at 640x480; every covered pixel's
// depth, back-projected through K and [R|t], lands on the sphere within 0.5% of its radius. The 256 x 512 facets lie
// inside the sphere by at most r (1 - cos(pi / 256)) = 0.0075% of r, well within.
TEST(ApiTyped, TheStillsCameraBackProjectsTheDepthOntoTheSurface) {
    const ig::Vec3 centre{0.7, -0.3, 0.4};
    const double radius = 0.5;
    const Sphere sphere = uvSphere(centre, radius, 256, 512);
    const ig::Scene scene = ig::Scene::fromArrays(arraysOf(sphere), "sphere");
    ig::Frame frame = frameOf(640, 480);
    frame.orbit = ig::Orbit{30.0, 20.0};
    const ig::Still still = renderer().render(scene, ig::Look(), frame, {"depth"});
    const ig::StillCamera& camera = still.camera();
    EXPECT_EQ(camera.source, ig::CameraSource::Orbit);
    EXPECT_EQ(camera.width, 640);
    EXPECT_EQ(camera.height, 480);
    const auto& k = camera.intrinsics;
    EXPECT_EQ(k[0][2], 319.5);
    EXPECT_EQ(k[1][2], 239.5);
    EXPECT_NEAR(k[1][1], 240.0 / std::tan(camera.fovY * M_PI / 360.0), 1e-9);
    const auto& rt = camera.extrinsics;
    // [R|t] is the view matrix with y and z turned: OpenCV's camera looks down +z with y down.
    for (int column = 0; column < 4; ++column) {
        EXPECT_NEAR(rt[0][column], camera.view[0][column], 1e-12);
        EXPECT_NEAR(rt[1][column], -camera.view[1][column], 1e-12);
        EXPECT_NEAR(rt[2][column], -camera.view[2][column], 1e-12);
    }

    const ig::Image& depth = still.buffer("depth");
    ASSERT_EQ(depth.width(), 640);
    ASSERT_EQ(depth.type(), ig::Image::Type::Float32);
    std::size_t covered = 0;
    double worst = 0.0;
    for (int v = 0; v < depth.height(); ++v)
        for (int u = 0; u < depth.width(); ++u) {
            const float z = depth.floats()[std::size_t(v) * std::size_t(depth.width()) + std::size_t(u)];
            if (z <= 0.0f) continue;
            ++covered;
            const double camX = z * (u - k[0][2]) / k[0][0];
            const double camY = z * (v - k[1][2]) / k[1][1];
            const double cam[3] = {camX - rt[0][3], camY - rt[1][3], double(z) - rt[2][3]};
            double world[3] = {0.0, 0.0, 0.0};
            for (int axis = 0; axis < 3; ++axis)
                for (int row = 0; row < 3; ++row) world[axis] += rt[row][axis] * cam[row]; // R^T (X - t)
            const double distance = std::hypot(world[0] - centre.x, world[1] - centre.y, world[2] - centre.z);
            worst = std::max(worst, std::abs(distance - radius) / radius);
        }
    EXPECT_GT(covered, 20000u) << "the sphere is in view";
    EXPECT_LT(worst, 0.005) << "worst deviation " << worst * 100.0 << "% of the radius";
}

// Still::strokes() (issue 37, docs/datasets.md): asked for as "strokes", every kept stroke with its world points. On a
// sphere at 256 x 256 without supersampling, contour points lie on the camera ray through (x, y) (to the 7-digit
// rounding) and on the sphere within half a pixel's worth of its radius (the contour's own position is exact to half
// a pixel: 0.36% measured); mesh-silhouette points lie on the facets' edges (inside by at most
// r (1 - cos(pi / 128)) = 0.030% of r) and project within half a pixel of (x, y) for 97% or more (98.4% measured).
TEST(ApiTyped, StrokesKnowTheirWorldPoints) {
    const ig::Vec3 centre{0.7, -0.3, 0.4};
    const double radius = 0.5;
    const Sphere sphere = uvSphere(centre, radius, 64, 128);
    const ig::Scene scene = ig::Scene::fromArrays(arraysOf(sphere), "sphere");
    ig::Frame frame = frameOf(256, 256);
    frame.orbit = ig::Orbit{30.0, 20.0};
    ig::Look look;
    look.setShading(ig::Shading::None).setLines({ig::LineType::Contour, ig::LineType::MeshSilhouette});
    const ig::Still plain = renderer().render(scene, look, frame);
    EXPECT_EQ(errorOf([&] { plain.strokes(); }).kind(), ig::Error::Kind::Usage);

    const ig::Still still = renderer().render(scene, look, frame, {"strokes"});
    const auto& k = still.camera().intrinsics;
    const auto& rt = still.camera().extrinsics;
    std::map<std::string, std::size_t> points, nearPixel;
    std::map<std::string, double> worstRadial, worstPixel;
    for (const ig::StillStroke& stroke : still.strokes()) {
        EXPECT_TRUE(stroke.visible);
        for (const ig::StillStrokePoint& point : stroke.points) {
            ASSERT_TRUE(point.world.has_value()) << stroke.type;
            EXPECT_EQ(point.mesh, 1) << stroke.type; // every point has its triangle: one mesh
            EXPECT_GE(point.triangle, 0) << stroke.type;
            const double world[3] = {point.world->x, point.world->y, point.world->z};
            double camera[3] = {rt[0][3], rt[1][3], rt[2][3]};
            for (int row = 0; row < 3; ++row)
                for (int axis = 0; axis < 3; ++axis) camera[row] += rt[row][axis] * world[axis];
            const double u = k[0][0] * camera[0] / camera[2] + k[0][2];
            const double v = k[1][1] * camera[1] / camera[2] + k[1][2];
            const double pixel = std::hypot(u - point.x, v - point.y);
            const double radial =
                std::abs(std::hypot(world[0] - centre.x, world[1] - centre.y, world[2] - centre.z) - radius) / radius;
            ++points[stroke.type];
            nearPixel[stroke.type] += pixel < 0.5;
            worstRadial[stroke.type] = std::max(worstRadial[stroke.type], radial);
            worstPixel[stroke.type] = std::max(worstPixel[stroke.type], pixel);
        }
    }
    ASSERT_GT(points["contour"], 400u);
    ASSERT_GT(points["mesh-silhouette"], 400u);
    EXPECT_LT(worstPixel["contour"], 1e-3);
    EXPECT_LT(worstRadial["contour"], 0.005);
    EXPECT_LT(worstRadial["mesh-silhouette"], 1.0 - std::cos(M_PI / 128) + 1e-5);
    EXPECT_GE(double(nearPixel["mesh-silhouette"]) / double(points["mesh-silhouette"]), 0.97);
}

/** `value` as OBJ text that reads back as exactly that float. */
std::string exact(float value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", double(value));
    return text;
}

TEST_F(TestFolder, ArraysRenderAsTheirObj) {
    const Sphere sphere = uvSphere({0.2, 0.1, -0.3}, 0.8, 24, 48);
    std::string obj;
    for (std::size_t i = 0; i < sphere.vertices.size(); i += 3)
        obj += "v " + exact(sphere.vertices[i]) + " " + exact(sphere.vertices[i + 1]) + " " +
               exact(sphere.vertices[i + 2]) + "\n";
    for (std::size_t i = 0; i < sphere.faces.size(); i += 3)
        obj += "f " + std::to_string(sphere.faces[i] + 1) + " " + std::to_string(sphere.faces[i + 1] + 1) + " " +
               std::to_string(sphere.faces[i + 2] + 1) + "\n";
    writeText(directory / "sphere.obj", obj);
    const ig::Scene fromFile = ig::Scene::load((directory / "sphere.obj").string());
    const ig::Scene fromArrays = ig::Scene::fromArrays(arraysOf(sphere), "");
    EXPECT_EQ(fromArrays.path(), "");
    EXPECT_EQ(fromArrays.triangleCount(), fromFile.triangleCount());
    const ig::Look look = ig::Look().setLines({ig::LineType::Silhouette, ig::LineType::Contour, ig::LineType::Crease});
    EXPECT_EQ(bytesOf(renderer().render(fromArrays, look, frameOf(96, 80)).picture()),
              bytesOf(renderer().render(fromFile, look, frameOf(96, 80)).picture()));
}

TEST(ApiTyped, BadArraysAreInputErrorsNamingTheArray) {
    Sphere sphere = uvSphere({0, 0, 0}, 1.0, 4, 8);
    sphere.vertices[7] = std::numeric_limits<float>::quiet_NaN();
    const ig::Error nan = errorOf([&] { ig::Scene::fromArrays(arraysOf(sphere), "ball"); });
    EXPECT_EQ(nan.kind(), ig::Error::Kind::Input);
    EXPECT_STREQ(nan.what(), "Scene::fromArrays(): 'ball': vertices: vertex 2: y is not finite (nan)");
    sphere = uvSphere({0, 0, 0}, 1.0, 4, 8);
    sphere.faces[4] = 1000;
    const ig::Error range = errorOf([&] { ig::Scene::fromArrays(arraysOf(sphere), "ball"); });
    EXPECT_EQ(range.kind(), ig::Error::Kind::Input);
    EXPECT_STREQ(range.what(),
                 "Scene::fromArrays(): 'ball': face 1: vertex index 1000 out of range (vertices has 45 rows)");
    ig::MeshArrays none;
    none.vertexCount = 3;
    EXPECT_EQ(errorOf([&] { ig::Scene::fromArrays(none); }).kind(), ig::Error::Kind::Input);
    ig::SceneOptions posed;
    posed.animation = "Walk";
    EXPECT_STREQ(errorOf([&] { ig::Scene::fromArrays(arraysOf(sphere), "ball", posed); }).what(),
                 "Scene::fromArrays(): SceneOptions::animation and time: a scene made from arrays has no animations");
    ig::SceneOptions humanoid;
    humanoid.pose = "a-pose";
    EXPECT_STREQ(errorOf([&] { ig::Scene::fromArrays(arraysOf(sphere), "ball", humanoid); }).what(),
                 "Scene::fromArrays(): SceneOptions::pose: a scene made from arrays has no humanoid");
}

TEST_F(TestFolder, AFramesPoseOrFaceTheModelLacksIsRefusedInTheCallersName) {
    // The frame's pose and face load the file again; the loader's refusal started with "loadScene():", a function the
    // caller never called, and named the flag rather than the frame's field.
    writeText(directory / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string path = (directory / "tri.obj").string();
    const ig::Scene scene = ig::Scene::load(path);
    ig::Frame face = frameOf(16, 16);
    face.expressions = {{"happy", 1.0}};
    const ig::Error expression = errorOf([&] { renderer().render(scene, ig::Look(), face); });
    EXPECT_EQ(expression.kind(), ig::Error::Kind::Input);
    EXPECT_EQ(std::string(expression.what()), "Renderer::render(): Frame::expressions: '" + path +
                                                  "': --expression: obj files have no VRM expressions or look-at");
    ig::Frame pose = frameOf(16, 16);
    pose.pose = "a-pose";
    const ig::Error humanoid = errorOf([&] { renderer().render(scene, ig::Look(), pose); });
    EXPECT_EQ(humanoid.kind(), ig::Error::Kind::Input);
    EXPECT_EQ(std::string(humanoid.what()),
              "Renderer::render(): Frame::pose: '" + path +
                  "': cannot take a humanoid pose: not a VRM model (obj files have no humanoid bones)");
    pose.lookAt = ig::Vec3{0.0, 0.0, 1.0};
    std::vector<std::uint8_t> pixels(16 * 16 * 4);
    const std::string both =
        errorOf([&] { renderer().renderInto(pixels.data(), 16 * 4, scene, ig::Look(), pose); }).what();
    EXPECT_EQ(both.rfind("Renderer::renderInto(): Frame::pose, Frame::lookAt: '" + path + "': ", 0), 0u) << both;
    // The scene is as it was: the frame without them renders.
    EXPECT_NO_THROW(renderer().render(scene, ig::Look(), frameOf(16, 16)));
}

TEST_F(TestFolder, WarningsAreRecordsWithCodes) {
    // An OBJ whose material's texture is missing, and a glTF whose only texture is a KTX2 (KHR_texture_basisu) image.
    writeText(directory / "quad.obj", "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                                      "vt 0 1\nusemtl paper\nf 1/1 2/2 3/3 4/4\n");
    writeText(directory / "quad.mtl", "newmtl paper\nKd 1 1 1\nmap_Kd absent.png\n");
    const ig::Scene missing = ig::Scene::load((directory / "quad.obj").string());
    ASSERT_EQ(missing.warnings().size(), 1u);
    EXPECT_EQ(missing.warnings()[0].code, "texture-missing");
    EXPECT_NE(missing.warnings()[0].file.find("absent.png"), std::string::npos) << missing.warnings()[0].file;
    EXPECT_NE(missing.warnings()[0].item.find("paper"), std::string::npos) << missing.warnings()[0].item;
    // The load's warnings are the scene's: a still that did not pose the scene again repeated them (a program that
    // prints both said each load warning once per still more).
    const ig::Still still = renderer().render(missing, ig::Look(), frameOf(32, 32));
    EXPECT_TRUE(still.warnings().empty()) << still.warnings()[0].code;

    writeText(
        directory / "ktx.gltf",
        R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_texture_basisu"],)"
        R"("buffers":[{"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA","byteLength":42}],)"
        R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
        R"({"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],)"
        R"("images":[{"uri":"skin.ktx2","mimeType":"image/ktx2"}],)"
        R"("textures":[{"name":"skin","extensions":{"KHR_texture_basisu":{"source":0}}}],)"
        R"("materials":[{"name":"coat","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],)"
        R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
    const ig::Scene ktx = ig::Scene::load((directory / "ktx.gltf").string());
    const std::vector<ig::Warning> ktxWarnings = ktx.warnings();
    const auto ktxFound = std::find_if(ktxWarnings.begin(), ktxWarnings.end(), [](const ig::Warning& warning) {
        return warning.code == "texture-without-core-image";
    });
    ASSERT_NE(ktxFound, ktxWarnings.end()) << (ktxWarnings.empty() ? "no warnings" : ktxWarnings[0].code);
    EXPECT_NE(ktxFound->item.find("skin"), std::string::npos) << ktxFound->item;
    EXPECT_NE(ktxFound->file.find("ktx.gltf"), std::string::npos) << ktxFound->file;
}

TEST(ApiTyped, ImagesViewTheRendersPixelsAndStayAsTheyWere) {
    const ig::Scene scene = ig::Scene::load(kSuzanne);
    const ig::Still first = renderer().render(scene, ig::Look(), frameOf(64, 48), {"depth", "lines.contour"});
    const std::vector<std::uint8_t> picture = bytesOf(first.picture());
    const std::vector<std::uint8_t> depth = bytesOf(first.buffer("depth"));
    const ig::Image copy = first.buffer("depth");
    EXPECT_EQ(copy.data(), first.buffer("depth").data()) << "copies of an image share its pixels";
    // Another still of another look and size reuses the renderer's buffers, not the first still's pixels.
    ig::Frame orbit = frameOf(64, 48);
    orbit.orbit = ig::Orbit{90.0, 0.0};
    const ig::Still second = renderer().render(scene, ig::Look().setShading(ig::Shading::Phong), orbit, {"depth"});
    EXPECT_NE(bytesOf(second.buffer("depth")), depth);
    EXPECT_EQ(bytesOf(first.picture()), picture);
    EXPECT_EQ(bytesOf(first.buffer("depth")), depth);
}

TEST(ApiTyped, RenderIntoWritesTheCallersRows) {
    const ig::Scene scene = ig::Scene::load(kSuzanne);
    const int width = 50;
    const int height = 40;
    const std::size_t rowBytes = width * 4 + 24; // rows with room after them, as a caller's image may have
    std::vector<std::uint8_t> buffer(rowBytes * height, 7);
    const ig::Still into = renderer().renderInto(buffer.data(), rowBytes, scene, ig::Look(), frameOf(width, height));
    const ig::Still own = renderer().render(scene, ig::Look(), frameOf(width, height));
    EXPECT_EQ(into.picture().data(), buffer.data());
    EXPECT_EQ(into.picture().rowBytes(), rowBytes);
    EXPECT_EQ(bytesOf(into.picture()), bytesOf(own.picture()));
    for (int row = 0; row < height; ++row)
        for (std::size_t pad = width * 4; pad < rowBytes; ++pad) EXPECT_EQ(buffer[row * rowBytes + pad], 7) << row;
    EXPECT_STREQ(
        errorOf([&] { renderer().renderInto(buffer.data(), 10, scene, ig::Look(), frameOf(width, height)); }).what(),
        "Renderer::renderInto(): the picture's rows are 10 bytes apart; 50 RGBA8 pixels need 200");
    // The widest frame's row in size_t (int arithmetic overflowed: "need -4").
    EXPECT_STREQ(errorOf([&] {
                     renderer().renderInto(buffer.data(), 10, scene, ig::Look(),
                                           frameOf(std::numeric_limits<int>::max(), height));
                 }).what(),
                 "Renderer::renderInto(): the picture's rows are 10 bytes apart; 2147483647 RGBA8 pixels need "
                 "8589934588");
    // Rows farther apart than memory: the offsets wrapped around and the copy wrote before the buffer.
    for (const std::size_t farApart :
         {std::numeric_limits<std::size_t>::max(), std::numeric_limits<std::size_t>::max() / 63}) {
        const std::vector<std::uint8_t> before = buffer;
        EXPECT_STREQ(errorOf([&] {
                         renderer().renderInto(buffer.data(), farApart, scene, ig::Look(), frameOf(width, height));
                     }).what(),
                     ("Renderer::renderInto(): the picture's rows are " + std::to_string(farApart) +
                      " bytes apart: 40 of them reach beyond any memory")
                         .c_str());
        EXPECT_EQ(buffer, before);
    }
    // The function named once (it was twice: "Renderer::render(): Renderer::render(): ...").
    EXPECT_STREQ(errorOf([&] {
                     renderer().render(scene, ig::Look::fromArguments({"--lines", "none"}), frameOf(8, 8), {"strokes"});
                 }).what(),
                 "Renderer::render(): 'strokes' needs a look that draws lines (Look::lines)");
}

TEST(ApiTyped, ValuesNoTypeHoldsAreUsageErrorsNotCrashes) {
    // A Look moved from: its state went with the move; every use is refused (it dereferenced null before).
    ig::Look moved;
    const ig::Look taken = std::move(moved);
    const auto refusedAsMovedFrom = [](const std::function<void()>& use) {
        const ig::Error error = errorOf(use);
        EXPECT_EQ(error.kind(), ig::Error::Kind::Usage);
        EXPECT_NE(std::string(error.what()).find("Look: this Look was moved from"), std::string::npos) << error.what();
    };
    refusedAsMovedFrom([&] { (void)moved.arguments(); });
    refusedAsMovedFrom([&] { moved.setShading(ig::Shading::Phong); });
    refusedAsMovedFrom([&] { const ig::Look copy(moved); });
    refusedAsMovedFrom([&] { (void)ig::bufferNames(moved); });
    refusedAsMovedFrom([&] { renderer().render(ig::Scene::load(kSuzanne), moved, frameOf(16, 16)); });
    moved = taken; // assigned, it is a look again
    EXPECT_EQ(moved.shading(), taken.shading());

    // Enum values cast from numbers that name no enumerator.
    const auto usage = [](const std::function<void()>& use) { return errorOf(use).kind() == ig::Error::Kind::Usage; };
    EXPECT_STREQ(errorOf([] { (void)ig::nameOf(static_cast<ig::LineType>(12345)); }).what(),
                 "nameOf(): no LineType has the value 12345");
    EXPECT_TRUE(usage([] { (void)ig::nameOf(static_cast<ig::Shading>(999)); }));
    EXPECT_TRUE(usage([] { (void)ig::nameOf(static_cast<ig::Precision>(7)); }));
    EXPECT_TRUE(usage([] { (void)ig::nameOf(static_cast<ig::ViewVector>(-1)); }));
    EXPECT_TRUE(usage([] { (void)ig::nameOf(static_cast<ig::FaceOrientation>(4)); }));
    ig::Look look;
    EXPECT_TRUE(usage([&] { look.setShading(static_cast<ig::Shading>(999)); }));
    EXPECT_TRUE(usage([&] { look.setGbufferPrecision(static_cast<ig::Precision>(7)); }));
    EXPECT_TRUE(usage([&] { look.setLines({static_cast<ig::LineType>(999)}); }));
    EXPECT_TRUE(usage([&] { look.setLineStyle(static_cast<ig::LineType>(999), {}); }));
    EXPECT_TRUE(usage([] { ig::Renderer wrong(static_cast<ig::Renderer::Platform>(9)); }));
    ig::Frame frame = frameOf(16, 16);
    frame.placement = static_cast<ig::CameraPlacement>(9);
    EXPECT_TRUE(usage([&] { renderer().render(ig::Scene::load(kSuzanne), {}, frame); }));

    // A line width a single float cannot hold (it reached the strokes as 0, an internal error).
    EXPECT_STREQ(errorOf([&] {
                     look.setLineStyle(ig::LineType::Contour, {1e-46, {}});
                 }).what(),
                 "Look::setLineStyle(): --contour-width: pixels must be from 0.001 to 256, got '1e-46'");

    // An image whose byte count would wrap around size_t matched a short buffer.
    EXPECT_TRUE(
        usage([] { ig::Image(2147380029, 536896818, 4, ig::Image::Type::Float32, std::vector<uint8_t>(11936)); }));
    EXPECT_TRUE(usage([] { ig::Image(1 << 30, 1 << 30, 4, ig::Image::Type::Float32, {}); }));
}

} // namespace
} // namespace inkgraph::test::api_typed_gl_test
