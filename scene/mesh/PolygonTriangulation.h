#pragma once
/** @file The triangles of a polygon as a file writes it (an OBJ `f` or a PLY `face` of more than three corners).
 *  Blender exports n-gons by default, and text, logos and floor plans give concave ones: a fan from the first corner
 *  draws a star or an L-shape with triangles outside it, so a concave polygon is cut into ears instead (ear clipping:
 *  Meisters, "Polygons have ears", 1975; each ear a corner whose triangle with its two neighbours holds no other
 *  corner, cut off until three are left, O(n^2)).
 *
 *  The polygon is taken in its plane: the plane of its Newell normal (the sum of its edges' cross products, which
 *  holds for warped polygons too), the corners projected onto it, turning counter-clockwise about the normal. A
 *  convex polygon, and a flat one (no area: every triangulation is as good), keeps the fan from its first corner.
 *  The readers hand a polygon over from the corner of its lowest vertex index (lowestCornerFirst()), so a convex
 *  polygon written again in reverse (the back of a double-faced card) is fanned from the same corner along the same
 *  diagonals, into back-to-back twins of the first's triangles (scene/mesh/MeshOps.h); a concave one's ears may
 *  differ. Corners written twice in a row and the tips of spikes that go out
 *  and come back along themselves enclose nothing: they are cut first, as triangles of no area. A polygon that crosses
 *  itself has no one right triangulation: a star that winds twice round is fanned, and one with no ear left, or whose
 *  last triangle turns the wrong way, is cut into ears as far as that goes and the rest fanned; each is counted, so
 *  the reader can warn (not every crossing shows in these tests: one whose ears all turn the right way is cut
 *  without a word).
 *
 *  Written here because Debian 12 packages no triangulator that does not come with GL: GLU's tessellator links
 *  libOpenGL, which the scene layer must not (docs/architecture.md). */

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkgraph {

/** What a polygon turned out to be. */
/** Where a polygon is handed to the triangulator from: the corner with the lowest vertex index (`vertexOf(corner)`),
 *  whichever corner the file wrote first. */
template <typename Corner, typename VertexOf>
std::size_t lowestCornerFirst(std::span<const Corner> corners, VertexOf vertexOf) {
    std::size_t first = 0;
    for (std::size_t i = 1; i < corners.size(); ++i)
        if (vertexOf(corners[i]) < vertexOf(corners[first])) first = i;
    return first;
}

/** Triangles cut from a polygon's corners taken from `first` on, as indices into its corners in their own order. */
void rotateTriangles(std::vector<glm::uvec3>& triangles, std::size_t first, std::size_t cornerCount);

enum class PolygonShape {
    Convex,    ///< or flat, or a triangle: a fan from the first corner
    Concave,   ///< simple and concave: cut into ears
    Unresolved ///< crosses itself, or the work budget ran out: fanned where no ear was found, maybe the wrong shape
};

/** Triangulates the polygons of one file, counting what it found and bounding the work of all of them together: a
 *  hostile file of many large concave polygons costs at most kWorkBudget corner tests, then the rest are fanned. */
class PolygonTriangulator {
public:
    /** Corner-in-triangle tests for one file: about a second. A real file's concave polygons (a text's glyphs of a
     *  few hundred corners) take a few thousand tests each. */
    static constexpr std::size_t kWorkBudget = std::size_t(1) << 28;

    explicit PolygonTriangulator(std::size_t workBudget = kWorkBudget) : mWorkLeft(workBudget) {}

    /** The corners.size() - 2 triangles of the polygon whose corners are `corners`, in order, as indices into
     *  `corners`, each in the polygon's winding; replaces what `triangles` held. */
    PolygonShape triangulate(std::span<const glm::dvec3> corners, std::vector<glm::uvec3>& triangles);

    std::size_t concavePolygons() const { return mConcave; }
    /** PolygonShape::Unresolved, both kinds. */
    std::size_t unresolvedPolygons() const { return mUnresolved + mBeyondWork; }
    /** Of them, the concave polygons fanned because the file's work budget was spent. */
    std::size_t polygonsBeyondWork() const { return mBeyondWork; }

private:
    /** `noArea`: twice an area that counts as none. */
    PolygonShape clipEars(std::span<const glm::dvec3> corners, const glm::dvec3& normal, double noArea,
                          std::vector<glm::uvec3>& triangles);

    std::size_t mWorkLeft;
    std::size_t mConcave = 0;
    std::size_t mUnresolved = 0; ///< crossing themselves
    std::size_t mBeyondWork = 0;
    std::vector<glm::dvec2> mPlane; ///< scratch: the corners in the polygon's plane
    std::vector<std::uint32_t> mNext, mPrevious;
    std::vector<char> mMayBlock; ///< scratch: a corner that is not strictly convex, which alone can lie in an ear
};

} // namespace inkgraph
