#pragma once
/** @file The scene's meshes on the GPU, uploaded the first time a pass that runs asks for them. */

#include "gl/GlObjects.h"
#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <vector>

namespace inkgraph {

class GpuScene {
public:
    struct DrawMesh {
        GlBuffer positions;
        GlBuffer normals;
        GlBuffer indices;
        GlVertexArray vertexArray;
        GLsizei indexCount;
        glm::vec4 baseColor;
    };

    static constexpr GLuint kPositionLocation = 0;
    static constexpr GLuint kNormalLocation = 1;

    /** Keeps references; nothing is uploaded until meshes() is called. */
    GpuScene(const Scene& scene, glm::dvec3 worldOrigin) : mScene(scene), mWorldOrigin(worldOrigin) {}

    /** Uploads on first call (positions relative to worldOrigin, in float), then returns the cached meshes. */
    const std::vector<DrawMesh>& meshes();
    bool isUploaded() const { return mUploaded; }

private:
    const Scene& mScene;
    glm::dvec3 mWorldOrigin;
    std::vector<DrawMesh> mMeshes;
    bool mUploaded = false;
};

} // namespace inkgraph
