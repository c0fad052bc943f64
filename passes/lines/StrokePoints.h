#pragma once
/** @file --strokes: every kept stroke of every drawn line type with, per point, its position in output pixels and the
 *  3-D point it came from (docs/datasets.md, "Strokes with their 3-D points"). Built on the CPU from what the graph
 *  computed for it (StillGraph::strokePointResources(): the stroke stage's kept strokes, the G-buffer's depth, the
 *  object-space skeletons and the mesh edges' point images), only when --strokes or the library asks.
 *
 *  Where a point's 3-D point comes from, by its type's family (passes/lines/LineType.h):
 *  - image space and the GL bands (contour, suggestive, the image edges, outline, silhouette): the G-buffer surface
 *    under the sub-pixel point. Of the model pixels in the 3 x 3 around it, the nearer surface (those within a 5%
 *    depth jump of the nearest depth: a contour on the rim lies half on the background or on a farther surface) and
 *    of that the pixel nearest to the point gives the linear depth, and the point is put on the camera ray through
 *    (x, y) at that depth: it projects back to (x, y) exactly and lies on the surface within the depth's sampling
 *    error. Its triangle is that pixel's (gbuffer.triangleId, requested with the strokes; the mesh from the triangle's
 *    range). No model pixel there: null. A GL
 *    band (outline, silhouette) looks as far as half its width plus a pixel, since its middle may lie off the model.
 *  - object space (intersection, suggestive-object and their hidden twins): the 3-D point of the segment sample the
 *    stroke point is (LineSkeleton::surface), with its triangle.
 *  - mesh edges (crease, border, mesh-silhouette and their hidden twins): the mesh-edges pass's "<kind>-points" image,
 *    each line fragment's view position interpolated along its edge and the edge's triangle, at the stroke point's
 *    pixel (the nearest drawn pixel of the 3 x 3 around it): the edge's own point, for hidden edges too. GL
 *    interpolates a line's attributes at the pixel centre's foot on the infinite line, so on an edge shorter than a
 *    pixel (a fine mesh's pole) the point may lie past the edge's end: it is clamped to the nearest side of its
 *    triangle, the edge it was drawn from.
 *  A point the stroke stage put in to bridge a gap of a mesh-space type takes the 3-D point between its stroke
 *  neighbours' (linear in the stroke's point order). */

#include "passes/lines/StrokesPass.h"
#include "scene/Camera.h"
#include "scene/MeshLabels.h"

#include <glm/glm.hpp>
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace inkgraph {

/** Where --strokes finds a type's 3-D points. */
enum class StrokePointSource {
    Surface,  ///< the G-buffer's depth under the point
    Skeleton, ///< the skeleton's own SurfacePoint (object space)
    Image,    ///< an RGBA32F image of view positions and triangle ids (+1, 0 = none): the mesh edges
};

/** One drawn type as the builder takes it, in the stroke stage's input order. */
struct StrokePointInput {
    StrokePointSource source = StrokePointSource::Surface;
    const LineSkeleton* skeleton = nullptr; ///< for Skeleton: the type's skeleton (its `surface` filled)
    cv::Mat image;                          ///< for Image: CV_32FC4 at the data size
    bool visible = true;                    ///< false for the hidden-lines types
};

struct StrokePointSetup {
    const DrawnStrokes* drawn = nullptr;  ///< the stroke stage's kept strokes
    std::vector<StrokePointInput> inputs; ///< one per drawn.inputs
    cv::Mat depth;                        ///< CV_32FC1 linear view depth at the data size, 0 off the model
    cv::Mat triangleIds;                  ///< CV_32FC1 or CV_32SC1/CV_32UC1 global triangle index + 1, or empty
    const Camera* camera = nullptr;       ///< the still's camera (output size)
    /** The scene's triangle numbering (scene/MeshLabels.h), which the triangleId field and the mesh-edge point images
     *  use too; null: no point names its mesh or triangle. */
    const TriangleNumbering* numbering = nullptr;
    /** The scene: a mesh edge's point is clamped to its triangle's nearest side (see the file comment); null: not. */
    const Scene* scene = nullptr;
};

/** One point of a stroke. */
struct StrokePointRecord {
    double x = 0.0, y = 0.0;         ///< output pixels, x right, y down, pixel (0, 0)'s centre at (0, 0)
    std::optional<glm::dvec3> world; ///< world coordinates (Scene::origin added back); none: no surface there
    int mesh = 0;                    ///< its mesh id (scene/MeshNumbering.h number + 1), 0 when not known
    std::int64_t triangle = -1;      ///< global triangle index over the meshes in Scene order, -1 when not known
};

struct StrokeRecord {
    std::string type;
    bool visible = true;
    bool closed = false;
    std::vector<StrokePointRecord> points;
};

/** Every kept stroke in the stroke stage's order (the dashes of the hidden types each a stroke of their own), values
 *  rounded as the file writes them: x and y to 1e-4 pixels, world to 7 significant digits, and a point equal in all
 *  of them (and its mesh and triangle) to the one before it written once. Throws
 *  std::invalid_argument naming the argument when `drawn` or `camera` is null, an input is missing what its source
 *  needs, or an image is not at the data size. */
std::vector<StrokeRecord> strokeRecords(const StrokePointSetup& setup);

} // namespace inkgraph
