#include "passes/edges/MeshEdgesPass.h"

#include "gl/GraphExecutor.h"
#include "passes/LineMaskTarget.h"
#include "scene/MeshLabels.h"
#include "scene/mesh/EdgeAdjacency.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace inkgraph {
namespace {

constexpr const char* kHiddenPrefix = "hidden-";

/** The edge kind an output draws: "crease" for "crease" and "hidden-crease". */
std::string kindOf(const std::string& field) {
    return field.rfind(kHiddenPrefix, 0) == 0 ? field.substr(std::string(kHiddenPrefix).size()) : field;
}

bool isHidden(const std::string& field) { return field.rfind(kHiddenPrefix, 0) == 0; }

/** Whether `field`'s edges are drawn: its skeleton or its "-points" output is live. --request may ask for the points
 *  alone, without the line type; they were then never written (an internal error). */
bool drawsField(const GlPassContext& gl, const std::string& field) {
    return gl.isLive(field) || gl.isLive(field + MeshEdgesPass::kPointsSuffix);
}

} // namespace

MeshEdgesPass::MeshEdgesPass(std::string name, ShaderLibrary& shaders, GpuScene& scene, const FrameParams& frame,
                             MeshEdgesSettings settings)
    : mName(std::move(name)), mShaders(shaders), mScene(scene), mFrame(frame), mSettings(settings),
      mDepth(mName + " model depth") {
    if (!std::isfinite(mSettings.creaseAngleDegrees) || mSettings.creaseAngleDegrees < 0.0f ||
        mSettings.creaseAngleDegrees > 180.0f)
        throw std::invalid_argument("MeshEdgesPass(): pass '" + mName +
                                    "': 'creaseAngleDegrees' must be in [0, 180], got " +
                                    std::to_string(mSettings.creaseAngleDegrees));
    if (!std::isfinite(mSettings.creaseMinLength) || mSettings.creaseMinLength < 0.0f)
        throw std::invalid_argument("MeshEdgesPass(): pass '" + mName +
                                    "': 'creaseMinLength' must be finite and >= 0, got " +
                                    std::to_string(mSettings.creaseMinLength));
    if (mSettings.supersample < 1)
        throw std::invalid_argument("MeshEdgesPass(): pass '" + mName + "': 'supersample' must be >= 1, got " +
                                    std::to_string(mSettings.supersample));
}

void MeshEdgesPass::declare(PassBuilder& builder) const {
    builder.import(SceneImport::kMeshes);
    builder.import(SceneImport::kEdgeAdjacency);
    for (const char* field : kFields)
        builder.write(field, {Format::R8, mSettings.supersample}, Need::Optional,
                      {"", Appearance::Lines,
                       std::string("the one-pixel skeleton of the mesh's ") +
                           (isHidden(field) ? "hidden " + kindOf(field) : std::string(field)) +
                           " edges, at the --supersample size"});
    for (const char* field : kFields)
        builder.write(std::string(field) + kPointsSuffix, {Format::RGBA32F, mSettings.supersample}, Need::Optional,
                      {"", Appearance::Data,
                       std::string("--strokes: on each line pixel of ") + field +
                           ", the fragment's view position along its edge and the edge's triangle (global index + "
                           "1)"});
}

void MeshEdgesPass::describe(nlohmann::ordered_json& report) const {
    nlohmann::ordered_json drawn = nlohmann::ordered_json::object();
    if (mEdgesDrawn.crease) drawn["crease"] = *mEdgesDrawn.crease;
    if (mEdgesDrawn.border) drawn["border"] = *mEdgesDrawn.border;
    if (mEdgesDrawn.silhouette) drawn["silhouette"] = *mEdgesDrawn.silhouette;
    if (mEdgesDrawn.hiddenCrease) drawn["hidden-crease"] = *mEdgesDrawn.hiddenCrease;
    if (mEdgesDrawn.hiddenBorder) drawn["hidden-border"] = *mEdgesDrawn.hiddenBorder;
    if (mEdgesDrawn.hiddenSilhouette) drawn["hidden-silhouette"] = *mEdgesDrawn.hiddenSilhouette;
    report["edges_drawn"] = drawn;
    if (mCreaseCounts)
        report["crease_edges"] = {{"by_angle", mCreaseCounts->edgesByAngle},
                                  {"kept", mCreaseCounts->edgesKept},
                                  {"chains", mCreaseCounts->chains},
                                  {"chains_kept", mCreaseCounts->chainsKept}};
}

MeshEdgesPass::EdgeLines MeshEdgesPass::uploadEdgeLines(const std::string& output, std::size_t meshIndex,
                                                        const std::vector<std::uint32_t>& indices) const {
    EdgeLines lines;
    if (indices.empty()) return lines;
    const std::string label = mName + " " + output + " edges of mesh " + std::to_string(meshIndex);
    lines.indices.emplace(indices.data(), indices.size() * sizeof(std::uint32_t), label);
    lines.vertexArray.emplace(label);
    lines.vertexArray->setVec3Attribute(GpuScene::kPositionLocation, mScene.meshes()[meshIndex].positions);
    lines.vertexArray->setIndexBuffer(*lines.indices);
    mScene.meshes()[meshIndex].materialAttributes.attachTo(*lines.vertexArray);
    lines.indexCount = GLsizei(indices.size());
    if (mPointsWanted) {
        const std::vector<float> triangles = edgeTriangles(meshIndex, indices);
        lines.triangles.emplace(triangles.data(), triangles.size() * sizeof(float), label + " triangles");
    }
    return lines;
}

std::vector<float> MeshEdgesPass::edgeTriangles(std::size_t meshIndex,
                                                const std::vector<std::uint32_t>& indices) const {
    const Scene& scene = mScene.scene();
    const TriangleNumbering numbering(scene);
    // The edges' vertex pairs, each to the first triangle (in the mesh's order) that has it.
    std::unordered_map<std::uint64_t, std::uint32_t> wanted;
    const auto key = [](std::uint32_t a, std::uint32_t b) {
        return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
    };
    for (std::size_t edge = 0; edge + 1 < indices.size(); edge += 2)
        wanted.emplace(key(indices[edge], indices[edge + 1]), 0u);
    const std::vector<glm::uvec3>& triangles = scene.meshes[meshIndex].triangles;
    for (std::size_t triangle = triangles.size(); triangle-- > 0;)
        for (int corner = 0; corner < 3; ++corner) {
            const auto found = wanted.find(key(triangles[triangle][corner], triangles[triangle][(corner + 1) % 3]));
            if (found != wanted.end()) found->second = std::uint32_t(numbering.global(meshIndex, triangle) + 1);
        }
    std::vector<float> perEdge;
    for (std::size_t edge = 0; edge + 1 < indices.size(); edge += 2)
        perEdge.push_back(float(wanted[key(indices[edge], indices[edge + 1])]));
    return perEdge;
}

std::size_t MeshEdgesPass::drawEdgeLines(const GlProgram& program, const std::vector<EdgeLines>& lines) {
    std::size_t edges = 0;
    const bool transparency = mScene.hasTransparency();
    for (std::size_t index = 0; index < lines.size(); ++index) {
        const EdgeLines& mesh = lines[index];
        if (mesh.indexCount == 0) continue;
        // An edge through what a material cuts out is not drawn (the lines follow the cut-out surface).
        if (transparency) mScene.bindMaterial(program, index, MaterialUse::Coverage);
        mesh.vertexArray->bind();
        // The edge's triangle for the "-points" output: gl_PrimitiveID counts points, two per edge, and lines.
        // Without a "-points" output the shader reads nothing from it, but a buffer is bound all the same.
        if (!mesh.triangles && !mNoTriangles) {
            const float none = 0.0f;
            mNoTriangles.emplace(&none, sizeof none, mName + " no edge triangles");
        }
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, mesh.triangles ? mesh.triangles->id() : mNoTriangles->id());
        // GL's diamond-exit rule leaves out a line's last pixel, so two edges of a chain that meet head to head
        // would leave a one-pixel gap; the end points, drawn as 1-pixel points, close it. Drawn first, so where a
        // line passes over an end point's pixel its point (nearer the pixel centre's ray) is the one kept.
        glUniform1i(program.uniform("primitivesPerEdge"), 2);
        glDrawElements(GL_POINTS, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        glUniform1i(program.uniform("primitivesPerEdge"), 1);
        glDrawElements(GL_LINES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
        edges += std::size_t(mesh.indexCount) / 2;
    }
    return edges;
}

void MeshEdgesPass::prepare(GlPassContext& context) {
    if (!mDepthProgram)
        mDepthProgram = std::make_unique<GlProgram>(mShaders.build({mName + " model depth",
                                                                    "edges/edges.vert",
                                                                    "common/line_mask.frag",
                                                                    materialAlphaDefines(mScene),
                                                                    {"common/material.glsl"}}));
    if (!mLineProgram)
        mLineProgram = std::make_unique<GlProgram>(mShaders.build({mName + " lines",
                                                                   "edges/edges.vert",
                                                                   "edges/edges.frag",
                                                                   materialAlphaDefines(mScene),
                                                                   {"common/material.glsl"}}));
    // A kind's edges are chosen when its visible or its hidden output is live.
    const auto kindLive = [&](const std::string& kind) {
        return drawsField(context, kind) || drawsField(context, kHiddenPrefix + kind);
    };
    const bool anyHidden = drawsField(context, "hidden-silhouette") || drawsField(context, "hidden-crease") ||
                           drawsField(context, "hidden-border");
    if (anyHidden && !mHiddenProgram) {
        std::vector<std::string> defines = materialAlphaDefines(mScene);
        defines.push_back("HIDDEN 1");
        mHiddenProgram = std::make_unique<GlProgram>(mShaders.build(
            {mName + " hidden lines", "edges/edges.vert", "edges/edges.frag", defines, {"common/material.glsl"}}));
    }
    const std::size_t meshCount = mScene.meshes().size();
    mPointsWanted = false;
    for (const char* field : kFields)
        mPointsWanted = mPointsWanted || context.isLive(std::string(field) + kPointsSuffix);
    const bool anyLive = kindLive("silhouette") || kindLive("crease") || kindLive("border");
    if (!anyLive) return;
    // Edge lists uploaded by an earlier run without the edges' triangles are uploaded again with them.
    const auto lacksTriangles = [](const std::vector<EdgeLines>& meshes) {
        return std::any_of(meshes.begin(), meshes.end(),
                           [](const EdgeLines& lines) { return lines.indexCount > 0 && !lines.triangles; });
    };
    if (mPointsWanted && lacksTriangles(mCreaseLines)) mCreaseLines.clear();
    if (mPointsWanted && lacksTriangles(mBorderLines)) mBorderLines.clear();
    for (std::size_t mesh = 0; mesh < meshCount; ++mesh) mScene.edgeAdjacency(mesh);

    // Creases and borders do not depend on the view: chosen and uploaded once, outside the timed execute().
    const double creaseAngle = double(mSettings.creaseAngleDegrees) * glm::pi<double>() / 180.0;
    if (kindLive("crease") && mCreaseLines.empty()) {
        CreaseCounts counts;
        for (std::size_t mesh = 0; mesh < meshCount; ++mesh) {
            const CreaseSelection selection =
                selectProminentCreaseEdges(mScene.edgeAdjacency(mesh), mScene.scene().meshes[mesh].positions,
                                           creaseAngle, double(mSettings.creaseMinLength));
            counts.edgesByAngle += selection.edgesByAngle;
            counts.edgesKept += selection.edgesKept;
            counts.chains += selection.chains;
            counts.chainsKept += selection.chainsKept;
            mCreaseLines.push_back(uploadEdgeLines("crease", mesh, selection.indices));
        }
        mCreaseCounts = counts;
    }
    if (kindLive("border") && mBorderLines.empty())
        for (std::size_t mesh = 0; mesh < meshCount; ++mesh)
            mBorderLines.push_back(uploadEdgeLines("border", mesh, selectBorderEdges(mScene.edgeAdjacency(mesh))));
}

void MeshEdgesPass::execute(GlPassContext& gl) {
    mEdgesDrawn = {};
    std::vector<const char*> live;
    for (const char* field : kFields)
        if (drawsField(gl, field)) live.push_back(field);
    if (live.empty()) return; // only reachable outside a compiled plan: the compiler culls a pass with no live output

    // Every output has the same scale, so any gives the size.
    const std::string sized = gl.isLive(live.front()) ? live.front() : live.front() + std::string(kPointsSuffix);
    const int width = gl.widthOf(sized);
    const int height = gl.heightOf(sized);
    const glm::mat4 viewFromModel = mFrame.viewFromModel();
    const glm::mat4 clipFromView = mFrame.clipFromView();
    const std::vector<GpuScene::DrawMesh>& meshes = mScene.meshes();
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);

    // The silhouette edges for this eye, chosen before anything is drawn: when no live output has an edge (a smooth
    // scan's creases all shorter than the minimum length, say), the model's depth, a draw of every face, is not
    // needed, and the outputs are only cleared.
    if (drawsField(gl, "silhouette") || drawsField(gl, "hidden-silhouette")) {
        // The eye in the meshes' frame: the scene's local frame (Scene::origin), where Camera::eye lives too
        // (GpuScene subtracts worldOrigin only for the GPU).
        const glm::dvec3 eye = mFrame.camera.eye;
        mSilhouetteLines.clear();
        for (std::size_t mesh = 0; mesh < meshes.size(); ++mesh)
            mSilhouetteLines.push_back(
                uploadEdgeLines("silhouette", mesh, selectSilhouetteEdges(mScene.edgeAdjacency(mesh), eye)));
    }
    const auto linesOf = [&](const std::string& field) -> const std::vector<EdgeLines>& {
        const std::string kind = kindOf(field);
        return kind == "silhouette" ? mSilhouetteLines : kind == "crease" ? mCreaseLines : mBorderLines;
    };
    bool anyEdges = false;
    for (const char* field : live)
        for (const EdgeLines& lines : linesOf(field)) anyEdges = anyEdges || lines.indexCount > 0;

    // 1. The model's depth, once for every output: every face (open meshes and an eye inside show inner faces),
    // pushed back by about a pixel of its own depth slope so the edges lying on it pass.
    if (anyEdges) {
        GlFramebuffer depthTarget(mName + " model depth");
        depthTarget.attachDepth(mDepth.sized(width, height));
        depthTarget.finish({});
        depthTarget.bind();
        clearColorAndDepth(0);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(kDepthNearer);
        {
            // The depth fill one pixel of depth farther (gl/GlObjects.h): a line fragment, whose centre may sit half
            // a pixel off its edge, is not hidden by the face the edge lies on, valleys included, while a surface
            // more than about a pixel's worth of depth in front still hides it.
            const OnePixelFartherFill farther;
            drawModelDepth(*mDepthProgram, mScene, viewFromModel, clipFromView);
        }
        glDisable(GL_DEPTH_TEST);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    }

    // 2. Each output's edges into that output alone, and its "-points" output beside it, one framebuffer per output:
    // all of them at once would need up to twelve colour attachments, and GL guarantees eight. No depth attachment:
    // the fragment shader compares with the depth above, sampled (a texture cannot be sampled while attached and
    // written).
    if (anyEdges) glBindTextureUnit(0, mDepth.sized(width, height).id());
    glLineWidth(1.0f);
    glPointSize(1.0f);
    for (std::size_t slot = 0; slot < live.size(); ++slot) {
        const std::string field = live[slot];
        const std::string points = field + kPointsSuffix;
        const bool writesPoints = gl.isLive(points);
        GlFramebuffer lineTarget(mName + " " + field);
        // Points asked for without their skeleton: the shader writes both, the skeleton into a texture of its own.
        std::optional<GlTexture> unrequested;
        if (!gl.isLive(field)) unrequested.emplace(Format::R8, width, height, mName + " " + field + " (not requested)");
        lineTarget.attachColor(0, unrequested ? *unrequested : gl.outputTexture(field));
        if (writesPoints) lineTarget.attachColor(1, gl.outputTexture(points));
        lineTarget.finish(writesPoints ? std::vector<int>{0, 1} : std::vector<int>{0});
        lineTarget.bind();
        clearColorAndDepth(writesPoints ? 2 : 1);
        const GlProgram& program = isHidden(field) ? *mHiddenProgram : *mLineProgram;
        program.use();
        glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
        glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
        glUniform1i(program.uniform("writePoints"), writesPoints ? 1 : 0);
        const std::size_t drawn = drawEdgeLines(program, linesOf(field));
        (field == "silhouette"          ? mEdgesDrawn.silhouette
         : field == "crease"            ? mEdgesDrawn.crease
         : field == "border"            ? mEdgesDrawn.border
         : field == "hidden-silhouette" ? mEdgesDrawn.hiddenSilhouette
         : field == "hidden-crease"     ? mEdgesDrawn.hiddenCrease
                                        : mEdgesDrawn.hiddenBorder) = drawn;
    }

    glBindTextureUnit(0, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace inkgraph
