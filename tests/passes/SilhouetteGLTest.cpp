// The inflated-hull silhouette pass on llvmpipe: ring widths on a sphere in screen space (distance, field of view,
// resolution and aspect) and object space, no gaps at the hard edges of the fandisk with split normals (and the gaps
// that welding closes), the eye-inside skip, near-plane clipping, hull normals computed only on demand, and equal to
// computePositionWeldedNormals() to the bit (a loaded mesh's own smooth normals shared when they are the same).
#include "passes/LineMaskTarget.h"
#include "passes/silhouette/SilhouettePass.h"
#include "scene/mesh/MeshOps.h"

#include "LineMaskTestSupport.h"

#include <cstdint>
#include <limits>
#include <sstream>

namespace inkgraph {
namespace {

using test::LineRender;
using test::OutsideRun;

/** Every mask pixel outside the analytic silhouette lies within `maxOutside` px of it, and every pixel inside lies
 *  within `maxInside` px; returns how many broke either bound. */
int countPixelsOffTheRing(const LineRender& render, const test::SilhouetteCircle& circle, double maxOutside,
                          double maxInside) {
    int off = 0;
    for (int row = 0; row < render.lines.rows; ++row)
        for (int col = 0; col < render.lines.cols; ++col) {
            if (render.lines.at<uchar>(row, col) != 255) continue;
            const double distance = circle.distance(col, row);
            off += distance > maxOutside || distance < -maxInside;
        }
    return off;
}

class SilhouetteSphere : public test::LinePassFixture {
protected:
    void SetUp() override {
        LinePassFixture::SetUp();
        setScene(test::fineSphereScene());
    }
};

struct ScreenWidthCase {
    double distance;
    double fovYDegrees;
    int width;
    int height;
};

TEST_F(SilhouetteSphere, ScreenSpaceWidthHoldsAtAnyDistanceFovAndResolution) {
    constexpr float kWidth = 3.0f;
    const ScreenWidthCase cases[] = {
        {4.0, 35.0, 256, 256},   {8.0, 35.0, 256, 256}, {4.0, 35.0, 512, 512},
        {8.0, 35.0, 512, 512},   {4.0, 60.0, 512, 512}, {6.0, 20.0, 384, 256}, // non-square: aspect correction
        {4.0, 35.0, 2048, 2048}, // above 1024 rows the band is the same share of the height: 6 px
    };
    HullSettings settings;
    settings.widthPixels = kWidth;
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
    std::ostringstream measured;
    for (const ScreenWidthCase& view : cases) {
        lookFrom({0.0, 0.0, view.distance}, glm::dvec3(0.0), view.fovYDegrees, view.width, view.height);
        const LineRender render = this->render(pass);
        const double band = bandWidthPixels(kWidth, view.height);
        EXPECT_EQ(band, view.height > 1024 ? kWidth * view.height / 1024.0 : kWidth);
        const char* sides[] = {"left", "right", "top", "bottom"};
        const std::vector<OutsideRun> runs = test::runsFromCentre(render);
        measured << "d" << view.distance << "/fov" << view.fovYDegrees << "/" << view.width << "x" << view.height
                 << ":";
        for (int side = 0; side < 4; ++side) {
            SCOPED_TRACE(std::string(sides[side]) + " at distance " + std::to_string(view.distance) + ", fov " +
                         std::to_string(view.fovYDegrees) + ", " + std::to_string(view.width) + "x" +
                         std::to_string(view.height));
            EXPECT_NEAR(runs[side].length, band, 1.0);
            EXPECT_EQ(runs[side].strayBeyond, 0);
            measured << " " << runs[side].length;
        }
        measured << ";";
        // The whole ring, not just four runs: nothing beyond width + 1 outside, nothing more than a pixel inside.
        const test::SilhouetteCircle circle = test::silhouetteOf(frame.camera, 1.0, view.distance);
        EXPECT_EQ(countPixelsOffTheRing(render, circle, band + 1.0, 1.0), 0);
        // And no holes: every pixel centre between 1 and width - 1 px outside the circle is in the mask.
        int holes = 0;
        for (int row = 0; row < render.lines.rows; ++row)
            for (int col = 0; col < render.lines.cols; ++col) {
                const double distance = circle.distance(col, row);
                holes += distance > 1.0 && distance < band - 1.0 && render.lines.at<uchar>(row, col) != 255;
            }
        EXPECT_EQ(holes, 0);
        // The stroke stage opens the band (2 x 2 at 2048 rows) before thinning it: the ring stays whole.
        const cv::Mat opened = openedBand(render.lines, kWidth);
        int openedHoles = 0;
        for (int row = 0; row < opened.rows; ++row)
            for (int col = 0; col < opened.cols; ++col) {
                const double distance = circle.distance(col, row);
                openedHoles += distance > 1.0 && distance < band - 1.0 && opened.at<uchar>(row, col) != 255;
            }
        EXPECT_EQ(openedHoles, 0);
        EXPECT_FALSE(pass.skippedEyeInside());
    }
    RecordProperty("ring_widths_left_right_top_bottom", measured.str());
}

TEST_F(SilhouetteSphere, ObjectSpaceWidthFollowsTheProjection) {
    constexpr double kObjectWidth = 0.1;
    constexpr int kFrameSide = 512;
    HullSettings settings;
    settings.objectWidth = float(kObjectWidth);
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
    double meanWidth[2] = {0.0, 0.0};
    const double distances[2] = {4.0, 8.0};
    for (int i = 0; i < 2; ++i) {
        lookFrom({0.0, 0.0, distances[i]}, glm::dvec3(0.0), 35.0, kFrameSide, kFrameSide);
        const LineRender render = this->render(pass);
        // The inflated sphere (radius R + t) projects to f (R + t) / sqrt(d^2 - (R + t)^2); to first order the ring
        // is t f / z at the silhouette's depth z = d - R^2 / d.
        const double focal = frame.camera.focalPixels();
        const double d = distances[i];
        const double expected = focal * ((1.0 + kObjectWidth) / std::sqrt(d * d - std::pow(1.0 + kObjectWidth, 2.0)) -
                                         1.0 / std::sqrt(d * d - 1.0));
        const double firstOrder = kObjectWidth * focal / (d - 1.0 / d);
        for (const OutsideRun& run : test::runsFromCentre(render)) {
            EXPECT_NEAR(run.length, expected, 1.0) << "distance " << d << ", first order " << firstOrder;
            EXPECT_EQ(run.strayBeyond, 0);
            meanWidth[i] += run.length / 4.0;
        }
        RecordProperty("object_width_px_at_distance_" + std::to_string(int(d)),
                       std::to_string(meanWidth[i]) + " (projected " + std::to_string(expected) + ")");
    }
    // Twice as far, half as wide (2.17x for this sphere: the silhouette's depth does not quite double).
    EXPECT_NEAR(meanWidth[1], meanWidth[0] / 2.0, 1.5);
    EXPECT_LT(meanWidth[1], meanWidth[0] * 0.6);
}

/** The fandisk with every triangle given its own three vertices carrying the face normal (what a file with
 *  per-face normals, or an auto-smooth split, gives): every edge is a hard edge. */
Scene flatShadedFandisk() {
    const Scene loaded = loadScene(std::string(INKGRAPH_SOURCE_ROOT) + "/models/fandisk_c3d.obj");
    Mesh flat;
    flat.name = "fandisk-flat";
    for (const Mesh& mesh : loaded.meshes)
        for (const glm::uvec3& triangle : mesh.triangles) {
            const glm::vec3 a = mesh.positions[triangle.x], b = mesh.positions[triangle.y],
                            c = mesh.positions[triangle.z];
            const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
            const auto first = std::uint32_t(flat.positions.size());
            for (const glm::vec3& p : {a, b, c}) {
                flat.positions.push_back(p);
                flat.normals.push_back(normal);
            }
            flat.triangles.emplace_back(first, first + 1, first + 2);
        }
    return makeScene(std::move(flat));
}

/** Pixels outside the model's coverage, 4-adjacent to a covered one, and not in the mask: cracks between the hull's
 *  outline and the model's. */
int gapPixels(const LineRender& render) {
    int gaps = 0;
    const cv::Mat& covered = render.coverage;
    for (int row = 0; row < covered.rows; ++row)
        for (int col = 0; col < covered.cols; ++col) {
            if (covered.at<uchar>(row, col) == 255 || render.lines.at<uchar>(row, col) == 255) continue;
            const bool touchesModel = (col > 0 && covered.at<uchar>(row, col - 1) == 255) ||
                                      (col + 1 < covered.cols && covered.at<uchar>(row, col + 1) == 255) ||
                                      (row > 0 && covered.at<uchar>(row - 1, col) == 255) ||
                                      (row + 1 < covered.rows && covered.at<uchar>(row + 1, col) == 255);
            gaps += touchesModel;
        }
    return gaps;
}

class SilhouetteFandisk : public test::LinePassFixture {
protected:
    void SetUp() override {
        LinePassFixture::SetUp();
        setScene(flatShadedFandisk());
    }
};

TEST_F(SilhouetteFandisk, WeldedHullHasNoGapsAtHardEdges) {
    const BoundingSphere sphere = computeBoundingSphere(scene);
    // Three views: the default framing's side, a top-down view and a grazing one.
    const glm::dvec3 directions[] = {glm::normalize(glm::dvec3(0.0, 0.25, 1.0)),
                                     glm::normalize(glm::dvec3(1.0, 2.0, 0.3)),
                                     glm::normalize(glm::dvec3(-1.0, -0.2, -0.4))};
    HullSettings welded;
    welded.widthPixels = 3.0f;
    HullSettings split = welded;
    split.weldNormals = false;
    SilhouettePass weldedPass("silhouette", shaders, *gpuScene, frame, welded);
    SilhouettePass splitPass("silhouette", shaders, *gpuScene, frame, split);
    int splitGapsTotal = 0;
    std::ostringstream measured;
    for (const glm::dvec3& direction : directions) {
        lookFrom(sphere.center + direction * (3.2 * sphere.radius), sphere.center, 35.0, 512, 512);
        const LineRender good = render(weldedPass);
        ASSERT_GT(cv::countNonZero(good.coverage), 10000) << "the model must fill a good part of the frame";
        EXPECT_EQ(gapPixels(good), 0) << "view from " << direction.x << "," << direction.y << "," << direction.z;
        const LineRender cracked = render(splitPass);
        const int splitGaps = gapPixels(cracked);
        splitGapsTotal += splitGaps;
        measured << splitGaps << " ";
    }
    // Negative control: offsetting along the raw split normals tears the hull open at the hard edges.
    EXPECT_GT(splitGapsTotal, 0);
    RecordProperty("split_normal_gap_pixels_per_view", measured.str());
}

/** A square card of a one-sided material, +z normals; `doubled` adds its back: a copy of its corners with -z normals
 *  and the two triangles wound the other way, as exporters write a double-faced card. */
Scene cardScene(bool doubled) {
    Mesh card;
    card.name = doubled ? "double-faced card" : "card";
    card.material.doubleSided = false;
    const std::vector<glm::vec3> corners = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    for (const glm::vec3& corner : corners) {
        card.positions.push_back(corner);
        card.normals.emplace_back(0, 0, 1);
    }
    card.triangles = {{0, 1, 2}, {0, 2, 3}};
    if (doubled) {
        for (const glm::vec3& corner : corners) {
            card.positions.push_back(corner);
            card.normals.emplace_back(0, 0, -1);
        }
        card.triangles.insert(card.triangles.end(), {{7, 6, 4}, {6, 5, 4}});
    }
    return makeScene(std::move(card));
}

class SilhouetteCard : public test::LinePassFixture {};

TEST_F(SilhouetteCard, ADoubleFacedCardsHullIsItsFirstSides) {
    // The second sheet's hull lay on the first's and drew lines across the card (a Y from its corners); left out of
    // the hull, the card's silhouette is the single card's, to the pixel, from the front.
    std::vector<cv::Mat> masks;
    for (const bool doubled : {false, true}) {
        setScene(cardScene(doubled));
        ASSERT_EQ(scene.meshes.at(0).triangles.size(), doubled ? 4u : 2u) << "a one-sided card keeps its back";
        EXPECT_EQ(gpuScene->hullIndexCount(0), 6);
        SilhouettePass pass("silhouette", shaders, *gpuScene, frame, HullSettings{});
        lookFrom({0.9, 1.2, 3.0}, glm::dvec3(0.0), 40.0, 256, 256);
        const LineRender rendered = render(pass);
        ASSERT_GT(cv::countNonZero(rendered.coverage), 5000);
        masks.push_back(rendered.lines.clone());
    }
    EXPECT_EQ(cv::norm(masks[0], masks[1], cv::NORM_INF), 0.0)
        << cv::countNonZero(masks[1] != masks[0]) << " pixels differ";
}

TEST_F(SilhouetteSphere, EyeInsideLeavesAnEmptyMask) {
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, HullSettings{});
    lookFrom({0.2, 0.1, 0.3}, {0.0, 0.0, -1.0}, 60.0, 128, 128);
    const LineRender inside = render(pass, false);
    EXPECT_TRUE(pass.skippedEyeInside());
    EXPECT_EQ(cv::countNonZero(inside.lines), 0);
    // The same pass outside again draws its ring.
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 128, 128);
    const LineRender outside = render(pass, false);
    EXPECT_FALSE(pass.skippedEyeInside());
    EXPECT_GT(cv::countNonZero(outside.lines), 100);
}

TEST_F(SilhouetteSphere, AnObjectWidthHullHoldingTheEyeIsSaidAsTheEyeInside) {
    // The unit sphere 1.5 units from the eye, its hull offset by 0.4 and then by 0.6 units: the second holds the eye
    // (radius 1.6), and from inside it the hull drew nothing, its skippedEyeInside false.
    lookFrom({0.0, 0.0, 1.5}, glm::dvec3(0.0), 90.0, 128, 128);
    HullSettings narrow;
    narrow.objectWidth = 0.4f;
    SilhouettePass outside("silhouette", shaders, *gpuScene, frame, narrow);
    const LineRender ring = render(outside, false);
    EXPECT_FALSE(outside.skippedEyeInside());
    EXPECT_GT(cv::countNonZero(ring.lines), 100);
    HullSettings wide;
    wide.objectWidth = 0.6f;
    SilhouettePass holding("silhouette", shaders, *gpuScene, frame, wide);
    const LineRender none = render(holding, false);
    EXPECT_TRUE(holding.skippedEyeInside());
    EXPECT_EQ(cv::countNonZero(none.lines), 0);
}

TEST_F(SilhouetteSphere, SphereBesideAndBehindTheEyeClipsCleanly) {
    // The eye 1.2 radii from the centre, looking past the sphere: it reaches behind the eye, the near plane cuts it
    // and hull vertices have w <= 0. Every visible point has view x > 0, so the left half must stay empty apart from
    // the line width (a vertex behind the eye projected without clipping would streak across it).
    constexpr float kWidth = 3.0f;
    HullSettings settings;
    settings.widthPixels = kWidth;
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, settings);
    lookFrom({-1.2, 0.0, 0.0}, {-1.2, 0.0, -1.0}, 90.0, 256, 256);
    const LineRender render = this->render(pass);
    EXPECT_FALSE(pass.skippedEyeInside());
    const int leftColumns = 128 - int(kWidth) - 1;
    EXPECT_EQ(cv::countNonZero(render.lines.colRange(0, leftColumns)), 0);
    EXPECT_EQ(cv::countNonZero(render.coverage.colRange(0, 128)), 0);
    EXPECT_GT(cv::countNonZero(render.lines), 100);
}

TEST_F(SilhouetteSphere, HullNormalsOnlyWhenThePassRuns) {
    SilhouettePass pass("silhouette", shaders, *gpuScene, frame, HullSettings{});
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 64, 64);
    // Only the coverage requested: the silhouette pass is culled, and nothing derives hull normals.
    const Plan plan = compile({gbuffer.get(), &pass}, {"gbuffer.coverage"});
    EXPECT_EQ(plan.findPass("silhouette"), nullptr);
    executor.run(plan, {gbuffer.get(), &pass}, {64, 64, false});
    EXPECT_TRUE(gpuScene->isUploaded());
    EXPECT_FALSE(gpuScene->hullNormalsComputed());
    render(pass, false);
    EXPECT_TRUE(gpuScene->hullNormalsComputed());
}

/** The hull normals GpuScene holds (read back from GL) against computePositionWeldedNormals() at its weld distance:
 *  equal to the bit whether they were computed or are the mesh's own smooth normals (a file without normals, nothing
 *  left to weld), which are then shared, not uploaded again. */
class HullNormalsOfModels : public test::LinePassFixture {};

TEST_F(HullNormalsOfModels, AreThePositionWeldedNormals) {
    struct Case {
        Scene scene;
        bool shared;
    };
    std::vector<Case> cases;
    cases.push_back({loadScene(std::string(INKGRAPH_SOURCE_ROOT) + "/models/fandisk_c3d.obj"), true});
    cases.push_back({loadScene(std::string(INKGRAPH_SOURCE_ROOT) + "/models/teapot_c3d.obj"), true});
    cases.push_back({flatShadedFandisk(), false});
    for (Case& entry : cases) {
        setScene(std::move(entry.scene));
        const Mesh& mesh = scene.meshes.at(0);
        const GlBuffer& buffer = gpuScene->hullNormals(0);
        EXPECT_EQ(&buffer == &gpuScene->meshes()[0].normals, entry.shared) << mesh.name;
        std::vector<glm::vec3> uploaded(mesh.positions.size());
        ASSERT_EQ(buffer.byteCount(), uploaded.size() * sizeof(glm::vec3));
        glGetNamedBufferSubData(buffer.id(), 0, GLsizeiptr(buffer.byteCount()), uploaded.data());
        const double distance = LoadOptions{}.weldTolerance * computeBoundingBox(mesh.positions).diagonal();
        EXPECT_EQ(uploaded, computePositionWeldedNormals(mesh.positions, mesh.triangles, distance)) << mesh.name;
    }
}

/** The hull tested against the G-buffer's z-buffer (what StillGraph chooses when the G-buffer runs anyway) against
 *  the pass's own draw of the model's depth: the same mask to the bit, on models with open borders (the teapot),
 *  hard edges (the fandisk) and fine detail (the bunny), from three sides, in screen and object width. */
TEST_F(HullNormalsOfModels, TheGBuffersZBufferGivesTheMaskOfTheModelsOwnDepth) {
    const char* models[] = {"fandisk_c3d.obj", "bunny_c3d_70k.obj", "teapot_c3d.obj"};
    const glm::dvec3 directions[] = {glm::normalize(glm::dvec3(0.2, 0.3, 1.0)),
                                     glm::normalize(glm::dvec3(1.0, 2.0, 0.3)),
                                     glm::normalize(glm::dvec3(-1.0, -0.2, -0.4))};
    HullSettings screenWidth;
    screenWidth.widthPixels = 3.0f;
    for (const char* model : models) {
        setScene(loadScene(std::string(INKGRAPH_SOURCE_ROOT) + "/models/" + model));
        const BoundingSphere sphere = computeBoundingSphere(scene); // relative to Scene::origin, like the positions
        const glm::dvec3 centre = scene.origin + sphere.center;
        HullSettings objectWidth;
        objectWidth.objectWidth = float(0.01 * sphere.radius);
        for (const HullSettings& settings : {screenWidth, objectWidth}) {
            SilhouettePass own("silhouette", shaders, *gpuScene, frame, settings);
            HullSettings sharing = settings;
            sharing.modelDepth = "gbuffer.zBuffer";
            SilhouettePass shared("silhouette", shaders, *gpuScene, frame, sharing);
            // The z-buffer is read only where the G-buffer runs anyway (here for its coverage).
            const Plan alone = compile({gbuffer.get(), &shared}, {"silhouette.lines"});
            ASSERT_NE(alone.findPass("silhouette"), nullptr);
            EXPECT_TRUE(alone.findPass("silhouette")->reads.empty());
            EXPECT_EQ(alone.findPass("gbuffer"), nullptr);
            const Plan plan = compile({gbuffer.get(), &shared}, {"silhouette.lines", "gbuffer.coverage"});
            ASSERT_NE(plan.findPass("silhouette"), nullptr);
            EXPECT_EQ(plan.findPass("silhouette")->reads, std::vector<std::string>{"gbuffer.zBuffer"});
            for (const glm::dvec3& direction : directions) {
                SCOPED_TRACE(std::string(model) + (settings.objectWidth ? ", object width" : ", screen width") +
                             ", view from " + std::to_string(direction.x) + "," + std::to_string(direction.y) + "," +
                             std::to_string(direction.z));
                lookFrom(centre + direction * (3.0 * sphere.radius), centre, 35.0, 384, 320);
                const cv::Mat expected = render(own, false).lines;
                const cv::Mat reused = render(shared, true).lines; // with the coverage: the G-buffer runs
                ASSERT_GT(cv::countNonZero(expected), 500) << "the hull must show";
                EXPECT_EQ(cv::countNonZero(expected != reused), 0);
            }
        }
    }
}

TEST(SilhouettePass, RejectsBadWidths) {
    const Scene scene = test::fineSphereScene();
    GpuScene gpuScene(scene, glm::dvec3(0.0));
    ShaderLibrary shaders;
    FrameParams frame;
    HullSettings negative;
    negative.widthPixels = -1.0f;
    EXPECT_THROW(SilhouettePass("s", shaders, gpuScene, frame, negative), std::invalid_argument);
    HullSettings notFinite;
    notFinite.objectWidth = std::numeric_limits<float>::infinity();
    EXPECT_THROW(SilhouettePass("s", shaders, gpuScene, frame, notFinite), std::invalid_argument);
}

} // namespace
} // namespace inkgraph
