#include "passes/orientation/SceneOrientation.h"

#include "graph/Milliseconds.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace inkgraph {

namespace {

using Clock = std::chrono::steady_clock;

/** GL refuses zero-sized buffer storage (GL_INVALID_VALUE), and an empty set is normal (no back faces seen from
 *  inside, no front faces when everything faces away). An empty list therefore gets one zeroed element as a
 *  placeholder; its draw count stays 0, so nothing reads it. */
template <typename Element>
GlBuffer uploadList(const std::vector<Element>& elements, const std::string& label) {
    if (elements.empty()) {
        const Element placeholder{};
        return GlBuffer(&placeholder, sizeof(Element), label + " (empty)");
    }
    return GlBuffer(elements.data(), elements.size() * sizeof(Element), label);
}

GLsizei indexCountOf(const std::vector<glm::uvec3>& triangles, const std::string& meshName) {
    if (triangles.size() > std::size_t(std::numeric_limits<GLsizei>::max()) / 3) {
        throw std::length_error("SceneOrientation::sets(): mesh '" + meshName +
                                "' has too many triangles for one draw");
    }
    return GLsizei(triangles.size() * 3);
}

/** The fields every method reports the same way. */
OrientationReport baseReport(const Scene& scene, const OrientationSettings& settings, const ViewVectorChoice& view) {
    OrientationReport report;
    report.method = faceOrientationMethodName(settings.method);
    report.viewVector = viewVectorModeName(view.constant ? ViewVectorMode::Constant : ViewVectorMode::Exact);
    report.fellBack = view.fellBack;
    report.fallBackReason = view.reason;
    report.sinAlpha = view.sinAlpha;
    report.triangles = scene.triangleCount();
    report.vertices = scene.vertexCount();
    return report;
}

} // namespace

void checkOrientationSettings(const char* function, const OrientationSettings& settings) {
    if (settings.frontRule < 1 || settings.frontRule > 3) {
        throw std::invalid_argument(std::string(function) + ": the front rule must be 1, 2 or 3, got " +
                                    std::to_string(settings.frontRule));
    }
    if (!(settings.shininess >= 0.0)) {
        throw std::invalid_argument(std::string(function) + ": the shininess must be >= 0, got " +
                                    std::to_string(settings.shininess));
    }
}

SceneOrientation::SceneOrientation(const Scene& scene, GpuScene& gpuScene, const FrameParams& frame,
                                   OrientationSettings settings)
    : mScene(scene), mGpuScene(gpuScene), mFrame(frame), mSettings(settings) {
    checkOrientationSettings("SceneOrientation()", mSettings);
}

nlohmann::ordered_json SceneOrientation::describe() {
    const OrientationReport& report = this->report();
    return {{"method", report.method},
            {"view_vector", report.viewVector},
            {"fell_back_to_exact", report.fellBack},
            {"fall_back_reason", report.fallBackReason},
            {"sin_alpha", report.sinAlpha},
            {"beta_max_degrees", report.betaMaxDegrees},
            {"cutoff", report.cutoff},
            {"triangles", report.triangles},
            {"vertices", report.vertices},
            {"front_triangles", report.frontTriangles},
            {"front_vertices", report.frontVertices},
            {"front_triangle_share", report.triangles ? double(report.frontTriangles) / double(report.triangles) : 0.0},
            {"front_vertex_share", report.vertices ? double(report.frontVertices) / double(report.vertices) : 0.0},
            {"exact_front_triangles", report.exactFrontTriangles},
            {"missed_triangles", report.missedTriangles},
            {"derive_ms", report.deriveMilliseconds},
            {"mark_ms", report.markMilliseconds},
            {"upload_ms", report.uploadMilliseconds}};
}

const std::vector<SceneOrientation::MeshSets>& SceneOrientation::sets() {
    if (!usesCpuMarking()) {
        throw std::logic_error("SceneOrientation::sets(): the 'standard' method marks nothing on the CPU; the GPU "
                               "culls");
    }
    if (!mComputed) {
        compute();
    }
    return mSets;
}

ViewVectorChoice SceneOrientation::viewVector() {
    // The sphere depends on the mesh alone: computed once; the choice depends on the eye, so per frame.
    if (!mSphere) mSphere = computeBoundingSphere(mScene);
    return chooseViewVector(mSettings.viewVector, mFrame.camera.eye, mSphere->center, mSphere->radius);
}

void SceneOrientation::invalidate() {
    mSets.clear();
    mOrientations.clear();
    mReport.reset();
    mComputed = false;
    mCounted = false;
}

const OrientationReport& SceneOrientation::report() {
    if (usesCpuMarking()) {
        if (!mComputed) {
            compute();
        }
        if (!mCounted) {
            for (std::size_t i = 0; i < mScene.meshes.size(); ++i) {
                mReport->exactFrontTriangles += countExactFrontTriangles(mScene.meshes[i], mFrame.camera.eye);
                mReport->missedTriangles +=
                    countMissedTriangles(mScene.meshes[i], mFrame.camera.eye, mOrientations[i].frontTriangles);
            }
            mCounted = true;
        }
        return *mReport;
    }
    if (!mReport) {
        // Standard: the GPU culls, so the share shown in the stats is counted here, and only when asked for.
        OrientationReport report = baseReport(mScene, mSettings, viewVector());
        for (const Mesh& mesh : mScene.meshes) {
            report.exactFrontTriangles += countExactFrontTriangles(mesh, mFrame.camera.eye);
            report.frontVertices += countExactFrontVertices(mesh, mFrame.camera.eye);
        }
        report.frontTriangles = report.exactFrontTriangles;
        mReport = std::move(report);
    }
    return *mReport;
}

void SceneOrientation::compute() {
    // GpuScene's own upload happens here, outside this class's timers.
    const std::vector<GpuScene::DrawMesh>& drawMeshes = mGpuScene.meshes();
    if (drawMeshes.size() != mScene.meshes.size()) {
        throw std::logic_error("SceneOrientation::sets(): GpuScene holds " + std::to_string(drawMeshes.size()) +
                               " meshes for a scene of " + std::to_string(mScene.meshes.size()));
    }
    const ViewVectorChoice view = viewVector();
    OrientationReport report = baseReport(mScene, mSettings, view);

    OrientationRequest request;
    request.method = mSettings.method;
    request.frontRule = mSettings.frontRule;
    request.view = view;
    request.eye = mFrame.camera.eye;
    request.towardLight = mFrame.towardLightWorld;
    request.shininess = mSettings.shininess;
    request.countMissed = false; // counted below, outside the marking time

    std::vector<MeshSets> sets;
    sets.reserve(mScene.meshes.size());
    mOrientations.resize(mScene.meshes.size());
    const bool withAdjacency = mSettings.method == FaceOrientationMethod::DuringVertices;
    if (mDerived.empty()) {
        const Clock::time_point deriveStart = Clock::now();
        for (const Mesh& mesh : mScene.meshes) mDerived.push_back(deriveOrientationData(mesh, withAdjacency));
        mDeriveMilliseconds = millisecondsSince(deriveStart);
    }
    report.deriveMilliseconds = mDeriveMilliseconds;
    double betaMaxRadians = 0.0;
    for (std::size_t i = 0; i < mScene.meshes.size(); ++i) {
        const Mesh& mesh = mScene.meshes[i];
        const GpuScene::DrawMesh& drawMesh = drawMeshes[i];

        const Clock::time_point markStart = Clock::now();
        MeshOrientation& orientation = mOrientations[i];
        orientMesh(mesh, mDerived[i], request, orientation);
        report.markMilliseconds += millisecondsSince(markStart);

        report.frontTriangles += orientation.frontTriangles.size();
        report.frontVertices += orientation.frontVertexCount;
        report.cutoff = i == 0 ? orientation.cutoff : std::max(report.cutoff, orientation.cutoff);
        betaMaxRadians = std::max(betaMaxRadians, orientation.betaMaxRadians);

        const Clock::time_point uploadStart = Clock::now();
        const std::string label = "mesh '" + mesh.name + "' orientation";
        MeshSets meshSets{uploadList(orientation.shadeCoords, label + " shade coords"),
                          uploadList(orientation.frontTriangles, label + " front indices"),
                          uploadList(orientation.backTriangles, label + " back indices"),
                          GlVertexArray(label + " front"),
                          GlVertexArray(label + " back"),
                          indexCountOf(orientation.frontTriangles, mesh.name),
                          indexCountOf(orientation.backTriangles, mesh.name)};
        meshSets.frontArray.setVec3Attribute(GpuScene::kPositionLocation, drawMesh.positions);
        meshSets.frontArray.setVec3Attribute(GpuScene::kNormalLocation, drawMesh.normals);
        meshSets.frontArray.setVec2Attribute(kShadeCoordLocation, meshSets.shadeCoords);
        meshSets.frontArray.setIndexBuffer(meshSets.frontIndices);
        drawMesh.materialAttributes.attachTo(meshSets.frontArray);
        meshSets.backArray.setVec3Attribute(GpuScene::kPositionLocation, drawMesh.positions);
        meshSets.backArray.setVec3Attribute(GpuScene::kNormalLocation, drawMesh.normals);
        meshSets.backArray.setIndexBuffer(meshSets.backIndices);
        drawMesh.materialAttributes.attachTo(meshSets.backArray);
        sets.push_back(std::move(meshSets));
        report.uploadMilliseconds += millisecondsSince(uploadStart);
    }
    report.betaMaxDegrees = glm::degrees(betaMaxRadians);

    mSets = std::move(sets);
    mReport = std::move(report);
    mComputed = true;
    mCounted = false;
}

} // namespace inkgraph
