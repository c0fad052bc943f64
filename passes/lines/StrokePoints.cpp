#include "passes/lines/StrokePoints.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Two model pixels of the 3 x 3 around a point belong to one surface unless their depths differ by more than this
 *  share of the nearer (the contour's default depth jump, postfx/Contour.h). */
constexpr double kNearSurfaceJump = 0.05;

/** A mesh edge's point whose projection lies farther than this from its stroke point (in data pixels) belongs to
 *  another edge: GL puts an edge's end pixel's vertex up to about 0.7 data pixels off the pixel centre. */
constexpr double kFarEdgePointDataPixels = 1.5;

double roundedPixels(double value) { return std::round(value * 1e4) / 1e4; }

/** 7 significant digits, so the file's shortest round-trip numbers stay short (float precision). */
double roundedSignificant(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.7g", value);
    return std::strtod(text, nullptr);
}

/** A world point rounded to 7 significant digits of its offset from the scene origin (near the model), not of its
 *  world coordinates: a model placed 1e5 or 1e7 units from 0 keeps float precision relative to its own size. */
glm::dvec3 roundedWorld(const glm::dvec3& world, const glm::dvec3& origin) {
    const glm::dvec3 local = world - origin;
    return origin + glm::dvec3(roundedSignificant(local.x), roundedSignificant(local.y), roundedSignificant(local.z));
}

/** The global triangle index of a mesh's (loaded) triangle; -1 when either is not known. */
std::int64_t globalTriangle(const StrokePointSetup& setup, int mesh, long triangle) {
    if (setup.numbering == nullptr || mesh < 0 || triangle < 0) return -1;
    return std::int64_t(setup.numbering->global(std::size_t(mesh), std::size_t(triangle)));
}

/** The mesh id (number + 1, scene/MeshNumbering.h) a global triangle index lies in, 0 when none. */
int meshOfTriangle(const StrokePointSetup& setup, std::int64_t triangle) {
    if (triangle < 0 || setup.numbering == nullptr) return 0;
    const std::optional<std::size_t> mesh = setup.numbering->meshNumberOf(std::size_t(triangle));
    return mesh ? int(*mesh) + 1 : 0;
}

/** A triangle id image's value (global index + 1, 0 = none) at a pixel, as a global index or -1. */
std::int64_t triangleAt(const cv::Mat& ids, int row, int col) {
    if (ids.empty()) return -1;
    double value = 0.0;
    switch (ids.depth()) {
    case CV_32F: value = ids.at<float>(row, col); break;
    case CV_32S: value = double(std::uint32_t(ids.at<std::int32_t>(row, col))); break;
    default: return -1;
    }
    return value >= 1.0 ? std::int64_t(std::llround(value)) - 1 : -1;
}

/** Maps points between data pixels, output pixels and the world. */
class Projection {
public:
    Projection(const Camera& camera, int supersample)
        : mScale(supersample), mIntrinsics(camera.openCvIntrinsics()), mExtrinsics(camera.openCvExtrinsics()),
          mWorldFromView(glm::inverse(camera.worldViewMatrix())) {}

    /** Data pixels (centres at integers) to output pixels (the same convention). */
    glm::dvec2 outputPixel(cv::Point2f data) const {
        return {(double(data.x) + 0.5) / mScale - 0.5, (double(data.y) + 0.5) / mScale - 0.5};
    }
    /** The world point on the ray through output pixel `pixel` at linear view depth `depth`: R^T (depth K^-1 p - t). */
    glm::dvec3 onRay(glm::dvec2 pixel, double depth) const {
        const glm::dvec3 camera = depth * glm::dvec3((pixel.x - mIntrinsics[2][0]) / mIntrinsics[0][0],
                                                     (pixel.y - mIntrinsics[2][1]) / mIntrinsics[1][1], 1.0);
        const glm::dmat3 rotation(mExtrinsics[0], mExtrinsics[1], mExtrinsics[2]);
        return glm::transpose(rotation) * (camera - mExtrinsics[3]);
    }
    glm::dvec3 fromView(const glm::dvec3& view) const { return glm::dvec3(mWorldFromView * glm::dvec4(view, 1.0)); }
    /** A world point's output pixel: K (R X + t), divided by its depth. */
    glm::dvec2 toPixel(const glm::dvec3& world) const {
        const glm::dmat3 rotation(mExtrinsics[0], mExtrinsics[1], mExtrinsics[2]);
        const glm::dvec3 camera = mIntrinsics * (rotation * world + mExtrinsics[3]);
        return glm::dvec2(camera) / camera.z;
    }

private:
    double mScale;
    glm::dmat3 mIntrinsics;
    glm::dmat4x3 mExtrinsics;
    glm::dmat4 mWorldFromView;
};

/** The skeleton's points grouped by pixel, to find the sample a stroke point came from. */
class PointsByPixel {
public:
    explicit PointsByPixel(const LineSkeleton& skeleton) : mSkeleton(skeleton) {
        const int cols = skeleton.mask.cols;
        for (std::size_t index = 0; index < skeleton.points.size(); ++index) {
            const cv::Point2f position = skeleton.points[index].position;
            mKeyed.emplace_back(std::int64_t(std::lround(position.y)) * cols + std::lround(position.x), index);
        }
        std::sort(mKeyed.begin(), mKeyed.end());
    }
    /** The index of the point of `pixel` (or of its 3 x 3) nearest to `position`, or -1. */
    long nearest(cv::Point pixel, cv::Point2f position) const {
        long best = -1;
        double bestDistance = std::numeric_limits<double>::infinity();
        const int cols = mSkeleton.mask.cols;
        for (int ring = 0; ring <= 1 && best < 0; ++ring)
            for (int dy = -ring; dy <= ring; ++dy)
                for (int dx = -ring; dx <= ring; ++dx) {
                    if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
                    // Outside the image a key would wrap to the other side's pixel of the next or previous row.
                    if (pixel.x + dx < 0 || pixel.x + dx >= cols || pixel.y + dy < 0 ||
                        pixel.y + dy >= mSkeleton.mask.rows)
                        continue;
                    const std::int64_t key = std::int64_t(pixel.y + dy) * cols + (pixel.x + dx);
                    auto it = std::lower_bound(mKeyed.begin(), mKeyed.end(), std::make_pair(key, std::size_t(0)));
                    for (; it != mKeyed.end() && it->first == key; ++it) {
                        const double distance = cv::norm(mSkeleton.points[it->second].position - position);
                        if (distance < bestDistance) {
                            bestDistance = distance;
                            best = long(it->second);
                        }
                    }
                }
        return best;
    }

private:
    const LineSkeleton& mSkeleton;
    std::vector<std::pair<std::int64_t, std::size_t>> mKeyed;
};

/** The G-buffer surface under a data-pixel point (the file comment's rule, over the (2 reach + 1)^2 pixels around it),
 *  or nothing. */
std::optional<StrokePointRecord> surfaceUnder(const StrokePointSetup& setup, const Projection& projection,
                                              cv::Point2f data, int reach) {
    const cv::Mat& depth = setup.depth;
    const int col = int(std::lround(data.x)), row = int(std::lround(data.y));
    float nearest = std::numeric_limits<float>::infinity();
    for (int r = row - reach; r <= row + reach; ++r)
        for (int c = col - reach; c <= col + reach; ++c)
            if (r >= 0 && c >= 0 && r < depth.rows && c < depth.cols && depth.at<float>(r, c) > 0.0f)
                nearest = std::min(nearest, depth.at<float>(r, c));
    if (!std::isfinite(nearest)) return std::nullopt;
    cv::Point chosen(-1, -1);
    double chosenDistance = std::numeric_limits<double>::infinity();
    for (int r = row - reach; r <= row + reach; ++r)
        for (int c = col - reach; c <= col + reach; ++c) {
            if (r < 0 || c < 0 || r >= depth.rows || c >= depth.cols) continue;
            const float z = depth.at<float>(r, c);
            if (!(z > 0.0f) || z > nearest * (1.0 + kNearSurfaceJump)) continue;
            const double distance = std::hypot(c - double(data.x), r - double(data.y));
            if (distance < chosenDistance) {
                chosenDistance = distance;
                chosen = {c, r};
            }
        }
    StrokePointRecord point;
    point.world = projection.onRay(projection.outputPixel(data), double(depth.at<float>(chosen)));
    point.triangle = triangleAt(setup.triangleIds, chosen.y, chosen.x);
    point.mesh = meshOfTriangle(setup, point.triangle);
    return point;
}

/** The drawn pixel of a mesh-edge point image nearest to a data-pixel point (its own pixel first), or nothing. */
std::optional<StrokePointRecord> edgePointAt(const StrokePointSetup& setup, const Projection& projection,
                                             const cv::Mat& image, cv::Point pixel, cv::Point2f data) {
    cv::Point chosen(-1, -1);
    double chosenDistance = std::numeric_limits<double>::infinity();
    for (int r = pixel.y - 1; r <= pixel.y + 1; ++r)
        for (int c = pixel.x - 1; c <= pixel.x + 1; ++c) {
            if (r < 0 || c < 0 || r >= image.rows || c >= image.cols) continue;
            const cv::Vec4f& value = image.at<cv::Vec4f>(r, c);
            if (!(value[2] < 0.0f)) continue; // nothing drawn: view z is negative in front of the eye
            const double distance = (r == pixel.y && c == pixel.x) ? -1.0 : std::hypot(c - data.x, r - data.y);
            if (distance < chosenDistance) {
                chosenDistance = distance;
                chosen = {c, r};
            }
        }
    if (chosen.x < 0) return std::nullopt;
    const cv::Vec4f& value = image.at<cv::Vec4f>(chosen);
    StrokePointRecord point;
    point.world = projection.fromView({value[0], value[1], value[2]});
    point.triangle = value[3] >= 1.0f ? std::int64_t(std::llround(value[3])) - 1 : -1;
    point.mesh = meshOfTriangle(setup, point.triangle);
    return point;
}

/** The point of segment a-b nearest `point`. */
glm::dvec3 nearestOnSegment(const glm::dvec3& point, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 along = b - a;
    const double lengthSquared = glm::dot(along, along);
    const double t = lengthSquared > 0.0 ? std::clamp(glm::dot(point - a, along) / lengthSquared, 0.0, 1.0) : 0.0;
    return a + t * along;
}

/** A mesh edge's point clamped to the nearest side of its triangle (the file comment says why). */
void clampToTriangle(StrokePointRecord& point, const StrokePointSetup& setup) {
    if (setup.scene == nullptr || setup.numbering == nullptr || !point.world || point.triangle < 0) return;
    const std::optional<TriangleNumbering::Loaded> loaded = setup.numbering->loaded(std::size_t(point.triangle));
    if (!loaded) return;
    const Mesh& mesh = setup.scene->meshes[loaded->mesh];
    const glm::uvec3 corners = mesh.triangles[loaded->triangle];
    const glm::dvec3 origin = setup.camera->origin;
    const glm::dvec3 onMesh = *point.world - origin;
    glm::dvec3 best = onMesh;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int side = 0; side < 3; ++side) {
        const glm::dvec3 nearest = nearestOnSegment(onMesh, glm::dvec3(mesh.positions[corners[side]]),
                                                    glm::dvec3(mesh.positions[corners[(side + 1) % 3]]));
        if (glm::length(nearest - onMesh) < bestDistance) {
            bestDistance = glm::length(nearest - onMesh);
            best = nearest;
        }
    }
    point.world = best + origin;
}

/** Points left without a 3-D point (a bridge over a gap, a dash's cut end: the stroke stage's own points between two
 *  of its pixels) of a mesh-space stroke take the one on the 3-D line through their two nearest neighbours that have
 *  one (one on each side when there are), at the share of the way their (x, y) lies between the neighbours'; the
 *  mesh and triangle of the nearer. */
void fillBridges(std::vector<StrokePointRecord>& points, const std::vector<bool>& found) {
    std::vector<long> known;
    for (std::size_t index = 0; index < points.size(); ++index)
        if (found[index]) known.push_back(long(index));
    if (known.empty()) return;
    std::size_t next = 0;
    for (std::size_t index = 0; index < points.size(); ++index) {
        if (found[index]) continue;
        while (next < known.size() && known[next] < long(index)) ++next;
        long first = -1, second = -1; // the nearer first
        if (next > 0 && next < known.size()) {
            first = known[next - 1];
            second = known[next];
            if (known[next] - long(index) < long(index) - known[next - 1]) std::swap(first, second);
        } else if (next == 0) {
            first = known[0];
            second = known.size() > 1 ? known[1] : -1;
        } else {
            first = known[next - 1];
            second = next > 1 ? known[next - 2] : -1;
        }
        StrokePointRecord& point = points[index];
        const StrokePointRecord& nearer = points[std::size_t(first)];
        point.mesh = nearer.mesh;
        point.triangle = nearer.triangle;
        point.world = nearer.world;
        if (second < 0) continue;
        const StrokePointRecord& other = points[std::size_t(second)];
        const glm::dvec2 from(nearer.x, nearer.y), to(other.x, other.y);
        const double lengthSquared = glm::dot(to - from, to - from);
        if (!(lengthSquared > 0.0)) continue;
        const double t = glm::dot(glm::dvec2(point.x, point.y) - from, to - from) / lengthSquared;
        point.world = *nearer.world + t * (*other.world - *nearer.world);
    }
}

/** A mesh edge's fragment holds the point of its edge nearest its pixel centre (GL interpolates along the line), and
 *  an end point's pixel the vertex itself, anywhere in the pixel. A point whose stroke neighbours lie on the same edge
 *  (the same triangle) slides along it (the direction between the neighbours' points) to where it projects nearest
 *  the stroke point, by one Gauss-Newton step, at most half the neighbours' span either way: still on the edge, and
 *  off (x, y) only by the pixel centre's distance across the line. Only neighbours found on the drawn edge count
 *  (`found`): a bridged one (a dash's cut end) holds a guess, and sliding by it took a point 3-6 px off. */
void slideAlongEdges(std::vector<StrokePointRecord>& points, const std::vector<bool>& found,
                     const Projection& projection) {
    const std::vector<StrokePointRecord> unslid = points;
    for (std::size_t index = 1; index + 1 < points.size(); ++index) {
        if (!found[index - 1] || !found[index + 1]) continue;
        const StrokePointRecord &before = unslid[index - 1], &after = unslid[index + 1];
        StrokePointRecord& point = points[index];
        if (!before.world || !after.world || !point.world) continue;
        if (point.triangle < 0 || before.triangle != point.triangle || after.triangle != point.triangle) continue;
        const glm::dvec3 direction = 0.5 * (*after.world - *before.world);
        // Only along a straight run: at a corner (two edges of one triangle) the neighbours' direction is neither.
        if (glm::length(glm::cross(direction, *point.world - *before.world)) > 1e-3 * glm::dot(direction, direction))
            continue;
        const glm::dvec2 at = projection.toPixel(*point.world);
        const glm::dvec2 slope = projection.toPixel(*point.world + 1e-3 * direction) - at;
        const double slopeSquared = glm::dot(slope, slope);
        if (!(slopeSquared > 0.0)) continue;
        const double step = 1e-3 * glm::dot(glm::dvec2(point.x, point.y) - at, slope) / slopeSquared;
        point.world = *point.world + std::clamp(step, -0.5, 0.5) * direction;
    }
}

} // namespace

std::vector<StrokeRecord> strokeRecords(const StrokePointSetup& setup) {
    if (setup.drawn == nullptr) throw std::invalid_argument("strokeRecords(): 'drawn' is null");
    if (setup.camera == nullptr) throw std::invalid_argument("strokeRecords(): 'camera' is null");
    const DrawnStrokes& drawn = *setup.drawn;
    if (setup.inputs.size() != drawn.inputs.size())
        throw std::invalid_argument("strokeRecords(): 'inputs' must hold one entry per drawn type");
    const cv::Size dataSize(setup.camera->width * drawn.supersample, setup.camera->height * drawn.supersample);
    if (setup.depth.type() != CV_32FC1 || setup.depth.size() != dataSize)
        throw std::invalid_argument("strokeRecords(): 'depth' must be CV_32FC1 at the data size");
    if (!setup.triangleIds.empty() && setup.triangleIds.size() != dataSize)
        throw std::invalid_argument("strokeRecords(): 'triangleIds' must be at the data size");
    std::vector<std::optional<PointsByPixel>> byPixel(setup.inputs.size());
    for (std::size_t index = 0; index < setup.inputs.size(); ++index) {
        const StrokePointInput& input = setup.inputs[index];
        const std::string& type = drawn.inputs[index].type;
        if (input.source == StrokePointSource::Skeleton) {
            if (input.skeleton == nullptr || input.skeleton->surface.size() != input.skeleton->points.size())
                throw std::invalid_argument("strokeRecords(): '" + type + "' has no skeleton with surface points");
            byPixel[index].emplace(*input.skeleton);
        }
        if (input.source == StrokePointSource::Image &&
            (input.image.type() != CV_32FC4 || input.image.size() != dataSize))
            throw std::invalid_argument("strokeRecords(): '" + type +
                                        "' point image must be CV_32FC4 at the data size");
    }

    const Projection projection(*setup.camera, drawn.supersample);
    std::vector<StrokeRecord> records;
    for (const Stroke& stroke : drawn.strokes.strokes) {
        if (!stroke.kept || stroke.layer < 0 || std::size_t(stroke.layer) >= setup.inputs.size()) continue;
        const StrokePointInput& input = setup.inputs[std::size_t(stroke.layer)];
        // A GL band (outline, silhouette) is drawn around the model's outline: its middle may lie half its width off
        // the model, where the nearest surface is looked for.
        const StrokeInput& drawnInput = drawn.inputs[std::size_t(stroke.layer)];
        // Half the band's width and a pixel, both in output pixels, as data pixels.
        const int reach =
            drawnInput.skeleton ? 1 : int(std::ceil((0.5 * drawnInput.widthPixels + 1.0) * drawn.supersample));
        StrokeRecord record;
        record.type = drawn.inputs[std::size_t(stroke.layer)].type;
        record.visible = input.visible;
        record.closed = stroke.closed;
        std::vector<bool> found(stroke.points.size(), false);
        for (std::size_t index = 0; index < stroke.points.size(); ++index) {
            const cv::Point2f data = stroke.points[index].position;
            const cv::Point pixel = index < stroke.pixels.size() ? stroke.pixels[index] : cv::Point(-1, -1);
            std::optional<StrokePointRecord> point;
            switch (input.source) {
            case StrokePointSource::Surface: point = surfaceUnder(setup, projection, data, reach); break;
            case StrokePointSource::Skeleton:
                if (pixel.x >= 0) {
                    const long sample = byPixel[std::size_t(stroke.layer)]->nearest(pixel, data);
                    if (sample >= 0) {
                        const SurfacePoint& surface = input.skeleton->surface[std::size_t(sample)];
                        point.emplace();
                        point->world = glm::dvec3(surface.position.x, surface.position.y, surface.position.z) +
                                       setup.camera->origin;
                        point->triangle = globalTriangle(setup, surface.mesh, surface.triangle);
                        point->mesh = surface.mesh >= 0 ? surface.mesh + 1 : 0;
                    }
                }
                break;
            case StrokePointSource::Image:
                if (pixel.x >= 0) point = edgePointAt(setup, projection, input.image, pixel, data);
                if (point) {
                    // The drawn pixel may hold another edge than the stroke's (where edges cross or meet within a
                    // pixel), whose point projects far from (x, y): such a point is left to the bridging below.
                    clampToTriangle(*point, setup);
                    const glm::dvec2 output = projection.outputPixel(data);
                    if (glm::length(projection.toPixel(*point->world) - output) >
                        kFarEdgePointDataPixels / drawn.supersample)
                        point.reset();
                }
                break;
            }
            StrokePointRecord recordPoint = point.value_or(StrokePointRecord{});
            found[index] = point.has_value();
            const glm::dvec2 output = projection.outputPixel(data);
            recordPoint.x = output.x;
            recordPoint.y = output.y;
            record.points.push_back(recordPoint);
        }
        if (input.source != StrokePointSource::Surface) fillBridges(record.points, found);
        if (input.source == StrokePointSource::Image) {
            slideAlongEdges(record.points, found, projection);
            for (StrokePointRecord& point : record.points) clampToTriangle(point, setup);
        }
        // A point left farther from (x, y) than a found point may lie is left without one: a bridged point whose
        // neighbours' line passes far from it (a stroke's end that the stroke stage drew on into another type's line
        // took its last point's world, 3-7 px from where it was drawn), or a mesh edge's point the steps above moved
        // there (a skeleton's own points are where their samples are drawn).
        for (std::size_t index = 0; index < record.points.size(); ++index) {
            StrokePointRecord& point = record.points[index];
            if (!point.world || (found[index] && input.source != StrokePointSource::Image)) continue;
            if (glm::length(projection.toPixel(*point.world) - glm::dvec2(point.x, point.y)) >
                kFarEdgePointDataPixels / drawn.supersample)
                point = StrokePointRecord{point.x, point.y, std::nullopt, 0, -1};
        }
        for (StrokePointRecord& point : record.points) {
            point.x = roundedPixels(point.x);
            point.y = roundedPixels(point.y);
            if (point.world) point.world = roundedWorld(*point.world, setup.camera->origin);
        }
        // Two consecutive points may come out the same (two of the stroke stage's points at one spot, or rounded to
        // one): written twice they are a segment of no length, on which a reader's tangent divides by zero.
        const auto same = [](const StrokePointRecord& a, const StrokePointRecord& b) {
            return a.x == b.x && a.y == b.y && a.world == b.world && a.mesh == b.mesh && a.triangle == b.triangle;
        };
        record.points.erase(std::unique(record.points.begin(), record.points.end(), same), record.points.end());
        // A closed stroke does not repeat its first point (docs/datasets.md), and one of two points or fewer encloses
        // nothing: it is the open stroke between them (a reader drawing it closed would go there and back).
        if (record.closed && record.points.size() > 1 && same(record.points.front(), record.points.back()))
            record.points.pop_back();
        record.closed = record.closed && record.points.size() > 2;
        records.push_back(std::move(record));
    }
    return records;
}

} // namespace inkgraph
