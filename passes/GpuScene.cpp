#include "passes/GpuScene.h"

namespace inkgraph {

const std::vector<GpuScene::DrawMesh>& GpuScene::meshes() {
    if (mUploaded) return mMeshes;
    mMeshes.reserve(mScene.meshes.size());
    for (const Mesh& mesh : mScene.meshes) {
        std::vector<glm::vec3> relative(mesh.positions.size());
        for (std::size_t i = 0; i < relative.size(); ++i)
            relative[i] = glm::vec3(glm::dvec3(mesh.positions[i]) - mWorldOrigin);
        const std::string label = "mesh '" + mesh.name + "'";
        DrawMesh draw{GlBuffer(relative.data(), relative.size() * sizeof(glm::vec3), label + " positions"),
                      GlBuffer(mesh.normals.data(), mesh.normals.size() * sizeof(glm::vec3), label + " normals"),
                      GlBuffer(mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3), label + " indices"),
                      GlVertexArray(label),
                      static_cast<GLsizei>(mesh.triangles.size() * 3),
                      mesh.baseColor};
        draw.vertexArray.setVec3Attribute(kPositionLocation, draw.positions);
        draw.vertexArray.setVec3Attribute(kNormalLocation, draw.normals);
        draw.vertexArray.setIndexBuffer(draw.indices);
        mMeshes.push_back(std::move(draw));
    }
    mUploaded = true;
    return mMeshes;
}

} // namespace inkgraph
