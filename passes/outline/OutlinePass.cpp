#include "passes/outline/OutlinePass.h"

#include "gl/GraphExecutor.h"
#include "passes/LineMaskTarget.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace inkgraph {
namespace {

/** The corner of `triangle` opposite the edge a-b: the one farthest from the edge's line. The ends may be other copies
 *  of a welded vertex than the triangle's, so ids cannot be compared. */
std::uint32_t oppositeCorner(std::span<const glm::vec3> positions, const glm::uvec3& triangle, const glm::dvec3& a,
                             const glm::dvec3& along) {
    std::uint32_t opposite = triangle[0];
    double farthest = -1.0;
    for (int corner = 0; corner < 3; ++corner) {
        const double distance = glm::length(glm::cross(glm::dvec3(positions[triangle[corner]]) - a, along));
        if (distance > farthest) {
            farthest = distance;
            opposite = triangle[corner];
        }
    }
    return opposite;
}

} // namespace

std::vector<std::uint32_t> outlineEdgeIndices(std::span<const glm::vec3> positions,
                                              std::span<const glm::uvec3> triangles, const EdgeAdjacency& adjacency) {
    std::vector<std::uint32_t> indices;
    indices.reserve(adjacency.edges.size() * 4);
    std::vector<std::pair<double, std::uint32_t>> around; // a non-manifold edge's faces: angle about the edge, vertex
    for (const MeshEdge& edge : adjacency.edges) {
        const glm::dvec3 a(positions[edge.vertices.x]);
        const glm::dvec3 along = glm::dvec3(positions[edge.vertices.y]) - a;
        around.clear();
        for (const EdgeFaceUse& use : adjacency.facesOf(edge)) {
            if (use.face >= triangles.size())
                throw std::invalid_argument("outlineEdgeIndices(): face " + std::to_string(use.face) +
                                            " of the adjacency is past the " + std::to_string(triangles.size()) +
                                            " triangles");
            around.emplace_back(0.0, oppositeCorner(positions, triangles[use.face], a, along));
        }
        if (around.empty()) continue;
        std::uint32_t first = around.front().second;
        std::uint32_t second = around.back().second; // a border repeats its one opposite vertex
        if (around.size() > 2) {
            // Every face must lie within one half-space bounded by a plane through the edge for the surface to fold
            // back there; then the two faces bounding the widest gap around the edge are the outermost, and the
            // fold test on them is the test on all. A gap of exactly half a turn (two coincident sheets of a
            // double-sided plane, wound both ways) never folds.
            const glm::dvec3 axis = glm::normalize(along);
            const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
            const glm::dvec3 x = glm::normalize(glm::cross(axis, helper));
            const glm::dvec3 y = glm::cross(axis, x);
            for (auto& [angle, vertex] : around) {
                const glm::dvec3 offset = glm::dvec3(positions[vertex]) - a;
                angle = std::atan2(glm::dot(offset, y), glm::dot(offset, x));
            }
            std::sort(around.begin(), around.end());
            std::size_t widest = around.size() - 1; // the gap from the last angle round to the first
            double widestGap = around.front().first + glm::two_pi<double>() - around.back().first;
            for (std::size_t index = 0; index + 1 < around.size(); ++index) {
                const double gap = around[index + 1].first - around[index].first;
                if (gap > widestGap) {
                    widestGap = gap;
                    widest = index;
                }
            }
            if (widestGap <= glm::pi<double>() * (1.0 + 1e-9)) continue;
            first = around[widest].second;
            second = around[(widest + 1) % around.size()].second;
        }
        indices.insert(indices.end(), {first, edge.vertices.x, edge.vertices.y, second});
    }
    return indices;
}

OutlinePass::OutlinePass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                         float widthPixels, WidthMap widthMap)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mWidthPixels(widthPixels),
      mWidthMap(std::move(widthMap)), mDepth(mName + " model depth") {
    if (!std::isfinite(mWidthPixels) || mWidthPixels < 0.0f)
        throw std::invalid_argument("OutlinePass(): pass '" + mName + "': 'widthPixels' must be finite and >= 0, got " +
                                    std::to_string(mWidthPixels));
}

void OutlinePass::declare(PassBuilder& builder) const {
    builder.import(SceneImport::kMeshes);
    builder.import(SceneImport::kEdgeAdjacency); // the contour and border edges it chooses among
    builder.write("lines", {Format::R8}, Need::Required,
                  {"band-" + mName + ".png", Appearance::Lines,
                   "the band GL drew for " + mName + ", at the output size, before the stroke stage thins it"});
}

void OutlinePass::describe(nlohmann::ordered_json& report) const {
    report["skipped_eye_inside"] = skippedEyeInside();
    if (mWidthMap.enabled()) report["width_map"] = mWidthMap.text();
}

void OutlinePass::prepare(GlPassContext&) {
    if (!mDepthProgram)
        mDepthProgram =
            std::make_unique<GlProgram>(mShaders.build({mName + " model depth",
                                                        "outline/outline.vert",
                                                        "common/line_mask.frag",
                                                        materialAlphaDefines(mScene),
                                                        {"common/material.glsl", "common/width_map.glsl"}}));
    if (!mLineProgram)
        mLineProgram = std::make_unique<GlProgram>(mShaders.build({mName + " contour edges",
                                                                   "outline/outline.vert",
                                                                   "common/line_mask.frag",
                                                                   materialAlphaDefines(mScene),
                                                                   {"common/material.glsl", "common/width_map.glsl"},
                                                                   "outline/outline.geom"}));
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    if (!mEdges.empty()) return;
    // The edges do not depend on the view (the geometry shader chooses among them): chosen and uploaded once.
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        const Mesh& mesh = mScene.scene().meshes[index];
        const std::vector<std::uint32_t> indices =
            outlineEdgeIndices(mesh.positions, mesh.triangles, mScene.edgeAdjacency(index));
        EdgeList& edges = mEdges.emplace_back();
        if (indices.empty()) continue;
        const std::string label = mName + " edges of mesh " + std::to_string(index);
        edges.indices.emplace(indices.data(), indices.size() * sizeof(std::uint32_t), label);
        edges.vertexArray.emplace(label);
        edges.vertexArray->setVec3Attribute(GpuScene::kPositionLocation, meshes[index].positions);
        edges.vertexArray->setIndexBuffer(*edges.indices);
        meshes[index].materialAttributes.attachTo(*edges.vertexArray);
        edges.indexCount = GLsizei(indices.size());
    }
}

void OutlinePass::execute(GlPassContext& gl) {
    GlFramebuffer framebuffer(mName);
    mSkippedEyeInside = !beginLineMask(gl, framebuffer, mDepth, mScene, mFrame.camera.eye);
    if (mSkippedEyeInside) return;
    const int width = gl.widthOf("lines");
    const int height = gl.heightOf("lines");

    const glm::mat4 viewFromModel = mFrame.viewFromModel();
    const glm::mat4 clipFromView = mFrame.clipFromView();
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE); // the depth draw takes every face; the line draw chooses edges in its geometry shader

    // 1. The model's depth: every face (open meshes show their insides through holes), no colour.
    glDepthFunc(kDepthNearer);
    drawModelDepth(*mDepthProgram, mScene, viewFromModel, clipFromView);

    // 2. Contour and border edges as quads widthPixels wide on their outer side. Nearer or equal: a silhouette edge
    // lies exactly on the model's depth.
    glDepthFunc(kDepthNearerOrEqual);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_FALSE);
    mLineProgram->use();
    glUniformMatrix4fv(mLineProgram->uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix4fv(mLineProgram->uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    glUniform2f(mLineProgram->uniform("viewportSize"), float(width), float(height));
    glUniform1f(mLineProgram->uniform("widthPixels"), bandWidthPixels(mWidthPixels, height));
    // A cut-out's edges are cut with it (the ends carry the surface's texture coordinates to line_mask.frag).
    const bool transparency = mScene.hasTransparency();
    for (std::size_t index = 0; index < mEdges.size(); ++index) {
        if (mEdges[index].indexCount == 0) continue;
        if (transparency) mScene.bindMaterial(*mLineProgram, index, MaterialUse::Coverage);
        mScene.materials().bindWidthMap(*mLineProgram, index, mWidthMap);
        mEdges[index].vertexArray->bind();
        glDrawElements(GL_LINES_ADJACENCY, mEdges[index].indexCount, GL_UNSIGNED_INT, nullptr);
    }

    glDepthMask(GL_TRUE);
    glDepthFunc(kDepthNearer);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
