#pragma once
/** @file Per-vertex curvature of a triangle mesh (Rusinkiewicz 2004, docs/lines.md): normals,
 *  Voronoi point areas, the second fundamental form fitted per face and carried to the vertices, principal curvatures
 *  and directions, and the derivative of curvature C fitted the same way one order up. No GL; all in double.
 *
 *  Everything is computed on position-welded vertices (MeshOps weldVertices, ignoring normals): loaders keep a copy
 *  of a vertex per distinct normal, and a cube's split corners, or an STL soup, would otherwise be separate sheets
 *  with no neighbours across an edge. Sign convention: curvature is positive where the surface bends away from its
 *  normal (a sphere with outward normals has kappa = +1/R). */

#include "scene/mesh/MeshOps.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkgraph {

struct MeshCurvatureCounts {
    std::size_t weldedVertices = 0;
    /** Faces left out of everything: two corners weld together, or the area is at most 1e-14 x (bounding-box
     *  diagonal)^2 (the loaders' rule). */
    std::size_t degenerateFaces = 0;
    /** Faces whose least-squares fit (of II, or of C) was singular to working precision and so adds nothing; rtsc's
     *  LDL^T failure. A face that is not degenerate by area can still be singular (a needle). */
    std::size_t singularCurvatureFits = 0;
    std::size_t singularDerivativeFits = 0;
    /** Welded vertices no curvature fit reaches (no usable face touches them, or every fit around them was
     *  singular): zero curvature and C. Without a usable face the normal is (0, 0, 1). */
    std::size_t isolatedVertices = 0;
};

/** A smoothing of computeMeshCurvature() is refused when, estimated before it starts, the windows (each vertex's
 *  Gaussian window, flooded over the surface) of the meshes where a mean window would hold more than
 *  kMaxCostlyWindowShare of the mesh's vertices would cost more than kMaxSmoothingVisits vertex visits in all, about
 *  50 s for the three smoothings on the 2-core machine (the bunny's 35,000 vertices: 7.8e7 visits in 9 s, 7.6e8 in
 *  79 s, the whole mesh, 1.2e9, in 197 s).
 *  The second condition keeps a fine mesh at a narrow smoothing, costly only for its size (a million-vertex scan at
 *  the default, 0.01 of the radius: about 1.3e9 visits, windows of a thousandth of it), slow as before rather than
 *  refused: what is refused is a smoothing wide for the model, which blurs its shape away as well. */
inline constexpr double kMaxSmoothingVisits = 5e8;
inline constexpr double kMaxCostlyWindowShare = 1.0 / 16.0;

/** The refusal of a smoothing too costly and too wide for its mesh (kMaxSmoothingVisits, kMaxCostlyWindowShare). */
class SmoothingTooCostlyError : public SceneError {
public:
    SmoothingTooCostlyError(double smoothing, double estimatedVisits, std::size_t vertexCount,
                            double smoothingWithinLimit);
    double smoothing() const { return mSmoothing; }
    double estimatedVisits() const { return mEstimatedVisits; }
    std::size_t vertexCount() const { return mVertexCount; }
    /** About the largest smoothing, in the same units, that this mesh would not refuse; 0 when even a thousandth of
     *  the smoothing would be refused. */
    double smoothingWithinLimit() const { return mSmoothingWithinLimit; }

private:
    double mSmoothing;
    double mEstimatedVisits;
    std::size_t mVertexCount;
    double mSmoothingWithinLimit;
};

/** A mesh to smooth, for requireAffordableSmoothing(): its positions and triangles and their position weld. */
struct MeshToSmooth {
    std::span<const glm::vec3> positions;
    std::span<const glm::uvec3> triangles;
    const WeldMap* weld = nullptr;
};

/** Throws SmoothingTooCostlyError when smoothing these meshes over `smoothing` (absolute) is refused: the meshes
 *  whose mean window would hold more than kMaxCostlyWindowShare of them would cost more than kMaxSmoothingVisits
 *  in all. Each mesh's cost is estimated from 64 of its windows (a dozen times more to name the largest smoothing
 *  not refused, when one is), so a scene checks all of them before smoothing any. Nothing for a smoothing of 0. */
void requireAffordableSmoothing(std::span<const MeshToSmooth> meshes, double smoothing);
/** The same for one mesh. */
void requireAffordableSmoothing(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                const WeldMap& weld, double smoothing);

/** The curvature of one mesh, per welded vertex. Every value is finite. */
struct MeshCurvature {
    std::vector<std::uint32_t> weldedOf; ///< per input vertex: its welded vertex
    std::vector<glm::dvec3> positions;   ///< per welded vertex (the first input copy's position)
    /** The usable faces (not degenerate), in welded ids, counter-clockwise as the input; what lines are found on. */
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> sourceFace; ///< per usable face: its index in the input triangles
    std::vector<glm::dvec3> normals;       ///< unit, Max (1999) weighted: exact for vertices on a sphere
    std::vector<double> pointAreas;        ///< mixed Voronoi area (Meyer et al. 2003); they sum to the surface area
    /** Principal curvatures, sorted so |kappa1| >= |kappa2|, and their unit directions, perpendicular to the normal,
     *  with direction2 = normal x direction1. */
    std::vector<double> curvature1;
    std::vector<double> curvature2;
    std::vector<glm::dvec3> direction1;
    std::vector<glm::dvec3> direction2;
    /** The derivative of the second fundamental form, C(a, b, c) = (D_a II)(b, c), a symmetric trilinear form, in
     *  the principal frame: (C111, C112, C122, C222) with index 1 = direction1, 2 = direction2. */
    std::vector<glm::dvec4> derivative;
    MeshCurvatureCounts counts;

    /** C(d, d, d) for a tangent vector d = (d . direction1, d . direction2) in vertex `vertex`'s principal frame. */
    double derivativeAlong(std::size_t vertex, double alongDirection1, double alongDirection2) const {
        const glm::dvec4& c = derivative[vertex];
        const double a = alongDirection1, b = alongDirection2;
        return a * a * a * c.x + 3.0 * a * a * b * c.y + 3.0 * a * b * b * c.z + b * b * b * c.w;
    }
};

/** Curvature of a triangle list (docs/lines.md):
 *  1. vertex normals: the sum over faces of the face's cross product weighted by 1 / (|a|^2 |b|^2) for the corner's
 *     two edges a, b (Max 1999); faces with a zero-length edge are skipped;
 *  2. corner areas: the Voronoi part of each corner for a non-obtuse triangle, else half the area to the obtuse
 *     corner and a quarter to each other (Meyer et al.); a point area is the sum of its corners;
 *  3. per face, II in the frame (t, b) of the face plane by least squares over the three edges,
 *     II (e.t, e.b) = (dn.t, dn.b) with dn the difference of the vertex normals along e (normal equations, LDL^T);
 *  4. each vertex's frame rotated into the face's plane, II re-expressed in it and accumulated with weight
 *     corner area / point area;
 *  5. per vertex, the 2x2 tensor diagonalised (Jacobi rotation): kappa1, kappa2, direction1, direction2;
 *  6. per face, the three vertex tensors in the face frame, their differences along the edges giving C(e, ., .) by
 *     least squares for (C111, C112, C122, C222), carried back to the vertices like II.
 *  `weldDistance` (absolute, >= 0): vertices closer than this are one.
 *  `smoothing` (absolute, >= 0; 0 = none): the standard deviation of a Gaussian over the surface, as rtsc smooths
 *  before finding lines (diffuse_normals, diffuse_curv, diffuse_dcurv): the normals are averaged after step 1 (then
 *  renormalised), the tensors II after step 4 and C after step 6, each over the vertices joined to the vertex by
 *  edges within 3 x smoothing of it (a flood over the mesh, so the other side of a thin part is not reached through
 *  the air), weighted by exp(-d^2 / (2 smoothing^2)) x point area; tensors are re-expressed in the vertex's frame
 *  (rotated into its plane) as in step 4. So curvature is measured at that scale, not at the facets' or a scan's
 *  noise.
 *  Throws SmoothingTooCostlyError, before smoothing, when the smoothing is too costly and too wide for the mesh
 *  (requireAffordableSmoothing()). Throws std::out_of_range naming 'triangles' for an index past the positions,
 * std::invalid_argument naming 'weldDistance' or 'smoothing' for a negative or non-finite one, and naming 'positions'
 * for a non-finite coordinate. */
MeshCurvature computeMeshCurvature(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                   double weldDistance, double smoothing = 0.0);
/** The same with the position weld given (weldVertices() of `positions` ignoring normals, or weldMeshPositions()).
 *  Throws std::invalid_argument when the map is not one entry per position. */
MeshCurvature computeMeshCurvature(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                   const WeldMap& weld, double smoothing = 0.0);

} // namespace inkgraph
