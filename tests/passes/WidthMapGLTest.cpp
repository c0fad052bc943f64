// Width from the model (--outline-width-map, passes/WidthMap.h, shaders/common/width_map.glsl) against closed forms:
// a cylinder along x whose vertex colour and texture ramp r(x) = clamp((x + 1) / 2, 0, 1) runs from 0 (left of
// x = -1) to 1 (right of x = 1), seen side-on, has silhouette and outline bands W r(x) wide above and below it, none
// where r = 0; a mesh without what the map reads keeps W and warns; a file that cannot be read is refused naming it;
// MToon's shell is its width x the map x its own width texture. Needs a GL context (llvmpipe in CI).
#include "passes/mtoon/MToonOutlinePass.h"
#include "passes/outline/OutlinePass.h"
#include "passes/StillGraph.h"
#include "passes/lines/LineTypes.h"
#include "passes/silhouette/SilhouettePass.h"

#include "LineMaskTestSupport.h"

#include <glm/gtc/constants.hpp>
#include <opencv2/imgproc.hpp>

#include <stb/stb_image_write.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace inkgraph::width_map_gl_test {
namespace {

constexpr int kWidth = 256;
constexpr int kHeight = 128;
constexpr double kDistance = 4.0;
constexpr double kFovDegrees = 50.0;
constexpr float kRadius = 0.4f;
constexpr float kHalfLength = 1.5f;
constexpr double kBandPixels = 8.0;

/** The ramp every map of these tests holds: 0 left of x = -1, 1 right of x = 1, linear between. */
double ramp(double x) { return std::clamp((x + 1.0) / 2.0, 0.0, 1.0); }

/** A closed cylinder along x, 60 rings (every 0.05, so x = -1 and x = 1 are rings and the ramp is exact between
 *  vertices) of 64 vertices: COLOR_0 = (r, 1 - r, 0, 1) and TEXCOORD_0 = ((x + 1.5) / 3, 0.5), so a map that reads
 *  the wrong channel gets the ramp reversed. */
Mesh rampCylinder() {
    constexpr int kRings = 61;
    constexpr int kAround = 64;
    Mesh mesh;
    mesh.name = "ramp cylinder";
    const auto addVertex = [&](glm::vec3 position, glm::vec3 normal) {
        mesh.positions.push_back(position);
        mesh.normals.push_back(normal);
        const float r = float(ramp(position.x));
        mesh.colors.emplace_back(r, 1.0f - r, 0.0f, 1.0f);
        mesh.texcoords[0].emplace_back((position.x + kHalfLength) / (2.0f * kHalfLength), 0.5f);
        return std::uint32_t(mesh.positions.size() - 1);
    };
    for (int ring = 0; ring < kRings; ++ring) {
        const float x = -kHalfLength + 2.0f * kHalfLength * float(ring) / float(kRings - 1);
        for (int step = 0; step < kAround; ++step) {
            const float angle = 2.0f * glm::pi<float>() * float(step) / float(kAround);
            const glm::vec3 normal(0.0f, std::cos(angle), std::sin(angle));
            addVertex(glm::vec3(x, 0.0f, 0.0f) + kRadius * normal, normal);
        }
    }
    const auto side = [&](int ring, int step) { return std::uint32_t(ring * kAround + step % kAround); };
    for (int ring = 0; ring + 1 < kRings; ++ring)
        for (int step = 0; step < kAround; ++step) {
            // Counter-clockwise seen from outside: around +x the angle turns from +y to +z.
            mesh.triangles.emplace_back(side(ring, step), side(ring, step + 1), side(ring + 1, step + 1));
            mesh.triangles.emplace_back(side(ring, step), side(ring + 1, step + 1), side(ring + 1, step));
        }
    for (const float end : {-1.0f, 1.0f}) {
        const glm::vec3 normal(end, 0.0f, 0.0f);
        const std::uint32_t centre = addVertex(glm::vec3(end * kHalfLength, 0.0f, 0.0f), normal);
        const std::uint32_t first = std::uint32_t(mesh.positions.size());
        for (int step = 0; step < kAround; ++step) {
            const float angle = 2.0f * glm::pi<float>() * float(step) / float(kAround);
            addVertex(glm::vec3(end * kHalfLength, kRadius * std::cos(angle), kRadius * std::sin(angle)), normal);
        }
        for (int step = 0; step < kAround; ++step) {
            const std::uint32_t a = first + std::uint32_t(step);
            const std::uint32_t b = first + std::uint32_t((step + 1) % kAround);
            if (end > 0.0f)
                mesh.triangles.emplace_back(centre, a, b);
            else
                mesh.triangles.emplace_back(centre, b, a);
        }
    }
    return mesh;
}

/** `count` texels of the ramp over u in [0, 1] (x = 3u - 1.5) in G and its reverse in R, as PNG bytes. */
std::vector<unsigned char> rampPng(int count) {
    std::vector<unsigned char> texels;
    for (int texel = 0; texel < count; ++texel) {
        const double u = (texel + 0.5) / count;
        const auto value = static_cast<unsigned char>(std::lround(255.0 * ramp(2.0 * kHalfLength * u - kHalfLength)));
        texels.insert(texels.end(), {static_cast<unsigned char>(255 - value), value, 0, 255});
    }
    std::vector<unsigned char> bytes;
    const int written = stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        },
        &bytes, count, 1, 4, texels.data(), count * 4);
    EXPECT_NE(written, 0);
    return bytes;
}

/** Every message of `error` and the errors nested in it. */
std::string allMessages(const std::exception& error) {
    std::string text = error.what();
    try {
        std::rethrow_if_nested(error);
    } catch (const std::exception& inner) {
        text += " | " + allMessages(inner);
    }
    return text;
}

class WidthMapCylinder : public test::LinePassFixture {
protected:
    void SetUp() override {
        LinePassFixture::SetUp();
        useCylinder(rampCylinder());
        rampFile = std::filesystem::temp_directory_path() /
                   ("inkgraph-width-ramp-" + std::to_string(::getpid()) + "-" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".png");
        const std::vector<unsigned char> png = rampPng(240);
        std::ofstream(rampFile, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), png.size());
    }
    void TearDown() override { std::filesystem::remove(rampFile); }

    void useCylinder(Mesh mesh) {
        Scene cylinder = makeScene(std::move(mesh));
        // The model's own copy of the ramp, for texture:NAME by image name.
        SceneImage image;
        image.name = "width-ramp";
        image.mimeType = "image/png";
        image.encoded = std::make_shared<const std::vector<unsigned char>>(rampPng(240));
        cylinder.images.push_back(image);
        setScene(std::move(cylinder));
        lookFrom({0.0, 0.0, kDistance}, glm::dvec3(0.0), kFovDegrees, kWidth, kHeight);
    }

    /** The column whose centre sees x on the silhouette lines (at depth D - R^2 / D, where the tangent planes from
     *  the eye touch the cylinder). */
    int columnOf(double x) const {
        const double depth = kDistance - kRadius * kRadius / kDistance;
        return int(std::floor(kWidth / 2.0 + frame.camera.focalPixels() * x / depth));
    }
    /** The band above and below the cylinder in column `col`: the runs of line pixels just outside the coverage. */
    static std::pair<int, int> bandsAt(const test::LineRender& render, int col) {
        return {test::measureOutsideRun(render, {col, kHeight / 2}, 0, -1).length,
                test::measureOutsideRun(render, {col, kHeight / 2}, 0, 1).length};
    }
    /** Line pixels in the columns from x = -1.45 to -1.05, where the ramp is 0 (and left of the cylinder). */
    static int linePixelsLeftOf(const test::LineRender& render, int lastCol) {
        return cv::countNonZero(render.lines(cv::Rect(0, 0, lastCol + 1, kHeight)));
    }

    /** Checks the bands of `render` at x where r = 1/8, 1/4, 1/2, 3/4 and 1 against W r within a pixel, and that
     *  nothing is drawn where r = 0; `measured` gets the widths. */
    void expectRampBands(const test::LineRender& render, std::ostringstream& measured) {
        for (const double x : {-0.75, -0.5, 0.0, 0.5, 1.2}) {
            const int col = columnOf(x);
            const auto [above, below] = bandsAt(render, col);
            const double expected = kBandPixels * ramp(x);
            SCOPED_TRACE("x " + std::to_string(x) + ", column " + std::to_string(col));
            EXPECT_NEAR(above, expected, 1.0);
            EXPECT_NEAR(below, expected, 1.0);
            measured << " r" << ramp(x) << ":" << above << "/" << below;
        }
        EXPECT_EQ(linePixelsLeftOf(render, columnOf(-1.05)), 0);
    }

    std::filesystem::path rampFile;
};

TEST_F(WidthMapCylinder, SilhouetteBandFollowsTheVertexColourAndTextureRamps) {
    HullSettings settings;
    settings.widthPixels = float(kBandPixels);
    std::ostringstream measured;
    {
        // No map: W everywhere, and a band round the left end too (the control).
        SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
        const test::LineRender render = this->render(pass);
        for (const double x : {-0.75, 0.0, 1.2}) {
            const auto [above, below] = bandsAt(render, columnOf(x));
            EXPECT_NEAR(above, kBandPixels, 1.0) << x;
            EXPECT_NEAR(below, kBandPixels, 1.0) << x;
        }
        EXPECT_GT(linePixelsLeftOf(render, columnOf(-1.05)), 100);
    }
    for (const std::string& map : {std::string("color:R"), "texture:" + rampFile.string() + ":G"}) {
        SCOPED_TRACE(map);
        settings.widthMap = parseWidthMap(map);
        SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
        measured << map.substr(0, 7) << ":";
        expectRampBands(this->render(pass), measured);
    }
    EXPECT_TRUE(gpuScene->materials().warnings().empty());
    RecordProperty("band_pixels", measured.str());
    std::cout << "silhouette bands (above/below) for W = 8 px:" << measured.str() << "\n";
}

TEST_F(WidthMapCylinder, OutlineBandFollowsTheVertexColourAndTheModelsImageRamps) {
    std::ostringstream measured;
    for (const std::string map : {"color:R", "texture:width-ramp:G"}) {
        SCOPED_TRACE(map);
        OutlinePass pass("outline", shaders, *gpuScene, frame, float(kBandPixels), parseWidthMap(map));
        measured << map.substr(0, 7) << ":";
        expectRampBands(this->render(pass), measured);
    }
    EXPECT_TRUE(gpuScene->materials().warnings().empty());
    std::cout << "outline bands (above/below) for W = 8 px:" << measured.str() << "\n";
}

TEST_F(WidthMapCylinder, AMeshWithoutTheMapsAttributeKeepsItsWidthAndWarnsOnce) {
    Mesh bare = rampCylinder();
    bare.colors.clear();
    useCylinder(std::move(bare));
    HullSettings settings;
    settings.widthPixels = float(kBandPixels);
    settings.widthMap = parseWidthMap("color:R");
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
    for (int run = 0; run < 2; ++run) {
        const test::LineRender render = this->render(pass);
        const auto [above, below] = bandsAt(render, columnOf(-0.75)); // r would be 1/8 here
        EXPECT_NEAR(above, kBandPixels, 1.0);
        EXPECT_NEAR(below, kBandPixels, 1.0);
    }
    const std::vector<Warning>& warnings = gpuScene->materials().warnings();
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].code, "width-map-unread");
    EXPECT_EQ(warnings[0].message, "mesh 'ramp cylinder' has no vertex colours (COLOR_0) for --outline-width-map "
                                   "color:R: its outline widths are left unscaled");
}

TEST_F(WidthMapCylinder, AnUnreadableOrUnknownTextureIsRefusedNamingIt) {
    const std::filesystem::path corrupt = rampFile.string() + ".broken.png";
    std::ofstream(corrupt, std::ios::binary) << "not a png";
    for (const std::string& name : {corrupt.string(), std::string("no-such-image")}) {
        SCOPED_TRACE(name);
        OutlinePass pass("outline", shaders, *gpuScene, frame, float(kBandPixels),
                         parseWidthMap("texture:" + name + ":G"));
        try {
            render(pass);
            ADD_FAILURE() << "no error";
        } catch (const std::exception& error) {
            const std::string message = allMessages(error);
            EXPECT_NE(message.find("--outline-width-map: '" + name + "'"), std::string::npos) << message;
        }
    }
    std::filesystem::remove(corrupt);
}

/** The look's map reaches both GL-drawn types through the still graph, the silhouette then testing its hull against
 *  the G-buffer's z-buffer (the G-buffer runs for its coverage): the vertices the map leaves on the surface must land
 *  on that depth to the bit, or r = 0 would show specks. */
TEST_F(WidthMapCylinder, TheStillGraphDrawsTheLooksMapForOutlineAndSilhouette) {
    Look look;
    look.shading = ShadingModel::None;
    look.lines = {"outline", "silhouette"};
    look.lineStyles["outline"].widthPixels = kBandPixels;
    look.lineStyles["silhouette"].widthPixels = kBandPixels;
    look.outlineWidthMap = parseWidthMap("color:R");
    StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
    const StillGraph graph = buildStillGraph(setup);
    const Plan plan = compile(graph.view(), {"outline.lines", "silhouette.lines", "gbuffer.coverage"});
    ASSERT_NE(plan.findPass("silhouette"), nullptr);
    EXPECT_EQ(plan.findPass("silhouette")->reads, std::vector<std::string>{"gbuffer.zBuffer"});
    executor.run(plan, graph.mutableView(), {kWidth, kHeight, false});
    std::ostringstream measured;
    for (const char* type : {"outline", "silhouette"}) {
        SCOPED_TRACE(type);
        test::LineRender render;
        render.lines = executor.store().image(std::string(type) + ".lines").clone();
        render.coverage = executor.store().image("gbuffer.coverage").clone();
        measured << " " << type << ":";
        expectRampBands(render, measured);
    }
    executor.store().clear();
    std::cout << "still graph bands (above/below) for W = 8 px:" << measured.str() << "\n";
}

/** The stroke stage draws the GL bands again from their middle lines: a band whose width the model sets is drawn at
 *  its own width there, point by point, not at the type's. It drew the map's ramp at W all along (the map lost in the
 *  picture) and a --silhouette-object-width band at the type's 2 px halfway out (paper between it and the model). */
TEST_F(WidthMapCylinder, TheStrokeStageDrawsABandOfVaryingWidthAtItsOwnWidth) {
    const auto stroked = [&](const Look& look, const std::string& type) {
        StillGraphSetup setup{look, shaders, scene, computeBoundingSphere(scene), *gpuScene, frame, std::nullopt};
        const StillGraph graph = buildStillGraph(setup);
        const Plan plan = compile(graph.view(), {type + ".lines", "strokes." + type, "gbuffer.coverage"});
        executor.run(plan, graph.mutableView(), {frame.camera.width, frame.camera.height, false});
        test::LineRender band, layer;
        band.lines = executor.store().image(type + ".lines").clone();
        band.coverage = executor.store().image("gbuffer.coverage").clone();
        // The layer is anti-aliased coverage: a pixel at least half covered is a line pixel.
        cv::threshold(executor.store().image("strokes." + type), layer.lines, 127, 255, cv::THRESH_BINARY);
        layer.coverage = band.coverage;
        executor.store().clear();
        return std::make_pair(band, layer);
    };
    std::ostringstream measured;
    for (const char* type : {"outline", "silhouette"}) {
        SCOPED_TRACE(type);
        Look look;
        look.shading = ShadingModel::None;
        look.lines = {type};
        look.lineStyles[type].widthPixels = kBandPixels;
        look.outlineWidthMap = parseWidthMap("color:R");
        measured << " " << type << ":";
        expectRampBands(stroked(look, type).second, measured);
    }
    // In model units: 0.5 is about 17 px here, the type's width 2 px.
    Look look;
    look.shading = ShadingModel::None;
    look.lines = {"silhouette"};
    const LineType* silhouette = findLineType("silhouette");
    ASSERT_NE(silhouette, nullptr);
    ASSERT_EQ(silhouette->parameters.size(), 1u);
    look.lineParameters.set(*silhouette->parameters[0], 0.5);
    const auto [band, layer] = stroked(look, "silhouette");
    measured << " object-width:";
    for (const double x : {-1.0, 0.0, 1.0}) {
        const int col = columnOf(x);
        SCOPED_TRACE("x " + std::to_string(x));
        for (const int step : {-1, 1}) {
            const test::OutsideRun drawn = test::measureOutsideRun(layer, {col, kHeight / 2}, 0, step);
            const int wide = test::measureOutsideRun(band, {col, kHeight / 2}, 0, step).length;
            EXPECT_GT(wide, 12);
            // From the model's edge out (a run measured from the coverage: a gap would make it 0), as wide as the band.
            EXPECT_NEAR(drawn.length, wide, 1.5);
            measured << " " << drawn.length << "/" << wide;
        }
    }
    // From 1024 rows up a width map's band is drawn wider than the line (bandWidthPixels(): 2 W at 2048 rows), which
    // only finds it: the line stays W x the map wide. At x = 0 the map is 1/2.
    constexpr int kTallRows = 2048;
    lookFrom({0.0, 0.0, kDistance}, glm::dvec3(0.0), kFovDegrees, kWidth, kTallRows);
    Look mapped;
    mapped.shading = ShadingModel::None;
    mapped.lines = {"outline"};
    mapped.lineStyles["outline"].widthPixels = kBandPixels;
    mapped.outlineWidthMap = parseWidthMap("color:R");
    const auto [tallBand, tallLayer] = stroked(mapped, "outline");
    measured << " 2048 rows, r0.5:";
    for (const int step : {-1, 1}) {
        const int wide = test::measureOutsideRun(tallBand, {kWidth / 2, kTallRows / 2}, 0, step).length;
        EXPECT_NEAR(wide, 2.0 * kBandPixels * ramp(0.0), 1.0);
        // The line pixels in the column off the model on this side (the line lies on the band's middle line).
        int drawn = 0;
        for (int row = kTallRows / 2; row >= 0 && row < kTallRows; row += step)
            drawn +=
                tallLayer.coverage.at<uchar>(row, kWidth / 2) != 255 && tallLayer.lines.at<uchar>(row, kWidth / 2) != 0;
        EXPECT_NEAR(drawn, kBandPixels * ramp(0.0), 1.0);
        measured << " " << drawn << "/" << wide;
    }
    std::cout << "stroked bands (above/below; object width: stroked/band):" << measured.str() << "\n";
}

/** MToon's shell on a unit sphere at distance 4, world width w: with the map (every vertex's R = 1/2) and the
 *  material's own width texture (every texel's G = 128/255), a shell of radius 1 + w x 1/2 x 128/255, its silhouette
 *  at focal x tan(asin(radius / 4)) pixels. */
TEST(WidthMapMToon, ShellWidthIsTheMaterialsTimesItsWidthTextureTimesTheMap) {
    test::sharedGlContext();
    test::PassHarness harness;
    constexpr int kSize = 128;
    constexpr double kWorldWidth = 0.4;
    Mesh sphere = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 128, 64);
    sphere.colors.assign(sphere.positions.size(), glm::vec4(0.5f, 0.0f, 0.0f, 1.0f));
    sphere.texcoords[0].assign(sphere.positions.size(), glm::vec2(0.5f));
    MToonMaterial mtoon;
    mtoon.outlineWidthMode = MToonMaterial::OutlineWidthMode::WorldCoordinates;
    mtoon.outlineWidthFactor = float(kWorldWidth);
    mtoon.outlineColorFactor = glm::vec3(1.0f, 0.0f, 0.0f);
    sphere.material.mtoon = mtoon;
    harness.scene = makeScene(std::move(sphere));
    const std::vector<unsigned char> texel = {0, 128, 0, 255};
    std::vector<unsigned char> png;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            auto* out = static_cast<std::vector<unsigned char>*>(context);
            out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
        },
        &png, 1, 1, 4, texel.data(), 4);
    SceneImage image;
    image.name = "half";
    image.encoded = std::make_shared<const std::vector<unsigned char>>(png);
    harness.scene.images.push_back(image);
    harness.frame.camera =
        test::lookingAt(harness.scene, glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(0.0), 50.0, kSize, kSize);
    harness.frame.worldOrigin = glm::dvec3(0.0);
    const double focal = harness.frame.camera.focalPixels();
    const auto outerRadius = [&](const cv::Mat& layer) {
        // Along the row through the centre: the outermost pixel the shell covers, to its outer edge.
        int found = 0;
        for (int col = kSize / 2; col < kSize; ++col)
            if (layer.at<cv::Vec4b>(kSize / 2, col)[3] != 0) found = col;
        return found + 1 - kSize / 2.0;
    };
    std::ostringstream measured;
    for (const bool textured : {false, true}) {
        for (const std::string map : {"none", "color:R"}) {
            MToonMaterial& material = *harness.scene.meshes[0].material.mtoon;
            material.outlineWidthMultiplyTexture = TextureRef{};
            if (textured) material.outlineWidthMultiplyTexture.image = 0;
            harness.gpuScene = std::make_unique<GpuScene>(harness.scene, harness.frame.worldOrigin);
            MToonOutlinePass pass(kMToonOutlinePass, harness.shaders, *harness.gpuScene, harness.frame, 1,
                                  parseWidthMap(map));
            const Plan plan = compile({&pass}, {"mtoon-outline.color"});
            harness.executor.run(plan, {&pass}, {kSize, kSize, false});
            const cv::Mat layer = harness.executor.store().image("mtoon-outline.color").clone();
            harness.executor.store().clear();
            const double factor = (textured ? 128.0 / 255.0 : 1.0) * (map == "none" ? 1.0 : 0.5);
            const double expected = focal * std::tan(std::asin((1.0 + kWorldWidth * factor) / 4.0));
            SCOPED_TRACE(std::string(textured ? "textured, " : "") + map);
            EXPECT_NEAR(outerRadius(layer), expected, 1.0);
            measured << " x" << factor << ":" << outerRadius(layer) << "/" << expected;
        }
    }
    std::cout << "MToon shell radius measured/expected px:" << measured.str() << "\n";
}

} // namespace
} // namespace inkgraph::width_map_gl_test
