// Lander's back-face outline pass on llvmpipe: the visible ring outside a sphere's silhouette is widthPixels wide at
// several distances, fields of view and resolutions, the inner half stays hidden by the fill, the eye-inside skip,
// near-plane clipping of edges that pass behind the eye, and what an artist would draw on sheets and thin shells
// (issue 19): a double-sided plane's border and nothing inside it, from either side, and no dotted ink inside a thin
// shell.
#include "passes/LineMaskTarget.h"
#include "passes/outline/OutlinePass.h"
#include "passes/silhouette/SilhouettePass.h"

#include "LineMaskTestSupport.h"

#include <nlohmann/json.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

namespace inkgraph {
namespace {

using test::LineRender;
using test::OutsideRun;

/** Adds an n x n grid on the parallelogram corner + [0, 1] u + [0, 1] v to `mesh`, two triangles a square,
 *  counter-clockwise seen from the side u x v points to. */
void addGrid(Mesh& mesh, glm::vec3 corner, glm::vec3 u, glm::vec3 v, int n) {
    const auto first = std::uint32_t(mesh.positions.size());
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) mesh.positions.push_back(corner + u * (float(i) / n) + v * (float(j) / n));
    const auto at = [&](int i, int j) { return first + std::uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            mesh.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
}

/** A 2 x 2 sheet in the z = 0 plane facing +z, an n x n grid: every square's diagonal is an interior edge. */
Mesh gridSheet(int n) {
    Mesh sheet;
    addGrid(sheet, {-1.0f, -1.0f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}, n);
    return sheet;
}

/** A closed box centred at the origin with half extents `half`, each face an n x n grid, facing out. */
Mesh gridBox(glm::vec3 half, int n) {
    Mesh box;
    for (int axis = 0; axis < 3; ++axis)
        for (const float side : {-1.0f, 1.0f}) {
            glm::vec3 normal(0.0f), u(0.0f), v(0.0f);
            normal[axis] = side;
            u[(axis + 1) % 3] = 2.0f * half[(axis + 1) % 3];
            v[(axis + 2) % 3] = 2.0f * half[(axis + 2) % 3];
            if (glm::dot(glm::cross(u, v), normal) < 0.0f) std::swap(u, v);
            addGrid(box, normal * half - 0.5f * u - 0.5f * v, u, v, n);
        }
    return box;
}

/** `mesh` with the triangles of `more` appended (one mesh, as a loader gives a two-layer garment). */
Mesh merged(Mesh mesh, const Mesh& more, bool reverseMore) {
    const auto offset = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), more.positions.begin(), more.positions.end());
    for (const glm::uvec3& triangle : more.triangles)
        mesh.triangles.push_back(reverseMore ? glm::uvec3(triangle.x, triangle.z, triangle.y) + offset
                                             : triangle + offset);
    mesh.normals.clear(); // makeScene() recomputes them
    return mesh;
}

cv::Mat disc(int radius) { return cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * radius + 1, 2 * radius + 1}); }

/** Line pixels more than `margin` pixels inside the coverage: where no outline of the model's own silhouette reaches.
 */
int interiorInk(const LineRender& render, int margin) {
    cv::Mat deepInside;
    cv::erode(render.coverage, deepInside, disc(margin));
    return cv::countNonZero(render.lines & deepInside);
}

/** The share of the pixels `distance` pixels outside the coverage that are line pixels (1 for a closed outline). */
double outlinedShare(const LineRender& render, int distance) {
    cv::Mat outer, inner;
    cv::dilate(render.coverage, outer, disc(distance));
    cv::dilate(render.coverage, inner, disc(distance - 1));
    const cv::Mat ring = outer & ~inner;
    return double(cv::countNonZero(render.lines & ring)) / double(std::max(1, cv::countNonZero(ring)));
}

/** Line pixels farther outside the coverage than a line `widthPixels` wide reaches: its square caps reach sqrt(2)
 *  widthPixels out at a corner of the outline, plus a pixel of rasterisation. */
int farOutsideInk(const LineRender& render, float widthPixels) {
    cv::Mat near;
    cv::dilate(render.coverage, near, disc(int(std::ceil(widthPixels * std::sqrt(2.0))) + 1));
    return cv::countNonZero(render.lines & ~near);
}

class OutlineShapes : public test::LinePassFixture {};

struct ShapeView {
    const char* what;
    glm::dvec3 eye;
};

TEST_F(OutlineShapes, DoubleSidedPlaneIsOutlinedAtItsBorderOnly) {
    // Seen from behind every face of a sheet is a back face: Lander's wireframe inked every diagonal. Seen from the
    // front it has no back face, and its border went undrawn. A card made as two coincident sheets wound both ways
    // (what some exporters write for double-sided) must look the same.
    constexpr float kWidth = 3.0f;
    std::ostringstream measured;
    for (const bool twoSheets : {false, true}) {
        Mesh sheet = gridSheet(8);
        setScene(makeScene(twoSheets ? merged(sheet, sheet, true) : sheet));
        const ShapeView views[] = {{"front", {1.2, 0.9, 2.8}}, {"behind", {-1.0, 0.6, -2.9}}};
        for (const ShapeView& view : views) {
            OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
            lookFrom(view.eye, glm::dvec3(0.0), 50.0, 256, 256);
            const LineRender render = this->render(pass);
            const std::string where = std::string(twoSheets ? "two sheets, " : "one sheet, ") + view.what;
            SCOPED_TRACE(where);
            const int interior = interiorInk(render, int(kWidth) + 1);
            const double outlined = outlinedShare(render, 2);
            measured << where << ": interior " << interior << ", border " << outlined << "; ";
            EXPECT_EQ(interior, 0) << "no diagonal or grid edge inside the sheet";
            EXPECT_GT(outlined, 0.97) << "the border is outlined all round";
            EXPECT_EQ(farOutsideInk(render, kWidth), 0);
        }
    }
    RecordProperty("interior_ink_and_border_share", measured.str());
}

TEST_F(OutlineShapes, ThinShellsHaveNoInteriorInk) {
    // A sheet thickened to 1% of its size, and a hollow ball whose inner wall (facing in) lies 1% inside its outer:
    // Lander's wireframe of the back layer lay just behind the visible front layer, and its wide quads poked through
    // the tilted front surface as dotted ink. Only the outline may be drawn: nothing more than widthPixels + 1
    // inside the coverage.
    constexpr float kWidth = 3.0f;
    const Mesh ball = makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 128, 64);
    const Mesh innerWall = makeUvSphere({0.0f, 0.0f, 0.0f}, 0.99f, 128, 64);
    struct Shell {
        const char* what;
        Mesh mesh;
        std::vector<ShapeView> views;
    };
    const Shell shells[] = {
        {"sheet", gridBox({1.0f, 1.0f, 0.01f}, 24), {{"above", {0.9, 1.8, 2.2}}, {"below", {-1.5, -0.8, -2.0}}}},
        {"hollow ball", merged(ball, innerWall, true), {{"front", {0.0, 0.6, 3.5}}}},
    };
    std::ostringstream measured;
    for (const Shell& shell : shells) {
        setScene(makeScene(shell.mesh));
        for (const ShapeView& view : shell.views) {
            OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
            lookFrom(view.eye, glm::dvec3(0.0), 50.0, 256, 256);
            const LineRender render = this->render(pass);
            const std::string where = std::string(shell.what) + " from " + view.what;
            SCOPED_TRACE(where);
            const int interior = interiorInk(render, int(kWidth) + 1);
            measured << where << ": " << interior << "; ";
            EXPECT_EQ(interior, 0);
            EXPECT_GT(outlinedShare(render, 2), 0.97) << "the outline is closed";
            EXPECT_EQ(farOutsideInk(render, kWidth), 0);
        }
    }
    RecordProperty("interior_ink", measured.str());
}

class OutlineSphere : public test::LinePassFixture {
protected:
    void SetUp() override {
        LinePassFixture::SetUp();
        setScene(test::fineSphereScene());
    }
};

struct OutlineCase {
    double distance;
    double fovYDegrees;
    int width;
    int height;
    float widthPixels;
};

TEST_F(OutlineSphere, VisibleRingIsWidthPixelsWide) {
    const OutlineCase cases[] = {
        {4.0, 35.0, 256, 256, 3.0f},   {8.0, 35.0, 256, 256, 3.0f}, {4.0, 35.0, 512, 512, 3.0f},
        {8.0, 60.0, 512, 512, 3.0f},   {6.0, 20.0, 384, 256, 3.0f}, {4.0, 35.0, 512, 512, 6.0f},
        {4.0, 35.0, 2048, 2048, 3.0f}, // above 1024 rows the band is the same share of the height: 6 px
    };
    std::ostringstream measured;
    for (const OutlineCase& view : cases) {
        OutlinePass pass("outline", shaders, *gpuScene, frame, view.widthPixels);
        lookFrom({0.0, 0.0, view.distance}, glm::dvec3(0.0), view.fovYDegrees, view.width, view.height);
        const LineRender render = this->render(pass);
        const double band = bandWidthPixels(view.widthPixels, view.height);
        const std::string where = "distance " + std::to_string(view.distance) + ", fov " +
                                  std::to_string(view.fovYDegrees) + ", " + std::to_string(view.width) + "x" +
                                  std::to_string(view.height) + ", width " + std::to_string(view.widthPixels);
        SCOPED_TRACE(where);
        measured << "d" << view.distance << "/fov" << view.fovYDegrees << "/" << view.width << "x" << view.height
                 << "/w" << view.widthPixels << ":";
        for (const OutsideRun& run : test::runsFromCentre(render)) {
            EXPECT_NEAR(run.length, band, 1.0);
            EXPECT_EQ(run.strayBeyond, 0);
            measured << " " << run.length;
        }
        measured << ";";
        // The fill hides the inner half of every line, and no back edge shows through the front of the sphere.
        const test::SilhouetteCircle circle = test::silhouetteOf(frame.camera, 1.0, view.distance);
        int deepInside = 0, farOutside = 0, holes = 0;
        for (int row = 0; row < render.lines.rows; ++row)
            for (int col = 0; col < render.lines.cols; ++col) {
                const double distance = circle.distance(col, row);
                const bool line = render.lines.at<uchar>(row, col) == 255;
                deepInside += line && distance < -(band + 1.0);
                farOutside += line && distance > band + 1.0;
                holes += !line && distance > 1.0 && distance < band - 1.0;
            }
        EXPECT_EQ(deepInside, 0);
        EXPECT_EQ(farOutside, 0);
        EXPECT_EQ(holes, 0);
        EXPECT_FALSE(pass.skippedEyeInside());
    }
    RecordProperty("ring_widths_left_right_top_bottom", measured.str());
}

TEST_F(OutlineSphere, InnerHalfIsHiddenByTheFill) {
    // Measured directly: the line pixels inside the model's coverage are at most a pixel deep, not widthPixels.
    constexpr float kWidth = 4.0f;
    OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 256, 256);
    const LineRender render = this->render(pass);
    const test::SilhouetteCircle circle = test::silhouetteOf(frame.camera, 1.0, 4.0);
    double deepest = 0.0;
    for (int row = 0; row < render.lines.rows; ++row)
        for (int col = 0; col < render.lines.cols; ++col)
            if (render.lines.at<uchar>(row, col) == 255 && render.coverage.at<uchar>(row, col) == 255)
                deepest = std::max(deepest, -circle.distance(col, row));
    EXPECT_LT(deepest, 1.5);
    RecordProperty("deepest_inner_line_pixel", std::to_string(deepest));
}

TEST_F(OutlineSphere, EyeInsideLeavesBothMasksEmpty) {
    OutlinePass outline("outline", shaders, *gpuScene, frame, 2.0f);
    SilhouettePass silhouette("silhouette", shaders, *gpuScene, frame, HullSettings{});
    lookFrom({0.1, -0.2, 0.3}, {1.0, 0.0, 0.0}, 70.0, 128, 128);
    EXPECT_EQ(cv::countNonZero(render(outline, false).lines), 0);
    EXPECT_TRUE(outline.skippedEyeInside());
    EXPECT_EQ(cv::countNonZero(render(silhouette, false).lines), 0);
    EXPECT_TRUE(silhouette.skippedEyeInside());
    nlohmann::ordered_json outlineReport, silhouetteReport;
    outline.describe(outlineReport);
    silhouette.describe(silhouetteReport);
    EXPECT_EQ(outlineReport.dump(), R"({"skipped_eye_inside":true})");
    EXPECT_EQ(silhouetteReport.dump(), R"({"skipped_eye_inside":true,"model_depth":"drawn by the pass"})");
    lookFrom({0.0, 0.0, 4.0}, glm::dvec3(0.0), 35.0, 128, 128);
    EXPECT_GT(cv::countNonZero(render(outline, false).lines), 100);
    EXPECT_FALSE(outline.skippedEyeInside());
}

TEST_F(OutlineSphere, EdgesBehindTheEyeAreClippedAtTheNearPlane) {
    // The eye 1.2 radii from the centre, looking past the sphere, which reaches behind the eye: back faces cross the
    // near plane and w = 0. Every visible point has view x > 0, so the left half of the frame must stay empty apart
    // from the line width; an edge projected without clipping would streak across it.
    constexpr float kWidth = 3.0f;
    OutlinePass pass("outline", shaders, *gpuScene, frame, kWidth);
    for (const double nearScale : {1.0, 4.0}) {
        lookFrom({-1.2, 0.0, 0.0}, {-1.2, 0.0, -1.0}, 90.0, 256, 256);
        // Also with the near plane pushed into the sphere, so the cut opens it and shows its back faces.
        frame.camera.zNear *= nearScale;
        const LineRender render = this->render(pass);
        SCOPED_TRACE("near " + std::to_string(frame.camera.zNear));
        EXPECT_FALSE(pass.skippedEyeInside());
        EXPECT_EQ(cv::countNonZero(render.coverage.colRange(0, 128)), 0);
        EXPECT_EQ(cv::countNonZero(render.lines.colRange(0, 128 - int(kWidth) - 1)), 0);
        EXPECT_GT(cv::countNonZero(render.lines), 100);
    }
}

/** outlineEdgeIndices() of a triangle list (welded exactly). */
std::vector<std::uint32_t> edgeIndicesOf(const Mesh& mesh) {
    return outlineEdgeIndices(mesh.positions, mesh.triangles, buildEdgeAdjacency(mesh.positions, mesh.triangles, 0.0));
}

TEST(OutlineEdges, EachEdgeOnceWithAnOppositeVertexOnEachSide) {
    const Mesh cube = gridBox(glm::vec3(1.0f), 1); // 12 triangles, 18 edges, each shared by two faces
    const std::vector<std::uint32_t> indices = edgeIndicesOf(cube);
    ASSERT_EQ(indices.size(), 18u * 4u);
    for (std::size_t edge = 0; edge < 18; ++edge) {
        const glm::vec3 a = cube.positions[indices[4 * edge + 1]];
        const glm::vec3 b = cube.positions[indices[4 * edge + 2]];
        for (const std::size_t opposite : {4 * edge, 4 * edge + 3}) {
            const glm::vec3 o = cube.positions[indices[opposite]];
            EXPECT_GT(glm::length(glm::cross(o - a, b - a)), 0.1f) << "edge " << edge << ": an end sent as opposite";
        }
        EXPECT_NE(cube.positions[indices[4 * edge]], cube.positions[indices[4 * edge + 3]]) << "edge " << edge;
    }
    // A lone triangle: three borders, each repeating its one opposite vertex (the shader's "always kept").
    Mesh triangle;
    triangle.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    triangle.triangles = {{0, 1, 2}};
    const std::vector<std::uint32_t> borders = edgeIndicesOf(triangle);
    ASSERT_EQ(borders.size(), 12u);
    for (std::size_t edge = 0; edge < 3; ++edge) {
        EXPECT_EQ(borders[4 * edge], borders[4 * edge + 3]);
        EXPECT_NE(borders[4 * edge], borders[4 * edge + 1]);
        EXPECT_NE(borders[4 * edge], borders[4 * edge + 2]);
    }
}

TEST(OutlineEdges, NonManifoldEdgesAreSentOnlyWhenTheirFacesCanFold) {
    // Two coincident sheets wound both ways: the 8 border edges are manifold (one face of each sheet) and sent; the
    // 8 inner edges (4 grid segments, 4 diagonals) have four faces on both sides and can never fold.
    const Mesh sheet = gridSheet(2);
    EXPECT_EQ(edgeIndicesOf(merged(sheet, sheet, true)).size(), 8u * 4u);
    EXPECT_EQ(edgeIndicesOf(sheet).size(), 16u * 4u) << "one sheet: every edge, borders and inner ones";

    // Three pages on a spine (the z axis), each a triangle reaching out at an angle about it: within less than half a
    // turn they can all lie on one side of the eye's plane, and the outermost two are sent; spread over more than half
    // a turn they cannot.
    const auto book = [](std::initializer_list<double> anglesDegrees) {
        Mesh pages;
        pages.positions = {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
        for (const double angle : anglesDegrees) {
            const double radians = glm::radians(angle);
            pages.positions.emplace_back(std::cos(radians), std::sin(radians), 0.5);
            pages.triangles.emplace_back(0, 1, std::uint32_t(pages.positions.size() - 1));
        }
        return pages;
    };
    const std::vector<std::uint32_t> narrow = edgeIndicesOf(book({0.0, 70.0, 30.0}));
    // The spine first, then each page's two borders.
    ASSERT_EQ(narrow.size(), 7u * 4u);
    EXPECT_EQ(std::min(narrow[0], narrow[3]), 2u) << "the page at 0 degrees";
    EXPECT_EQ(std::max(narrow[0], narrow[3]), 3u) << "the page at 70 degrees";
    EXPECT_EQ(edgeIndicesOf(book({0.0, 90.0, 180.0})).size(), 6u * 4u) << "a T: exactly half a turn";
    EXPECT_EQ(edgeIndicesOf(book({0.0, 100.0, 200.0})).size(), 6u * 4u);
}

TEST(OutlinePass, RejectsBadWidths) {
    const Scene scene = test::fineSphereScene();
    GpuScene gpuScene(scene, glm::dvec3(0.0));
    ShaderLibrary shaders;
    FrameParams frame;
    EXPECT_THROW(OutlinePass("o", shaders, gpuScene, frame, -2.0f), std::invalid_argument);
    EXPECT_THROW(OutlinePass("o", shaders, gpuScene, frame, std::numeric_limits<float>::quiet_NaN()),
                 std::invalid_argument);
}

} // namespace
} // namespace inkgraph
