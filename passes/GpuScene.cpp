#include "passes/GpuScene.h"

#include "passes/orientation/SceneOrientation.h"
#include "scene/MaterialIds.h"
#include "scene/MeshLabels.h"
#include "scene/MeshNumbering.h"
#include "scene/ObjectIds.h"
#include "scene/mesh/MeshOps.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace inkgraph {

GpuScene::GpuScene(const Scene& scene, glm::dvec3 worldOrigin, std::shared_ptr<SceneDerivedData> derived)
    : mScene(scene), mWorldOrigin(worldOrigin),
      mDerived(derived ? std::move(derived) : std::make_shared<SceneDerivedData>(scene)),
      mMaterials(scene, scene.report.inputFiles.empty() ? std::string("scene") : scene.report.inputFiles.front()) {
    if (&mDerived->scene() != &scene)
        throw std::invalid_argument("GpuScene::GpuScene(): the derived data given is another scene's");
}

bool GpuScene::hasTransparency() const {
    return std::ranges::any_of(mScene.meshes,
                               [](const Mesh& mesh) { return mesh.material.alphaMode != AlphaMode::Opaque; });
}

std::vector<std::size_t> GpuScene::drawOrder(const glm::mat4& viewFromModel) {
    std::vector<std::size_t> order;
    std::vector<std::pair<double, std::size_t>> blended; // (view-space z, mesh): larger z is nearer the eye
    for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
        const Mesh& mesh = mScene.meshes[index];
        if (mesh.material.alphaMode != AlphaMode::Blend) {
            order.push_back(index);
            continue;
        }
        if (mBlendCentres.empty()) mBlendCentres.resize(mScene.meshes.size());
        if (!mBlendCentres[index]) mBlendCentres[index] = computeBoundingBox(mesh.positions).center() - mWorldOrigin;
        const glm::dvec3 centre = *mBlendCentres[index];
        const glm::dvec4 view = glm::dmat4(viewFromModel) * glm::dvec4(centre, 1.0);
        blended.emplace_back(view.z, index);
    }
    // Farthest (most negative z) first; ties keep scene order.
    std::ranges::stable_sort(blended, {}, [](const auto& entry) { return entry.first; });
    for (const auto& entry : blended) order.push_back(entry.second);
    return order;
}

// Out of line: SceneOrientation is complete only here.
GpuScene::~GpuScene() = default;

void GpuScene::setOrientation(const FrameParams& frame, OrientationSettings settings) {
    checkOrientationSettings("GpuScene::setOrientation()", settings);
    mOrientationFrame = &frame;
    mOrientationSettings = settings;
    mOrientation.reset();
}

SceneOrientation* GpuScene::orientation() {
    if (mOrientationFrame == nullptr) return nullptr;
    if (!mOrientation)
        mOrientation = std::make_unique<SceneOrientation>(mScene, *this, *mOrientationFrame, mOrientationSettings);
    return mOrientation.get();
}

SceneOrientation* GpuScene::cpuOrientation() {
    if (mOrientationFrame == nullptr || mOrientationSettings.method == FaceOrientationMethod::Standard) return nullptr;
    return orientation();
}

const std::vector<GpuScene::DrawMesh>& GpuScene::meshes() {
    if (mUploaded) return mMeshes;
    const std::vector<std::uint32_t> materials = materialIds(mScene);
    const std::vector<std::uint32_t> objects = sceneObjects(mScene).ofMesh;
    const MeshNumbering numbering(mScene);
    mMeshes.reserve(mScene.meshes.size());
    for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
        const Mesh& mesh = mScene.meshes[index];
        const std::size_t number = numbering.numberOf(index);
        std::vector<glm::vec3> relative(mesh.positions.size());
        for (std::size_t i = 0; i < relative.size(); ++i)
            relative[i] = glm::vec3(glm::dvec3(mesh.positions[i]) - mWorldOrigin);
        const std::string label = "mesh '" + mesh.name + "'";
        DrawMesh draw{GlBuffer(relative.data(), relative.size() * sizeof(glm::vec3), label + " positions"),
                      GlBuffer(mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3), label + " normals"),
                      GlBuffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3), label + " indices"),
                      GlVertexArray(label),
                      static_cast<GLsizei>(mesh.triangles.size() * 3),
                      mesh.material.baseColorFactor,
                      materials[number],
                      objects[number],
                      std::uint32_t(number),
                      {},
                      &mesh.material,
                      mesh.drawsBackFaces()};
        draw.materialAttributes = uploadMaterialAttributes(mesh, label);
        draw.materialAttributes.attachTo(draw.vertexArray);
        draw.vertexArray.setVec3Attribute(kPositionLocation, draw.positions);
        draw.vertexArray.setVec3Attribute(kNormalLocation, draw.normals);
        draw.vertexArray.setIndexBuffer(draw.indices);
        mMeshes.push_back(std::move(draw));
    }
    mUploaded = true;
    return mMeshes;
}

const GpuScene::TriangleIdMap& GpuScene::triangleIdMap() {
    if (mTriangleIdMap) return *mTriangleIdMap;
    const TriangleNumbering numbering(mScene);
    std::vector<std::uint32_t> firstTriangle, fileTrianglesAt, fileTriangles;
    for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
        const Mesh& mesh = mScene.meshes[index];
        firstTriangle.push_back(std::uint32_t(numbering.firstOfMesh(index)));
        if (mesh.fileTriangles.empty() && mesh.cornersSwapped.empty()) {
            fileTrianglesAt.push_back(TriangleIdMap::kAsDrawn);
            continue;
        }
        if (mesh.numberedTriangleCount() >= TriangleIdMap::kCornersSwapped)
            throw std::invalid_argument("GpuScene::triangleIdMap(): mesh '" + mesh.name + "' has " +
                                        std::to_string(mesh.numberedTriangleCount()) +
                                        " triangles, more than its ids can hold");
        fileTrianglesAt.push_back(std::uint32_t(fileTriangles.size()));
        for (std::size_t triangle = 0; triangle < mesh.triangleCount(); ++triangle)
            fileTriangles.push_back(
                std::uint32_t(mesh.fileTriangleOf(triangle)) |
                (!mesh.cornersSwapped.empty() && mesh.cornersSwapped[triangle] ? TriangleIdMap::kCornersSwapped : 0u));
    }
    // A shader's storage block is bound to a buffer even where no mesh reads it.
    if (fileTriangles.empty()) fileTriangles.push_back(0);
    mTriangleIdMap.emplace(TriangleIdMap{
        std::move(firstTriangle), std::move(fileTrianglesAt),
        GlBuffer(fileTriangles.data(), fileTriangles.size() * sizeof(std::uint32_t), "file triangle indices")});
    return *mTriangleIdMap;
}

const GlBuffer& GpuScene::hullNormals(std::size_t meshIndex) {
    mDerived->requireMeshIndex("GpuScene::hullNormals()", meshIndex);
    if (mHullNormals.empty()) {
        const std::vector<DrawMesh>& drawMeshes = meshes();
        std::vector<GlBuffer> own;
        own.reserve(mScene.meshes.size()); // never reallocated below: the pointers into it stay valid
        std::vector<const GlBuffer*> buffers;
        for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
            const std::vector<glm::vec3>* normals = mDerived->hullNormals(index);
            if (normals == nullptr) { // the mesh's own normals are the hull's
                buffers.push_back(&drawMeshes[index].normals);
                continue;
            }
            own.emplace_back(normals->data(), normals->size() * sizeof(glm::vec3),
                             "mesh '" + mScene.meshes[index].name + "' hull normals");
            buffers.push_back(&own.back());
        }
        mOwnHullNormals = std::move(own); // moving the vector keeps its elements where they are
        mHullNormals = std::move(buffers);
    }
    return *mHullNormals[meshIndex];
}

const std::vector<GlVertexArray>& GpuScene::hullArrays() {
    if (mHullArrays.empty()) {
        const std::vector<DrawMesh>& drawMeshes = meshes();
        std::vector<GlVertexArray> arrays;
        arrays.reserve(drawMeshes.size());
        std::vector<GLsizei> counts;
        std::vector<GlBuffer> ownIndices;
        ownIndices.reserve(drawMeshes.size()); // never reallocated below: the arrays refer to its buffers
        for (std::size_t index = 0; index < drawMeshes.size(); ++index) {
            GlVertexArray array("mesh '" + mScene.meshes[index].name + "' hull");
            array.setVec3Attribute(kPositionLocation, drawMeshes[index].positions);
            array.setVec3Attribute(kNormalLocation, hullNormals(index));
            if (const std::vector<glm::uvec3>* triangles = mDerived->hullTriangles(index)) {
                ownIndices.emplace_back(triangles->data(), triangles->size() * sizeof(glm::uvec3),
                                        "mesh '" + mScene.meshes[index].name + "' hull indices");
                array.setIndexBuffer(ownIndices.back());
                counts.push_back(GLsizei(triangles->size() * 3));
            } else {
                array.setIndexBuffer(drawMeshes[index].indices);
                counts.push_back(drawMeshes[index].indexCount);
            }
            drawMeshes[index].materialAttributes.attachTo(array);
            arrays.push_back(std::move(array));
        }
        mOwnHullIndices = std::move(ownIndices); // moving the vector keeps its elements where they are
        mHullIndexCounts = std::move(counts);
        mHullArrays = std::move(arrays);
    }
    return mHullArrays;
}

GLsizei GpuScene::hullIndexCount(std::size_t meshIndex) {
    mDerived->requireMeshIndex("GpuScene::hullIndexCount()", meshIndex);
    hullArrays();
    return mHullIndexCounts[meshIndex];
}

bool GpuScene::containsPoint(glm::dvec3 worldPoint) {
    if (mContainmentPoint == worldPoint) return mContainsPoint;
    mContainsPoint = false;
    for (const Mesh& mesh : mScene.meshes) {
        if (isPointInsideMesh(mesh, worldPoint)) {
            mContainsPoint = true;
            break;
        }
    }
    mContainmentPoint = worldPoint;
    return mContainsPoint;
}

bool GpuScene::inflatedHullContainsPoint(glm::dvec3 worldPoint, float objectWidth, bool weldedNormals) {
    for (std::size_t index = 0; index < mScene.meshes.size(); ++index) {
        const Mesh& mesh = mScene.meshes[index];
        const std::vector<glm::vec3>* welded = weldedNormals ? mDerived->hullNormals(index) : nullptr;
        const std::vector<glm::vec3>& normals = welded != nullptr ? *welded : mesh.normals;
        if (normals.size() != mesh.positions.size()) continue;
        Mesh hull;
        hull.triangles = mesh.triangles;
        hull.positions.reserve(mesh.positions.size());
        for (std::size_t vertex = 0; vertex < mesh.positions.size(); ++vertex)
            hull.positions.push_back(mesh.positions[vertex] + objectWidth * normals[vertex]);
        if (isPointInsideMesh(hull, worldPoint)) return true;
    }
    return false;
}

std::size_t SceneImport::bytesPerTriangle(std::string_view name) {
    // Measured as the peak resident set of `--size 256x256 --lines T` over `--lines none` on a 1.3-million-triangle
    // mesh of 650,000 vertices (the armadillo subdivided), llvmpipe, one thread: docs/batch.md has the table. Each is
    // rounded up with a margin of a fifth or more; an import whose cost stayed under the load's peak is charged what
    // its arrays hold.
    struct Cost {
        std::string_view import;
        std::size_t bytes;
    };
    static constexpr Cost kCosts[] = {
        {kMeshes, 0},           // the meshes, their GPU copies: the estimate counts them by vertex and triangle
        {kHulls, 32},           // --lines silhouette: +5 MiB (4 bytes a triangle): welded normals, hull indices
        {kEdgeAdjacency, 128},  // --lines crease: +118 MiB (95): edges, face uses, face planes, the position weld
        {kFaceOrientation, 96}, // --face-orientation during-vertices: +89 MiB (72): per-vertex lighting, face sets
        {kCurvature, 384},      // --lines suggestive-object: +389 MiB (314): curvature, its derivative, the lines
        {kSurfacePatches, 32},  // --lines suggestive: +0 MiB (under the load's peak): a patch per triangle, a weld
        {kIntersections, 96},   // --lines intersection: +5 MiB; its index (boxes, order, nodes: about 40) is freed
    };
    for (const Cost& cost : kCosts)
        if (cost.import == name) return cost.bytes;
    throw std::logic_error("SceneImport::bytesPerTriangle(): no scene import '" + std::string(name) + "'");
}

void GpuScene::importDerived(const std::string& name) {
    if (name == SceneImport::kMeshes) {
        meshes();
    } else if (name == SceneImport::kHulls) {
        hullArrays();
    } else if (name == SceneImport::kEdgeAdjacency) {
        for (std::size_t mesh = 0; mesh < meshCount(); ++mesh) edgeAdjacency(mesh);
    } else if (name == SceneImport::kFaceOrientation) {
        cpuOrientation();
    } else if (name == SceneImport::kIntersections) {
        meshIntersections();
    } else if (name == SceneImport::kSurfacePatches) {
        surfacePatches();
    } else if (name != SceneImport::kCurvature) { // derived by its reader, at the smoothing it asks for
        throw std::logic_error("GpuScene::importDerived(): no scene import '" + name + "'");
    }
}

} // namespace inkgraph
