#pragma once
/** @file The CPU face orientation of Winnemoller & Bangay 2002 for every mesh, computed and uploaded the first time a
 *  pass that runs asks for it (the comic fill draws the front sets; the outline chooses its edges per view on the
 *  GPU and needs none); owned by GpuScene (setOrientation(), cpuOrientation()). With the Standard method the GPU
 *  culls and nothing is computed here. */

#include "gl/GlObjects.h"
#include "passes/FrameParams.h"
#include "passes/GpuScene.h"
#include "passes/orientation/OrientationSettings.h"
#include "scene/mesh/FaceOrientation.h"
#include "scene/Scene.h"

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** Per-method numbers for --stats (Winnemoller & Bangay 2002 Figure 8, plus holes and time). */
struct OrientationReport {
    std::string method;
    std::string viewVector; ///< what was used: "exact" or "constant"
    bool fellBack = false;  ///< constant asked for, exact used
    std::string fallBackReason;
    double sinAlpha = 0.0;
    double betaMaxDegrees = 0.0; ///< largest over the meshes
    double cutoff = 0.0;         ///< largest over the meshes (betaMax differs per mesh)
    std::size_t triangles = 0;
    std::size_t vertices = 0;
    std::size_t frontTriangles = 0; ///< Standard: the exact per-face count
    std::size_t frontVertices = 0;  ///< Standard: vertices of exact front triangles
    std::size_t exactFrontTriangles = 0;
    std::size_t missedTriangles = 0; ///< holes against exact classification
    double deriveMilliseconds = 0.0; ///< face normals, betaMax, adjacency (load-time work in the paper; 0 for
                                     ///< Standard)
    double markMilliseconds = 0.0;   ///< CPU marking and lighting (0 for Standard)
    double uploadMilliseconds = 0.0; ///< CPU time of creating the buffers and arrays (the driver copies the data
                                     ///< before returning)
};

class SceneOrientation {
public:
    /** One per mesh of the scene, in GpuScene's order. */
    struct MeshSets {
        GlBuffer shadeCoords; ///< vec2 per vertex, location kShadeCoordLocation
        GlBuffer frontIndices;
        GlBuffer backIndices;
        GlVertexArray frontArray; ///< positions + normals (GpuScene's buffers) + shadeCoords, frontIndices
        GlVertexArray backArray;  ///< positions + normals, backIndices
        GLsizei frontIndexCount;
        GLsizei backIndexCount;
    };
    static constexpr GLuint kShadeCoordLocation = 5; ///< after the material snippet's 2-4

    /** Keeps references; computes nothing until sets() or report() is called. Throws std::invalid_argument for a
     *  front rule outside 1..3 or a negative shininess. */
    SceneOrientation(const Scene& scene, GpuScene& gpuScene, const FrameParams& frame, OrientationSettings settings);

    bool usesCpuMarking() const { return mSettings.method != FaceOrientationMethod::Standard; }
    /** CPU methods: marks, lights and uploads on the first call. Throws std::logic_error for Standard. */
    const std::vector<MeshSets>& sets();
    /** The numbers for --stats; for Standard counts the exact front share on the CPU (only when asked). The exact
     *  counts and holes are counted here, not while marking, so they never add to a pass's time. */
    const OrientationReport& report();
    /** report() as the --stats "face_orientation" object (method, view vector, fall-back, shares, holes, times). */
    nlohmann::ordered_json describe();
    /** A new frame (the camera or light moved): the next sets() marks, lights and uploads again. The per-mesh
     *  derived data (face normals, betaMax, adjacency) is kept: it depends on the mesh alone. */
    void invalidate();

private:
    /** The view vector for the current eye (the scene's bounding sphere is computed on the first call only). */
    ViewVectorChoice viewVector();
    /** Derives (once), marks, lights and uploads every mesh; fills mSets, mOrientations and mReport. */
    void compute();

    const Scene& mScene;
    GpuScene& mGpuScene;
    const FrameParams& mFrame;
    OrientationSettings mSettings;
    std::optional<BoundingSphere> mSphere;      ///< of the scene; on the first viewVector()
    std::vector<OrientationMeshData> mDerived;  ///< per mesh; derived on the first compute()
    std::vector<MeshOrientation> mOrientations; ///< per mesh, of the last compute(); report() counts holes on it
    std::vector<MeshSets> mSets;
    std::optional<OrientationReport> mReport;
    bool mComputed = false;
    bool mCounted = false;
    double mDeriveMilliseconds = 0.0; ///< exact front and missed triangles are in mReport
};

} // namespace inkgraph
