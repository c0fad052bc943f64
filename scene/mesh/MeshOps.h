#pragma once
/** @file Geometry clean-up shared by every loader: welding, degenerate removal and smooth normals.
 *  Exposed (rather than hidden in a .cpp) so tests and procedural meshes can use the same code paths. */

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace inkgraph {

/** An axis-aligned box; empty (min > max) until a point is added. */
struct BoundingBox {
    glm::dvec3 min{std::numeric_limits<double>::max()};
    glm::dvec3 max{std::numeric_limits<double>::lowest()};

    void add(const glm::dvec3& point) {
        min = glm::min(min, point);
        max = glm::max(max, point);
    }
    bool empty() const { return min.x > max.x; }
    double diagonal() const { return empty() ? 0.0 : glm::length(max - min); }
    glm::dvec3 center() const { return (min + max) * 0.5; }
};

BoundingBox computeBoundingBox(std::span<const glm::vec3> positions);

/** Result of weldVertices(): the vertices to keep and where every input vertex went. */
struct WeldMap {
    std::vector<std::uint32_t> kept;     ///< input index of each output vertex, in first-seen order
    std::vector<std::uint32_t> outputOf; ///< output index of each input vertex
    /** Some vertex stayed apart from one in reach for its normal alone (a hard edge, a double-faced card's sides). */
    bool splitByNormals = false;
};

/** Merges vertices closer than `distance` (absolute). When `normals` is not empty (one per position), two vertices
 *  merge only if their normals also agree, so hard edges keep their split normals; when `attributeClasses` is not
 *  empty, only if their classes are equal (texture seams and colour borders keep their split vertices). Uses a hash
 * grid with cells of ~2.5 x distance and checks the 8 cells that can hold a match, so points straddling a cell border
 * still merge. Greedy: each vertex joins the first earlier representative within reach. */
WeldMap weldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, double distance,
                     std::span<const std::uint32_t> attributeClasses = {});

/** The position weld of a loaded mesh (weldVertices() ignoring normals and attributes) at `distance`: the identity
 *  map, computed without a lookup, when the loader already welded the mesh by position at that distance or more
 *  (Mesh::positionsWeldedAt), else weldVertices(). What every datum derived on position-welded vertices (hull
 *  normals, edge adjacency, curvature) is built from, so one weld can serve them all. */
WeldMap weldMeshPositions(const Mesh& mesh, double distance);

/** `v` of unit length, or zero when it is zero or not finite (the eye sitting on a vertex, a degenerate face). */
glm::dvec3 normalizedOrZero(const glm::dvec3& v);

/** Area-weighted smooth normals: every vertex sums the unnormalised cross products of its triangles. A vertex whose
 *  sum vanishes (e.g. two opposite faces) takes the normal of one incident face, or (0,0,1) if all are degenerate. */
std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions,
                                            std::span<const glm::uvec3> triangles);

/** Area-weighted smooth normals in which every vertex within `weldDistance` (absolute) of another shares its normal,
 *  whatever normals the mesh carries: the copies of a vertex that a hard edge splits get one common direction (the
 *  sum over all their faces, the second of each back-to-back pair left out, which would cancel the first), so a
 *  surface pushed out along these normals stays closed (the inflated hull). Welds
 *  with weldVertices() ignoring normals; returns one unit normal per input position. */
std::vector<glm::vec3> computePositionWeldedNormals(std::span<const glm::vec3> positions,
                                                    std::span<const glm::uvec3> triangles, double weldDistance);
/** The same with the position weld given (weldVertices() of `positions` ignoring normals, or weldMeshPositions()).
 *  Throws std::invalid_argument when the map is not one entry per position. */
std::vector<glm::vec3> computePositionWeldedNormals(std::span<const glm::vec3> positions,
                                                    std::span<const glm::uvec3> triangles, const WeldMap& weld);

/** Whether `point` (world space, like the mesh) lies inside the closed mesh, by ray parity: a ray from the point
 *  crosses the surface an odd number of times when it starts inside. Six fixed rays, three mutually skewed
 *  directions and their opposites, vote; five must cross an odd number of times, so one ray grazing an edge or a
 *  vertex (counted twice or not at all) cannot decide alone, and a point that an open mesh covers only on one side
 *  (under a dome, inside a cup) is outside. */
bool isPointInsideMesh(const Mesh& mesh, glm::dvec3 point);

/** Relative area at or below which a triangle counts as degenerate (times the squared bounding-box diagonal): the
 *  loaders drop such faces (finalizeMesh), and the mesh analyses skip them by the same rule, so a loaded mesh loses
 *  nothing more there. */
inline constexpr double kDegenerateAreaRelative = 1e-14;

/** finalizeMesh() warns (details-merged) when the weld collapses more than this share of a mesh's triangles. */
inline constexpr double kWeldedAwayShareToWarn = 0.01;

/** The triangles with a repeated index or an area at most `minArea`, ascending (finalizeMesh() drops them). */
std::vector<std::uint32_t> degenerateTriangles(std::span<const glm::vec3> positions,
                                               std::span<const glm::uvec3> triangles, double minArea);

/** A triangle's corners in ascending order, and whether reaching that order took an odd number of swaps: two
 *  triangles on the same corners face opposite ways exactly when their parities differ. */
struct SortedCorners {
    glm::uvec3 sorted;
    bool odd = false;
};
SortedCorners sortedCorners(const glm::uvec3& triangle);

/** The triangles that lie back to back with an earlier one: on the same three vertices, wound the other way, as
 *  exporters write a double-faced card, leaf or sheet of paper. Each earlier triangle takes at most one later one, so
 *  a pair names only its second; ascending. Linear time (hashed buckets), whatever the repeats. By vertex index: run
 *  on welded vertices, so copies of a corner count as one where the weld merged them. */
std::vector<std::uint32_t> backToBackTwins(std::span<const glm::uvec3> triangles);

/** The triangles that repeat an earlier one: on the same three vertices, wound the same way (a face the file gives
 *  twice, whichever corner it starts from). Ascending; linear time, as backToBackTwins(). By vertex index. */
std::vector<std::uint32_t> repeatedTriangles(std::span<const glm::uvec3> triangles);

/** Removes the entries of a per-triangle array (the triangles themselves, or anything kept per triangle) at
 *  `ascending` (triangle indices, as backToBackTwins() gives them), keeping the others in order. */
template <typename PerTriangle>
void removeTriangles(std::vector<PerTriangle>& perTriangle, std::span<const std::uint32_t> ascending) {
    if (ascending.empty()) return;
    std::size_t kept = 0;
    std::size_t next = 0;
    for (std::size_t t = 0; t < perTriangle.size(); ++t) {
        if (next < ascending.size() && ascending[next] == t) {
            ++next;
            continue;
        }
        perTriangle[kept++] = perTriangle[t];
    }
    perTriangle.resize(kept);
}

/** A mesh as a loader reads it: world-space, not welded, normals optional (empty or one per position). */
struct RawMesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::uvec3> triangles;
    std::vector<glm::vec2> texcoords[2]; ///< as Mesh::texcoords: empty or one per position
    std::vector<glm::vec4> colors;       ///< as Mesh::colors: empty or one per position
    /** Per triangle, 1 where the reader swapped its 2nd and 3rd corners (a mirroring node transform keeps its front
     *  outward so); empty when it swapped none. As Mesh::cornersSwapped. */
    std::vector<std::uint8_t> cornersSwapped;
    Material material;
    std::vector<std::string> nodePath; ///< as Mesh::nodePath
    std::size_t nodeInstance = 0;      ///< as Mesh::nodeInstance
};

/** Turns a raw mesh into a clean Mesh: welds within options.weldTolerance x modelDiagonal, drops degenerate
 *  triangles (area <= 1e-14 x modelDiagonal^2), faces given twice (repeatedTriangles()), a two-sided material's
 * back-to-back twins (backToBackTwins(): the material draws the back of the first, and the pair's smooth normals
 * cancel) and unreferenced vertices, normalises the file's normals (zero ones are recomputed) or computes smooth ones.
 * Adds its counts to `report`, and the warning details-merged when the weld collapsed more than kWeldedAwayShareToWarn
 * of the triangles. The result may have no triangles. */
Mesh finalizeMesh(RawMesh raw, double modelDiagonal, const LoadOptions& options, LoadReport& report);

} // namespace inkgraph
