#pragma once
/** @file Winnemöller & Bangay's CPU face orientation (Listing 1, errata fixed) and its per-vertex comic lighting.
 *
 *  Conventions (docs/shading.md): V is eye -> point, L is point -> light; a surface is front-facing
 *  where N.V < cut-off. The cut-off is +sin(alpha) for face tests and sin(min(pi/2, alpha + betaMax)) for vertex
 *  tests (the paper's "-sin alpha" is a sign slip that opens holes; `paperCutoff` reproduces it for tests). No GL. */

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace inkgraph {

enum class ViewVectorMode { Exact, Constant };
enum class FaceOrientationMethod { Standard, DuringTriangles, DuringVertices, AfterVertices };

std::string viewVectorModeName(ViewVectorMode mode);               ///< "exact", "constant"
std::string faceOrientationMethodName(FaceOrientationMethod mode); ///< "standard", "during-triangles", ...

/** Data derived from a mesh once, only when a CPU orientation method runs: unit face normals, each vertex's beta (the
 *  largest angle between its normal and the normals of its incident faces) and their maximum, and, for
 *  during-vertices, the triangles around each vertex. */
struct OrientationMeshData {
    std::vector<glm::vec3> faceNormals;
    /** Per vertex (sin beta_v, cos beta_v). The vertex tests use the vertex's own cut-off sin(min(pi/2, alpha +
     *  beta_v)): still hole-free (a front face's vertices each deviate from it by at most their own beta), and tight
     *  where the normals are good, so a few stray normals (the teapot's poles: beta 111 deg) do not mark every
     *  triangle front as the global betaMax would. */
    std::vector<glm::vec2> vertexBeta;
    double betaMaxRadians = 0.0;
    std::vector<std::uint32_t> vertexTriangleStart; ///< CSR offsets, size vertexCount + 1 (during-vertices only)
    std::vector<std::uint32_t> vertexTriangles;     ///< triangle indices around each vertex (during-vertices only)
};
/** `withVertexTriangles` builds the CSR adjacency too. */
OrientationMeshData deriveOrientationData(const Mesh& mesh, bool withVertexTriangles);

/** The constant view vector of Winnemöller & Bangay 2002 §3.5 for one frame, or why exact vectors are used
 *  instead. */
struct ViewVectorChoice {
    bool constant = false;        ///< false: exact per-vertex or per-face view vectors
    bool fellBack = false;        ///< constant was asked for, but the eye is inside or near the bounding sphere
    glm::dvec3 constantView{0.0}; ///< unit V_c = (C - E)/|C - E| when `constant`
    double sinAlpha = 0.0;        ///< r_b/|C - E| (the bounding-sphere radius, not the paper's box side)
    std::string reason;           ///< one line for the stats ("eye inside the bounding sphere", ...)
};
/** `center`/`radius`: the bounding sphere of the mesh (or scene). Falls back to exact when
 *  |C - E| <= radius x (1 + 1e-3) or sin(alpha) > 0.5 (docs/shading.md); never evaluates asin above 1. */
ViewVectorChoice chooseViewVector(ViewVectorMode requested, const glm::dvec3& eye, const glm::dvec3& center,
                                  double radius);

struct OrientationRequest {
    FaceOrientationMethod method = FaceOrientationMethod::AfterVertices; ///< not Standard (that is the GPU's job)
    int frontRule = 3;     ///< 1: all three vertices front, 2: at least two, 3: at least one (vertex methods)
    ViewVectorChoice view; ///< from chooseViewVector()
    glm::dvec3 eye{0.0};   ///< same space as the mesh positions
    glm::dvec3 towardLight{0.0, 0.0, 1.0}; ///< unit, L (point -> light)
    double shininess = 32.0;               ///< >= 0; 0 gives specular 1 wherever n.l > 0
    bool paperCutoff = false;              ///< tests only: the paper's -sin(alpha) cut-off without betaMax
    bool countMissed = true; ///< false skips the exact per-face reference (benchmarks, or callers that time
                             ///< the method and count holes apart); `missedTriangles` is then 0
};

/** What one method decided for one mesh. Both triangle lists keep the mesh's triangle order.
 *
 *  Intermediate triangles (Listing 1's setIntermediateFlag, errata fixed to N.V > -cut-off) are front triangles near
 *  the silhouette that the outline must still draw: with a vertex method, a front triangle with at least one vertex
 *  whose N.V > -cut-off; with during-triangles, a front face whose n_f.V > -cut-off (none with exact vectors, whose
 *  face cut-off is 0). They are in both lists. */
struct MeshOrientation {
    std::vector<glm::uvec3> frontTriangles; ///< drawn filled, shaded from `shadeCoords`
    std::vector<glm::uvec3> backTriangles;  ///< drawn by the back-face outline (BackCondition: every triangle that
                                            ///< is not front, plus the intermediate ones)
    std::vector<glm::vec2> shadeCoords;     ///< per vertex (s, t) = (max(N.L,0), max(R.V,0)^n gated by N.L > 0);
                                            ///< computed only for front vertices (others 0)
    std::size_t frontVertexCount = 0;       ///< vertices marked front (lighting computed)
    std::size_t missedTriangles = 0;        ///< exact per-face front triangles not in frontTriangles (holes)
    double cutoff = 0.0;                    ///< the N.V cut-off that was used (face test for during-triangles,
                                            ///< vertex test otherwise)
    double betaMaxRadians = 0.0;
};

/** Runs one method over one mesh. `data` must come from deriveOrientationData(mesh, method == DuringVertices).
 *  During-triangles tests faces directly and ignores `frontRule`. With exact view vectors its face test is the exact
 *  per-face test itself, so it marks exactly the exact front set.
 *  When the vertex cut-off angle alpha + betaMax reaches pi/2, every vertex is front (the bound then says nothing).
 *  The approximate tests compare against cut-off + 1e-6, so the rounding of float normals cannot open a hole.
 *  Throws std::invalid_argument for Standard, a rule outside 1..3, a negative or NaN shininess, a non-finite eye, a
 *  zero or non-finite light direction, or `data` that does not match the mesh. */
MeshOrientation orientMesh(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request);
/** The same into `result`, reusing its capacity: a caller that orients every frame allocates its lists only once. */
void orientMesh(const Mesh& mesh, const OrientationMeshData& data, const OrientationRequest& request,
                MeshOrientation& result);

/** Exact per-face classification (n_f.(P - E) < 0 with P the triangle's first vertex, in double), the reference for
 *  `missedTriangles` and for the Standard method's share in the stats. */
std::size_t countExactFrontTriangles(const Mesh& mesh, const glm::dvec3& eye);

/** Vertices used by at least one exact front triangle (the Standard method's lit vertices in the stats). */
std::size_t countExactFrontVertices(const Mesh& mesh, const glm::dvec3& eye);

/** Exact front triangles that are not in `frontTriangles`, which must list triangles of `mesh` in the mesh's order
 *  (as orientMesh() returns them). */
std::size_t countMissedTriangles(const Mesh& mesh, const glm::dvec3& eye,
                                 const std::vector<glm::uvec3>& frontTriangles);

} // namespace inkgraph
