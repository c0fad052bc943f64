// The G-buffer's per-pixel labels (issue 37): triangleId, meshId and barycentric, against a brute-force ray cast
// through every pixel centre on the CPU (double precision, every triangle of both meshes). The scene is a UV sphere
// with a cube in front of it, seen obliquely, so the cube hides part of the sphere and both show many triangles; and
// the same as an OBJ file with triangles the loader drops (zero-area, back to back), whose ids must still name the
// file's triangles. Needs a GL context (llvmpipe in CI).
#include "gl/GraphExecutor.h"
#include "graph/GraphCompiler.h"
#include "passes/GpuScene.h"
#include "passes/gbuffer/GBufferPass.h"
#include "scene/MeshLabels.h"
#include "scene/mesh/Procedural.h"
#include "tests/support/GlTestContext.h"
#include "tests/support/PassHarness.h"
#include "tests/support/TestCamera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

#include <unistd.h>

namespace inkgraph::gbuffer_labels_gl_test {
namespace {

constexpr int kSize = 160;
constexpr double kFovDegrees = 35.0;

/** What the ray through one pixel centre meets first. */
struct RayHit {
    std::uint32_t triangle = 0; ///< global index + 1, as the field stores it
    std::uint32_t mesh = 0;     ///< mesh index + 1
    glm::dvec3 point{0.0};      ///< world point
};

/** A mesh's triangles as the ids are to name them: the file's, in its order (in the scene's frame). */
struct TruthMesh {
    std::vector<glm::dvec3> positions;
    std::vector<glm::uvec3> triangles;
};

class GBufferLabels : public ::testing::Test, protected test::PassHarness {
protected:
    void SetUp() override {
        test::sharedGlContext();
        scene = makeScene(makeUvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 48, 24));
        // In front of the sphere toward the eye, clear of it (its back face at z = 1.15 > the radius).
        scene.meshes.push_back(makeCube({0.35f, -0.25f, 1.6f}, 0.45f));
        std::vector<TruthMesh> asBuilt;
        for (const Mesh& mesh : scene.meshes)
            asBuilt.push_back({std::vector<glm::dvec3>(mesh.positions.begin(), mesh.positions.end()), mesh.triangles});
        useTruth(std::move(asBuilt));
    }

    /** The triangles the ids must name, and the camera on the scene. */
    void useTruth(std::vector<TruthMesh> meshes) {
        truth = std::move(meshes);
        frame.camera =
            test::lookingAt(scene, glm::dvec3(2.2, 1.6, 4.8), glm::dvec3(0.0, 0.0, 0.4), kFovDegrees, kSize, kSize);
        frame.worldOrigin = glm::dvec3(0.0);
        firstTriangle.clear();
        triangleCount = 0;
        for (const TruthMesh& mesh : truth) {
            firstTriangle.push_back(triangleCount);
            triangleCount += mesh.triangles.size();
        }
    }

    /** Compiles the G-buffer pass for `requested` and runs it. */
    Plan render(const std::vector<std::string>& requested) {
        gpuScene = std::make_unique<GpuScene>(scene, frame.worldOrigin);
        pass = std::make_unique<GBufferPass>("gbuffer", shaders, *gpuScene, frame);
        Plan plan = compile({pass.get()}, requested);
        executor.run(plan, {pass.get()}, {kSize, kSize, false});
        return plan;
    }

    /** The eye ray through the centre of pixel (col, row) (row 0 at the top). */
    std::pair<glm::dvec3, glm::dvec3> rayThrough(int col, int row) const {
        const glm::dmat4 inverse = glm::inverse(frame.camera.projectionMatrix() * frame.camera.viewMatrix());
        const glm::dvec2 ndc((col + 0.5) / kSize * 2.0 - 1.0, 1.0 - (row + 0.5) / kSize * 2.0);
        const glm::dvec4 nearPoint = inverse * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farPoint = inverse * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
        return {origin, glm::dvec3(farPoint) / farPoint.w - origin};
    }

    /** Brute force: the nearest triangle of any mesh the ray through pixel (col, row) meets (Moller-Trumbore in
     *  double, both faces). */
    std::optional<RayHit> castPixel(int col, int row) const {
        const auto [origin, direction] = rayThrough(col, row);
        std::optional<RayHit> nearest;
        double nearestT = std::numeric_limits<double>::infinity();
        for (std::size_t meshIndex = 0; meshIndex < truth.size(); ++meshIndex) {
            const TruthMesh& mesh = truth[meshIndex];
            for (std::size_t index = 0; index < mesh.triangles.size(); ++index) {
                const std::array<glm::dvec3, 3> p = corners(meshIndex, index);
                const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
                const glm::dvec3 pvec = glm::cross(direction, e2);
                const double det = glm::dot(e1, pvec);
                if (std::abs(det) < 1e-300) continue; // parallel, or a zero-area triangle: no ray meets it
                const glm::dvec3 tvec = origin - p[0];
                const double u = glm::dot(tvec, pvec) / det;
                if (u < 0.0 || u > 1.0) continue;
                const glm::dvec3 qvec = glm::cross(tvec, e1);
                const double v = glm::dot(direction, qvec) / det;
                if (v < 0.0 || u + v > 1.0) continue;
                const double t = glm::dot(e2, qvec) / det;
                if (t <= 0.0 || t >= nearestT) continue; // of two back to back, the earlier: the one kept
                nearestT = t;
                nearest = RayHit{std::uint32_t(firstTriangle[meshIndex] + index + 1), std::uint32_t(meshIndex + 1),
                                 origin + t * direction};
            }
        }
        return nearest;
    }

    /** The corners of the file's triangle `index` of mesh `meshIndex`, in index order. */
    std::array<glm::dvec3, 3> corners(std::size_t meshIndex, std::size_t index) const {
        const TruthMesh& mesh = truth[meshIndex];
        const glm::uvec3 triangle = mesh.triangles[index];
        return {mesh.positions[triangle.x], mesh.positions[triangle.y], mesh.positions[triangle.z]};
    }

    /** The corners of the triangle with global id `id` (index + 1). */
    std::array<glm::dvec3, 3> cornersOfId(std::uint32_t id) const {
        std::size_t meshIndex = truth.size() - 1;
        while (firstTriangle[meshIndex] >= id) --meshIndex;
        return corners(meshIndex, id - 1 - firstTriangle[meshIndex]);
    }

    /** A world point in pixels (x right, y down, the pixel (col, row)'s centre at (col + 0.5, row + 0.5)). */
    glm::dvec2 project(const glm::dvec3& world) const {
        const glm::dvec4 clip = frame.camera.projectionMatrix() * frame.camera.viewMatrix() * glm::dvec4(world, 1.0);
        return {(clip.x / clip.w + 1.0) * 0.5 * kSize, (1.0 - clip.y / clip.w) * 0.5 * kSize};
    }

    /** How far (pixels) the centre of pixel (col, row) lies from the nearest edge of triangle `id`'s image. */
    double pixelsFromEdge(int col, int row, std::uint32_t id) const {
        const std::array<glm::dvec3, 3> p = cornersOfId(id);
        const glm::dvec2 centre(col + 0.5, row + 0.5);
        double best = std::numeric_limits<double>::infinity();
        for (int edge = 0; edge < 3; ++edge) {
            const glm::dvec2 a = project(p[edge]), b = project(p[(edge + 1) % 3]);
            const double along = std::clamp(glm::dot(centre - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
            best = std::min(best, glm::length(centre - (a + along * (b - a))));
        }
        return best;
    }

    /** Renders the ids and checks them against a ray cast through every pixel centre. */
    void expectIdsMatchTheRayCast();
    /** Renders the barycentrics and checks the points they give against the ray cast's. */
    void expectBarycentricsGiveTheRaysPoints();

    std::unique_ptr<GBufferPass> pass;
    std::vector<TruthMesh> truth;
    std::vector<std::size_t> firstTriangle; ///< per mesh: the global index of its first triangle
    std::size_t triangleCount = 0;
};

/** The distinct ids of the CPU ray cast within a pixel's 3x3 neighbourhood: one exactly when the pixel is away from
 *  every silhouette (between meshes or against the background). */
bool awayFromSilhouette(const std::vector<std::optional<RayHit>>& hits, int col, int row) {
    if (col == 0 || row == 0 || col == kSize - 1 || row == kSize - 1) return false;
    const std::optional<RayHit>& centre = hits[std::size_t(row * kSize + col)];
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const std::optional<RayHit>& other = hits[std::size_t((row + dy) * kSize + col + dx)];
            if (other.has_value() != centre.has_value() || (other && other->mesh != centre->mesh)) return false;
        }
    return true;
}

void GBufferLabels::expectIdsMatchTheRayCast() {
    const Plan plan = render({"gbuffer.triangleId", "gbuffer.meshId", "gbuffer.coverage"});
    EXPECT_EQ(plan.findResource("gbuffer.triangleId")->desc.format, Format::R32F) << "exact below 2^24 triangles";
    EXPECT_EQ(plan.findResource("gbuffer.meshId")->desc.format, Format::R32F);
    const cv::Mat triangles = executor.store().image("gbuffer.triangleId");
    const cv::Mat meshes = executor.store().image("gbuffer.meshId");
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    ASSERT_EQ(triangles.type(), CV_32FC1);
    ASSERT_EQ(triangles.size(), cv::Size(kSize, kSize));

    std::vector<std::optional<RayHit>> hits(std::size_t(kSize * kSize));
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) hits[std::size_t(row * kSize + col)] = castPixel(col, row);

    int covered = 0, sameTriangle = 0, coverageDisagrees = 0, compared = 0, meshWrong = 0, offModelNonZero = 0;
    double worstEdgeDistance = 0.0; // of a pixel whose triangle differs, from the nearer of the two triangles' edges
    std::array<int, 3> coveredPerMesh{};
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) {
            const std::optional<RayHit>& hit = hits[std::size_t(row * kSize + col)];
            const float triangle = triangles.at<float>(row, col);
            const float mesh = meshes.at<float>(row, col);
            const bool onModel = coverage.at<uchar>(row, col) != 0;
            if (!onModel) {
                offModelNonZero += triangle != 0.0f || mesh != 0.0f;
                coverageDisagrees += hit.has_value();
                if (hit) worstEdgeDistance = std::max(worstEdgeDistance, pixelsFromEdge(col, row, hit->triangle));
                continue;
            }
            ++covered;
            ++coveredPerMesh[std::size_t(std::clamp(int(mesh), 0, 2))];
            // An exact integer: the float holds the id itself.
            ASSERT_EQ(triangle, std::floor(triangle));
            ASSERT_GE(triangle, 1.0f);
            ASSERT_LE(triangle, float(triangleCount));
            if (!hit) {
                ++coverageDisagrees;
                worstEdgeDistance = std::max(worstEdgeDistance, pixelsFromEdge(col, row, std::uint32_t(triangle)));
                continue;
            }
            if (std::uint32_t(triangle) == hit->triangle) {
                ++sameTriangle;
            } else {
                // Where the two disagree, the pixel centre lies on (within rounding of) the edge between them.
                worstEdgeDistance =
                    std::max(worstEdgeDistance, std::min(pixelsFromEdge(col, row, hit->triangle),
                                                         pixelsFromEdge(col, row, std::uint32_t(triangle))));
            }
            if (awayFromSilhouette(hits, col, row)) {
                ++compared;
                meshWrong += std::uint32_t(mesh) != hit->mesh;
            }
        }
    EXPECT_GT(covered, 4000);
    EXPECT_GT(coveredPerMesh[1], 1000) << "the sphere shows";
    EXPECT_GT(coveredPerMesh[2], 1000) << "the cube shows";
    EXPECT_EQ(offModelNonZero, 0) << "off the model both ids are 0";
    const double agreement = double(sameTriangle) / double(covered);
    EXPECT_GE(agreement, 0.995);
    EXPECT_LE(worstEdgeDistance, 0.01) << "a pixel whose triangle (or coverage) differs lies off every edge";
    EXPECT_GT(compared, 3000);
    EXPECT_EQ(meshWrong, 0) << "pixels away from the silhouettes whose meshId is not the ray's mesh";
    RecordProperty("triangle_agreement", std::to_string(agreement));
    RecordProperty("coverage_disagreements", std::to_string(coverageDisagrees));
    RecordProperty("worst_edge_distance_px", std::to_string(worstEdgeDistance));
}

TEST_F(GBufferLabels, TriangleAndMeshIdsMatchARayCastThroughEveryPixelCentre) { expectIdsMatchTheRayCast(); }

void GBufferLabels::expectBarycentricsGiveTheRaysPoints() {
    const Plan plan = render({"gbuffer.barycentric", "gbuffer.triangleId", "gbuffer.coverage"});
    EXPECT_EQ(plan.findResource("gbuffer.barycentric")->desc.format, Format::RGBA32F);
    const cv::Mat weights = executor.store().image("gbuffer.barycentric");
    const cv::Mat triangles = executor.store().image("gbuffer.triangleId");
    const cv::Mat coverage = executor.store().image("gbuffer.coverage");
    ASSERT_EQ(weights.type(), CV_32FC4);
    // The model's size: the diagonal of the scene's bounding box (about 2.9 here).
    double modelSize = 0.0;
    {
        glm::dvec3 lower(std::numeric_limits<double>::infinity()), upper(-std::numeric_limits<double>::infinity());
        for (const Mesh& mesh : scene.meshes)
            for (const glm::vec3& position : mesh.positions) {
                lower = glm::min(lower, glm::dvec3(position));
                upper = glm::max(upper, glm::dvec3(position));
            }
        modelSize = glm::length(upper - lower);
    }
    int compared = 0, offModelNonZero = 0, sameAsTriangleId = 0, onModel = 0;
    double worstPointError = 0.0, worstOutside = 0.0, worstSumError = 0.0;
    for (int row = 0; row < kSize; ++row)
        for (int col = 0; col < kSize; ++col) {
            const cv::Vec4f b = weights.at<cv::Vec4f>(row, col);
            if (coverage.at<uchar>(row, col) == 0) {
                offModelNonZero += b != cv::Vec4f(0.0f, 0.0f, 0.0f, 0.0f);
                continue;
            }
            // Alpha names the weights' own triangle; it is the triangleId field's but where the two draws differ.
            ++onModel;
            EXPECT_GE(b[3], 1.0f);
            sameAsTriangleId += b[3] == triangles.at<float>(row, col);
            const std::optional<RayHit> hit = castPixel(col, row);
            if (!hit) continue; // the pixel centre grazes the silhouette (the triangle test bounds how closely)
            // The weights of the G-buffer's own triangle: where it is the ray's neighbour across an edge, the point
            // they give still lies within rounding of the ray's.
            const std::array<glm::dvec3, 3> p = cornersOfId(std::uint32_t(b[3]));
            const glm::dvec3 point = double(b[0]) * p[0] + double(b[1]) * p[1] + double(b[2]) * p[2];
            worstPointError = std::max(worstPointError, glm::length(point - hit->point));
            for (int corner = 0; corner < 3; ++corner)
                worstOutside = std::max({worstOutside, -double(b[corner]), double(b[corner]) - 1.0});
            worstSumError = std::max(worstSumError, std::abs(double(b[0]) + b[1] + b[2] - 1.0));
            ++compared;
        }
    EXPECT_GT(compared, 4000);
    EXPECT_GE(sameAsTriangleId, onModel - onModel / 1000) << "alpha and triangleId name the same triangle";
    EXPECT_EQ(offModelNonZero, 0) << "off the model the weights are 0";
    EXPECT_LE(worstPointError, 1e-4 * modelSize) << "sum of b_i p_i against the ray's hit point";
    EXPECT_LE(worstOutside, 1e-5) << "a weight outside [0, 1]";
    EXPECT_LE(worstSumError, 1e-5) << "weights that do not sum to 1";
    RecordProperty("worst_point_error_relative", std::to_string(worstPointError / modelSize));
    RecordProperty("worst_weight_outside", std::to_string(worstOutside));
    RecordProperty("worst_sum_error", std::to_string(worstSumError));
}

TEST_F(GBufferLabels, BarycentricWeightsReconstructTheRaysHitPoint) { expectBarycentricsGiveTheRaysPoints(); }

/** Writes `meshes` (positions in the file's frame) as an OBJ of one object per mesh, every coordinate float-exact. */
void writeObj(const std::filesystem::path& path, const std::vector<TruthMesh>& meshes) {
    std::ofstream file(path);
    std::size_t firstVertex = 1;
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        file << "o part" << index << "\n";
        char line[128];
        for (const glm::dvec3& position : meshes[index].positions) {
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", position.x, position.y, position.z);
            file << line;
        }
        for (const glm::uvec3& triangle : meshes[index].triangles)
            file << "f " << firstVertex + triangle.x << ' ' << firstVertex + triangle.y << ' '
                 << firstVertex + triangle.z << "\n";
        firstVertex += meshes[index].positions.size();
    }
}

TEST_F(GBufferLabels, IdsAndWeightsNameTheFilesTrianglesAndCornersWhereTheLoaderChangedThem) {
    // The fixture's sphere and cube as a file with triangles the loader drops in both: a triangle with a repeated
    // corner, one whose corner is a second vertex at another's position (the weld collapses it), and a face's back-to-
    // back twin (the default material is two-sided), in the middle and at each end. The ids must still be the file's
    // triangle numbers, not the loaded mesh's, and the weights the file's corners'.
    std::vector<TruthMesh> file = truth;
    TruthMesh& sphere = file[0];
    const std::uint32_t copyOfFirst = std::uint32_t(sphere.positions.size());
    sphere.positions.push_back(sphere.positions[sphere.triangles[40].x]);
    const glm::uvec3 twinOf = sphere.triangles[99];
    sphere.triangles.insert(sphere.triangles.begin() + 300, {twinOf.x, twinOf.z, twinOf.y});
    sphere.triangles.insert(sphere.triangles.begin() + 41,
                            {sphere.triangles[40].x, sphere.triangles[40].y, copyOfFirst});
    sphere.triangles.insert(sphere.triangles.begin(),
                            {sphere.triangles[7].x, sphere.triangles[7].x, sphere.triangles[7].y});
    // The cube wound inside out: the loader turns it outward, swapping each triangle's last two corners, so its
    // barycentric weights must be swapped back to be the file's corners'.
    TruthMesh& cube = file[1];
    for (glm::uvec3& triangle : cube.triangles) triangle = {triangle.x, triangle.z, triangle.y};
    cube.triangles.insert(cube.triangles.begin() + 5, {cube.triangles[5].y, cube.triangles[5].y, cube.triangles[5].z});
    const glm::uvec3 lastFace = cube.triangles.back();
    cube.triangles.push_back({lastFace.y, lastFace.x, lastFace.z});
    const std::filesystem::path path =
        std::filesystem::path(::testing::TempDir()) / ("gbuffer-labels-" + std::to_string(::getpid()) + ".obj");
    writeObj(path, file);
    scene = loadScene(path.string());
    std::filesystem::remove(path);
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.report.degenerateDropped, 3u);
    EXPECT_EQ(scene.report.backToBackDropped, 2u);
    EXPECT_EQ(scene.meshes[0].triangleCount() + 3, sphere.triangles.size());
    EXPECT_EQ(scene.meshes[1].triangleCount() + 2, cube.triangles.size());
    EXPECT_TRUE(scene.meshes[0].cornersSwapped.empty());
    EXPECT_EQ(scene.meshes[1].cornersSwapped, std::vector<std::uint8_t>(scene.meshes[1].triangleCount(), 1));
    // The ids the labels give the meshes cover the file's triangles.
    const SceneLabels labels = sceneLabels(scene);
    EXPECT_EQ(labels.meshes[0].triangleCount, sphere.triangles.size());
    EXPECT_EQ(labels.meshes[1].firstTriangle, sphere.triangles.size());
    EXPECT_EQ(labels.meshes[1].triangleCount, cube.triangles.size());
    // The loaded positions are relative to the model's centre (Scene::origin).
    for (TruthMesh& mesh : file)
        for (glm::dvec3& position : mesh.positions) position = glm::dvec3(glm::vec3(position - scene.origin));
    useTruth(std::move(file));
    {
        SCOPED_TRACE("triangle and mesh ids");
        expectIdsMatchTheRayCast();
    }
    SCOPED_TRACE("barycentrics");
    expectBarycentricsGiveTheRaysPoints();
}

} // namespace
} // namespace inkgraph::gbuffer_labels_gl_test
