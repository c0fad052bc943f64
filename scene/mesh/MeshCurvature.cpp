#include "scene/mesh/MeshCurvature.h"

#include "scene/MessageText.h"
#include "scene/mesh/MeshOps.h"
#include "scene/mesh/ParallelRanges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

/** An LDL^T pivot below this times the largest diagonal entry of the normal matrix is singular: the face's edges do
 *  not span the plane well enough to fit anything (a needle), and a fit there would be noise. */
constexpr double kSingularPivotRelative = 1e-10;

/** Solves the symmetric positive semi-definite system a x = b in place by LDL^T; false, leaving x untouched, when a
 *  pivot is not clearly positive. Small fixed sizes only (3 and 4 here). */
template <std::size_t N>
bool solveSymmetric(std::array<std::array<double, N>, N> a, std::array<double, N> b, std::array<double, N>& x) {
    double largestDiagonal = 0.0;
    for (std::size_t i = 0; i < N; ++i) largestDiagonal = std::max(largestDiagonal, a[i][i]);
    if (!(largestDiagonal > 0.0)) return false;
    const double minimumPivot = kSingularPivotRelative * largestDiagonal;
    // Factor in place: the lower triangle holds L (unit diagonal implied), the diagonal D.
    for (std::size_t i = 0; i < N; ++i) {
        for (std::size_t k = 0; k < i; ++k) a[i][i] -= a[i][k] * a[i][k] * a[k][k];
        if (!(a[i][i] > minimumPivot)) return false;
        for (std::size_t j = i + 1; j < N; ++j) {
            for (std::size_t k = 0; k < i; ++k) a[j][i] -= a[j][k] * a[i][k] * a[k][k];
            a[j][i] /= a[i][i];
        }
    }
    for (std::size_t i = 0; i < N; ++i)
        for (std::size_t k = 0; k < i; ++k) b[i] -= a[i][k] * b[k];
    for (std::size_t i = 0; i < N; ++i) b[i] /= a[i][i];
    for (std::size_t i = N; i-- > 0;)
        for (std::size_t k = i + 1; k < N; ++k) b[i] -= a[k][i] * b[k];
    x = b;
    return true;
}

/** Turns the tangent frame (u, v) of a vertex with unit normal `from` about the axis from x to, so that it becomes
 *  a frame of the plane with unit normal `to` (Rodrigues' formula with the unnormalised axis k = from x to, whose
 *  length is the sine). Opposite normals: a half turn about u. */
void rotateFrame(glm::dvec3& u, glm::dvec3& v, const glm::dvec3& from, const glm::dvec3& to) {
    const double cosine = glm::dot(from, to);
    if (cosine <= -1.0 + 1e-12) {
        v = -v;
        return;
    }
    const glm::dvec3 axis = glm::cross(from, to);
    const double scale = 1.0 / (1.0 + cosine);
    auto rotate = [&](const glm::dvec3& x) {
        return x * cosine + glm::cross(axis, x) + axis * (glm::dot(axis, x) * scale);
    };
    u = rotate(u);
    v = rotate(v);
}

/** Some unit vector perpendicular to unit `normal`: crossed with the coordinate axis it is least aligned with. */
glm::dvec3 perpendicularTo(const glm::dvec3& normal) {
    const glm::dvec3 magnitude = glm::abs(normal);
    const glm::dvec3 axis = magnitude.x <= magnitude.y && magnitude.x <= magnitude.z ? glm::dvec3(1, 0, 0)
                            : magnitude.y <= magnitude.z                             ? glm::dvec3(0, 1, 0)
                                                                                     : glm::dvec3(0, 0, 1);
    return glm::normalize(glm::cross(normal, axis));
}

/** A symmetric 2-tensor in some orthonormal frame: [[xx, xy], [xy, yy]]. */
struct Tensor2 {
    double xx = 0.0, xy = 0.0, yy = 0.0;
};

/** The tensor's value on the pair (p, q) of face-frame vectors. */
double evaluate(const Tensor2& tensor, const glm::dvec2& p, const glm::dvec2& q) {
    return tensor.xx * p.x * q.x + tensor.xy * (p.x * q.y + p.y * q.x) + tensor.yy * p.y * q.y;
}

/** A symmetric trilinear form on the plane, (a, b, c, d) = (C_xxx, C_xxy, C_xyy, C_yyy). */
double evaluate(const glm::dvec4& c, const glm::dvec2& x, const glm::dvec2& y, const glm::dvec2& z) {
    return c.x * x.x * y.x * z.x + c.y * (x.x * y.x * z.y + x.x * y.y * z.x + x.y * y.x * z.x) +
           c.z * (x.x * y.y * z.y + x.y * y.x * z.y + x.y * y.y * z.x) + c.w * x.y * y.y * z.y;
}

/** One usable face's geometry, shared by the steps. */
struct FaceFrame {
    std::array<glm::dvec3, 3> edges; ///< edges[i] is opposite corner i, running from corner i+1 to corner i+2
    glm::dvec3 normal;               ///< unit
    glm::dvec3 tangent;              ///< unit, along edges[2] (corner 0 to corner 1)
    glm::dvec3 bitangent;            ///< normal x tangent
    glm::dvec2 inPlane(const glm::dvec3& x) const { return {glm::dot(x, tangent), glm::dot(x, bitangent)}; }
};

/** The Gaussian neighbourhoods of the vertices over the mesh's edges: for a vertex, every vertex reached from it by
 *  edges through vertices within 3 sigma of it, with weight exp(-d^2 / (2 sigma^2)) x point area (rtsc's
 *  diffuse_vert_field). A flood rather than a distance query, so a thin part's other side is not averaged in. The
 *  adjacency is shared; each thread floods with a Flood of its own. */
class GaussianNeighbourhoods {
public:
    GaussianNeighbourhoods(const std::vector<glm::dvec3>& positions, const std::vector<glm::uvec3>& triangles,
                           const std::vector<double>& pointAreas, double sigma)
        : mPositions(positions), mPointAreas(pointAreas), mReachSquared(9.0 * sigma * sigma),
          mInverseTwoSigmaSquared(0.5 / (sigma * sigma)) {
        // Compressed adjacency: each vertex's neighbours across the faces' edges (a neighbour may repeat; the flood
        // marks it once).
        std::vector<std::uint32_t> degree(positions.size() + 1, 0);
        for (const glm::uvec3& t : triangles)
            for (int corner = 0; corner < 3; ++corner) degree[t[corner] + 1] += 2;
        for (std::size_t i = 1; i < degree.size(); ++i) degree[i] += degree[i - 1];
        mFirst = degree;
        mNeighbours.resize(mFirst.back());
        std::vector<std::uint32_t> next(mFirst.begin(), mFirst.end() - 1);
        for (const glm::uvec3& t : triangles)
            for (int corner = 0; corner < 3; ++corner) {
                const std::uint32_t vertex = t[corner];
                mNeighbours[next[vertex]++] = t[(corner + 1) % 3];
                mNeighbours[next[vertex]++] = t[(corner + 2) % 3];
            }
    }

    /** One thread's floods over the neighbourhoods: its marks and its queue. */
    class Flood {
    public:
        explicit Flood(const GaussianNeighbourhoods& neighbourhoods)
            : mOwner(neighbourhoods), mMark(neighbourhoods.mPositions.size(), kUnmarked) {}

        /** Calls visit(neighbour, weight) for `vertex` itself and every vertex of its neighbourhood, nearest by edges
         *  first (the same order on any thread). */
        template <typename Visit>
        void forEach(std::uint32_t vertex, Visit visit) {
            const GaussianNeighbourhoods& n = mOwner;
            const glm::dvec3 centre = n.mPositions[vertex];
            mQueue.clear();
            mQueue.push_back(vertex);
            mMark[vertex] = vertex;
            for (std::size_t head = 0; head < mQueue.size(); ++head) {
                const std::uint32_t current = mQueue[head];
                const glm::dvec3 offset = n.mPositions[current] - centre;
                visit(current,
                      std::exp(-glm::dot(offset, offset) * n.mInverseTwoSigmaSquared) * n.mPointAreas[current]);
                for (std::uint32_t k = n.mFirst[current]; k < n.mFirst[current + 1]; ++k) {
                    const std::uint32_t neighbour = n.mNeighbours[k];
                    if (mMark[neighbour] == vertex) continue;
                    mMark[neighbour] = vertex;
                    const glm::dvec3 away = n.mPositions[neighbour] - centre;
                    if (glm::dot(away, away) <= n.mReachSquared) mQueue.push_back(neighbour);
                }
            }
        }

    private:
        static constexpr std::uint32_t kUnmarked = 0xffffffffu;
        const GaussianNeighbourhoods& mOwner;
        std::vector<std::uint32_t> mMark; ///< the vertex whose flood last reached it
        std::vector<std::uint32_t> mQueue;
    };

    /** About how many vertices the floods of every vertex visit in all: the mean of up to kSampledFloods floods from
     *  vertices spread evenly over the index range, times the vertex count. What a smoothing costs, known before it
     *  is spent (a flood of a few percent of a large mesh from each of its vertices runs for hours). */
    double estimatedVisits() const {
        const std::size_t count = mPositions.size();
        if (count == 0) return 0.0;
        const std::size_t samples = std::min(count, kSampledFloods);
        Flood flood(*this);
        double visited = 0.0;
        for (std::size_t sample = 0; sample < samples; ++sample)
            flood.forEach(std::uint32_t(sample * count / samples), [&](std::uint32_t, double) { visited += 1.0; });
        return visited / double(samples) * double(count);
    }

    std::size_t vertexCount() const { return mPositions.size(); }

    /** The same for another sigma, on the same adjacency. */
    double estimatedVisits(double sigma) {
        const double reach = mReachSquared, inverse = mInverseTwoSigmaSquared;
        mReachSquared = 9.0 * sigma * sigma;
        mInverseTwoSigmaSquared = 0.5 / (sigma * sigma);
        const double visits = estimatedVisits();
        mReachSquared = reach;
        mInverseTwoSigmaSquared = inverse;
        return visits;
    }

    /** Calls perVertex(flood, vertex) for every vertex, split over the cores (parallelRanges()), each thread flooding
     *  with its own Flood: each vertex's sum is the same whatever the split, as long as perVertex writes its vertex
     *  only. */
    template <typename PerVertex>
    void forEveryVertex(PerVertex perVertex) const {
        parallelRanges(mPositions.size(), kVerticesPerThreadAtLeast,
                       [&](std::size_t, std::size_t begin, std::size_t end) {
                           Flood flood(*this);
                           for (std::size_t vertex = begin; vertex < end; ++vertex)
                               perVertex(flood, std::uint32_t(vertex));
                       });
    }

private:
    /** A thread's share of the vertices is worth its start (tens of microseconds) and its marks (4 bytes a vertex)
     *  only with a few thousand floods in it. */
    static constexpr std::size_t kVerticesPerThreadAtLeast = 4096;
    static constexpr std::size_t kSampledFloods = 64;

    const std::vector<glm::dvec3>& mPositions;
    const std::vector<double>& mPointAreas;
    double mReachSquared;
    double mInverseTwoSigmaSquared;
    std::vector<std::uint32_t> mFirst;
    std::vector<std::uint32_t> mNeighbours;
};

/** The tangent vectors (x, y) of the frame `to` (unit normal toNormal) expressed in the frame (u, v) of a vertex
 *  with unit normal fromNormal, once that frame is rotated into to's plane: the coordinates that carry a tensor
 *  from there to here. */
std::array<glm::dvec2, 2> frameChange(glm::dvec3 u, glm::dvec3 v, const glm::dvec3& fromNormal, const glm::dvec3& x,
                                      const glm::dvec3& y, const glm::dvec3& toNormal) {
    rotateFrame(u, v, fromNormal, toNormal);
    return {glm::dvec2(glm::dot(x, u), glm::dot(x, v)), glm::dvec2(glm::dot(y, u), glm::dot(y, v))};
}

/** The checks both computeMeshCurvature()s make before anything else (positions before a weld reads them). */
void checkCurvatureInput(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                         double smoothing) {
    if (!std::isfinite(smoothing) || smoothing < 0.0)
        throw std::invalid_argument("computeMeshCurvature(): 'smoothing' must be finite and >= 0, got " +
                                    std::to_string(smoothing));
    for (std::size_t i = 0; i < positions.size(); ++i)
        if (!(std::isfinite(positions[i].x) && std::isfinite(positions[i].y) && std::isfinite(positions[i].z)))
            throw std::invalid_argument("computeMeshCurvature(): 'positions' has a non-finite coordinate at vertex " +
                                        std::to_string(i));
    for (std::size_t face = 0; face < triangles.size(); ++face)
        for (int corner = 0; corner < 3; ++corner)
            if (triangles[face][corner] >= positions.size())
                throw std::out_of_range("computeMeshCurvature(): 'triangles' face " + std::to_string(face) +
                                        " uses vertex " + std::to_string(triangles[face][corner]) + " but there are " +
                                        std::to_string(positions.size()) + " positions");
}

} // namespace

namespace {

/** One mesh of an estimate: its welded positions and faces, and the floods over them (which refer to both, so it
 *  stays where it is made). */
struct EstimatedMesh {
    EstimatedMesh(std::vector<glm::dvec3> weldedPositions, std::vector<glm::uvec3> weldedTriangles, double smoothing)
        : positions(std::move(weldedPositions)), triangles(std::move(weldedTriangles)), noAreas(positions.size(), 0.0),
          floods(positions, triangles, noAreas, smoothing) {}
    std::vector<glm::dvec3> positions;
    std::vector<glm::uvec3> triangles;
    std::vector<double> noAreas; ///< the estimate counts visits, it weighs none
    GaussianNeighbourhoods floods;
};

/** The estimated visits at `sigma` of the meshes whose windows are wide (a mean window over kMaxCostlyWindowShare of
 *  the mesh), summed, with their vertices: a fine mesh at a narrow smoothing is slow, not refused. */
std::pair<double, std::size_t> wideVisits(const std::vector<GaussianNeighbourhoods*>& meshes, double sigma) {
    double visits = 0.0;
    std::size_t vertices = 0;
    for (GaussianNeighbourhoods* mesh : meshes) {
        const double count = double(mesh->vertexCount());
        const double meshVisits = mesh->estimatedVisits(sigma);
        if (meshVisits > count * count * kMaxCostlyWindowShare) {
            visits += meshVisits;
            vertices += mesh->vertexCount();
        }
    }
    return {visits, vertices};
}

/** Throws SmoothingTooCostlyError when the wide meshes' windows at `smoothing` would cost more than
 *  kMaxSmoothingVisits in all, naming the largest smoothing that would not. */
void requireAffordableSmoothing(const std::vector<GaussianNeighbourhoods*>& meshes, double smoothing) {
    const auto [visits, vertices] = wideVisits(meshes, smoothing);
    if (!(visits > kMaxSmoothingVisits)) return;
    // The largest smoothing not refused, for the message, by halving the interval on a log scale (visits grow with
    // the window's area until it holds the whole mesh, so no formula gives it).
    const auto refused = [&](double sigma) { return wideVisits(meshes, sigma).first > kMaxSmoothingVisits; };
    double within = smoothing * 1e-3, beyond = smoothing;
    if (refused(within)) {
        within = 0.0;
    } else {
        for (int step = 0; step < 12; ++step) {
            const double middle = std::sqrt(within * beyond);
            (refused(middle) ? beyond : within) = middle;
        }
    }
    throw SmoothingTooCostlyError(smoothing, visits, vertices, within);
}

} // namespace

void requireAffordableSmoothing(std::span<const MeshToSmooth> meshes, double smoothing) {
    if (!(smoothing > 0.0)) return;
    std::vector<std::unique_ptr<EstimatedMesh>> estimated;
    std::vector<GaussianNeighbourhoods*> floods;
    for (const MeshToSmooth& mesh : meshes) {
        const WeldMap& weld = *mesh.weld;
        if (weld.outputOf.size() != mesh.positions.size())
            throw std::invalid_argument("requireAffordableSmoothing(): the weld maps " +
                                        std::to_string(weld.outputOf.size()) + " vertices, not the " +
                                        std::to_string(mesh.positions.size()) + " 'positions'");
        std::vector<glm::dvec3> welded;
        welded.reserve(weld.kept.size());
        for (std::uint32_t input : weld.kept) welded.emplace_back(mesh.positions[input]);
        std::vector<glm::uvec3> faces;
        faces.reserve(mesh.triangles.size());
        for (const glm::uvec3& t : mesh.triangles) {
            if (t.x >= weld.outputOf.size() || t.y >= weld.outputOf.size() || t.z >= weld.outputOf.size()) continue;
            const glm::uvec3 face(weld.outputOf[t.x], weld.outputOf[t.y], weld.outputOf[t.z]);
            if (face.x != face.y && face.y != face.z && face.z != face.x) faces.push_back(face);
        }
        if (welded.empty()) continue;
        estimated.push_back(std::make_unique<EstimatedMesh>(std::move(welded), std::move(faces), smoothing));
        floods.push_back(&estimated.back()->floods);
    }
    requireAffordableSmoothing(floods, smoothing);
}

void requireAffordableSmoothing(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                const WeldMap& weld, double smoothing) {
    const MeshToSmooth mesh{positions, triangles, &weld};
    requireAffordableSmoothing(std::span<const MeshToSmooth>(&mesh, 1), smoothing);
}

SmoothingTooCostlyError::SmoothingTooCostlyError(double smoothing, double estimatedVisits, std::size_t vertexCount,
                                                 double smoothingWithinLimit)
    : SceneError(
          "computeMeshCurvature(): a 'smoothing' of " + detail::formatExtent(smoothing) + " model units floods about " +
          detail::formatNumber(std::round(estimatedVisits / double(std::max<std::size_t>(vertexCount, 1)))) +
          " vertices from each of " + std::to_string(vertexCount) +
          " (in meshes whose windows hold over a sixteenth of them), about " + detail::formatExtent(estimatedVisits) +
          " visits, more than the " + detail::formatExtent(kMaxSmoothingVisits) + " one smoothing may take; about " +
          detail::formatExtent(smoothingWithinLimit) + " would not"),
      mSmoothing(smoothing), mEstimatedVisits(estimatedVisits), mVertexCount(vertexCount),
      mSmoothingWithinLimit(smoothingWithinLimit) {}

MeshCurvature computeMeshCurvature(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                   double weldDistance, double smoothing) {
    if (!std::isfinite(weldDistance) || weldDistance < 0.0)
        throw std::invalid_argument("computeMeshCurvature(): 'weldDistance' must be finite and >= 0, got " +
                                    std::to_string(weldDistance));
    checkCurvatureInput(positions, triangles, smoothing);
    return computeMeshCurvature(positions, triangles, weldVertices(positions, {}, weldDistance), smoothing);
}

MeshCurvature computeMeshCurvature(std::span<const glm::vec3> positions, std::span<const glm::uvec3> triangles,
                                   const WeldMap& weld, double smoothing) {
    checkCurvatureInput(positions, triangles, smoothing);
    if (weld.outputOf.size() != positions.size())
        throw std::invalid_argument("computeMeshCurvature(): the weld maps " + std::to_string(weld.outputOf.size()) +
                                    " vertices, not the " + std::to_string(positions.size()) + " 'positions'");

    MeshCurvature result;
    result.weldedOf = weld.outputOf;
    const std::size_t vertexCount = weld.kept.size();
    result.counts.weldedVertices = vertexCount;
    result.positions.reserve(vertexCount);
    for (std::uint32_t input : weld.kept) result.positions.emplace_back(positions[input]);

    glm::dvec3 low(0.0), high(0.0);
    if (vertexCount > 0) low = high = result.positions[0];
    for (const glm::dvec3& p : result.positions) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const double diagonal = glm::length(high - low);
    const double minimumArea = kDegenerateAreaRelative * diagonal * diagonal;

    // The usable faces and their frames.
    std::vector<FaceFrame> frames;
    for (std::size_t face = 0; face < triangles.size(); ++face) {
        const glm::uvec3 welded(weld.outputOf[triangles[face].x], weld.outputOf[triangles[face].y],
                                weld.outputOf[triangles[face].z]);
        if (welded.x == welded.y || welded.y == welded.z || welded.z == welded.x) {
            ++result.counts.degenerateFaces;
            continue;
        }
        FaceFrame frame;
        const glm::dvec3& p0 = result.positions[welded.x];
        const glm::dvec3& p1 = result.positions[welded.y];
        const glm::dvec3& p2 = result.positions[welded.z];
        frame.edges = {p2 - p1, p0 - p2, p1 - p0};
        const glm::dvec3 areaVector = glm::cross(frame.edges[2], -frame.edges[1]);
        const double area = 0.5 * glm::length(areaVector);
        if (!(area > minimumArea)) {
            ++result.counts.degenerateFaces;
            continue;
        }
        frame.normal = areaVector / (2.0 * area);
        frame.tangent = glm::normalize(frame.edges[2]);
        frame.bitangent = glm::cross(frame.normal, frame.tangent);
        result.triangles.push_back(welded);
        result.sourceFace.push_back(std::uint32_t(face));
        frames.push_back(frame);
    }
    const std::size_t faceCount = result.triangles.size();

    // 1. Normals, Max's weights: for a corner with edges a, b, (a x b) / (|a|^2 |b|^2). Every corner's a x b is the
    // face's area vector. A usable face has no zero-length edge (its area is above the minimum).
    std::vector<glm::dvec3> normalSums(vertexCount, glm::dvec3(0.0));
    std::vector<glm::dvec3> fallbackNormals(vertexCount, glm::dvec3(0.0));
    for (std::size_t face = 0; face < faceCount; ++face) {
        const FaceFrame& frame = frames[face];
        const glm::dvec3 areaVector = glm::cross(frame.edges[2], -frame.edges[1]);
        std::array<double, 3> squaredLength;
        for (int i = 0; i < 3; ++i) squaredLength[i] = glm::dot(frame.edges[i], frame.edges[i]);
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t vertex = result.triangles[face][corner];
            // The corner's two edges are the ones not opposite it.
            const double weight = 1.0 / (squaredLength[(corner + 1) % 3] * squaredLength[(corner + 2) % 3]);
            normalSums[vertex] += areaVector * weight;
            if (fallbackNormals[vertex] == glm::dvec3(0.0)) fallbackNormals[vertex] = frame.normal;
        }
    }
    result.normals.resize(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        const double length = glm::length(normalSums[vertex]);
        if (length > 0.0 && std::isfinite(length))
            result.normals[vertex] = normalSums[vertex] / length;
        else if (fallbackNormals[vertex] != glm::dvec3(0.0))
            result.normals[vertex] = fallbackNormals[vertex]; // opposite faces cancelled: take one
        else
            result.normals[vertex] = glm::dvec3(0.0, 0.0, 1.0); // no usable face
    }

    // 2. Corner areas (Meyer et al.): Voronoi for a non-obtuse triangle, 1/2 and 1/4 + 1/4 for an obtuse one.
    std::vector<glm::dvec3> cornerAreas(faceCount);
    result.pointAreas.assign(vertexCount, 0.0);
    for (std::size_t face = 0; face < faceCount; ++face) {
        const FaceFrame& frame = frames[face];
        const double area = 0.5 * glm::length(glm::cross(frame.edges[2], -frame.edges[1]));
        std::array<double, 3> squaredLength, cornerDot;
        for (int i = 0; i < 3; ++i) {
            squaredLength[i] = glm::dot(frame.edges[i], frame.edges[i]);
            // The corner's edges, both pointing away from it: edges[i+2] and -edges[i+1].
            cornerDot[i] = -glm::dot(frame.edges[(i + 2) % 3], frame.edges[(i + 1) % 3]);
        }
        glm::dvec3 corners;
        int obtuse = -1;
        for (int i = 0; i < 3; ++i)
            if (cornerDot[i] < 0.0) obtuse = i;
        if (obtuse >= 0) {
            for (int i = 0; i < 3; ++i) corners[i] = i == obtuse ? 0.5 * area : 0.25 * area;
        } else {
            // cot of the angle at corner j = (its edges' dot) / |their cross| = dot / (2 area).
            for (int i = 0; i < 3; ++i) {
                const int j = (i + 1) % 3, k = (i + 2) % 3;
                corners[i] = (squaredLength[j] * cornerDot[j] + squaredLength[k] * cornerDot[k]) / (16.0 * area);
            }
        }
        cornerAreas[face] = corners;
        for (int corner = 0; corner < 3; ++corner) result.pointAreas[result.triangles[face][corner]] += corners[corner];
    }

    std::optional<GaussianNeighbourhoods> neighbourhoods;
    if (smoothing > 0.0) {
        neighbourhoods.emplace(result.positions, result.triangles, result.pointAreas, smoothing);
        // On the adjacency the smoothing floods: a direct caller is refused as a scene is (SceneDerivedData checks
        // its meshes together before this).
        requireAffordableSmoothing({&*neighbourhoods}, smoothing);
        // rtsc's diffuse_normals: curvature is the change of the normal, so the normals' noise is what the fits
        // would turn into curvature noise.
        std::vector<glm::dvec3> smoothed(vertexCount);
        neighbourhoods->forEveryVertex([&](GaussianNeighbourhoods::Flood& flood, std::uint32_t vertex) {
            glm::dvec3 sum(0.0);
            flood.forEach(vertex, [&](std::uint32_t other, double weight) { sum += weight * result.normals[other]; });
            const double length = glm::length(sum);
            smoothed[vertex] = length > 0.0 && std::isfinite(length) ? sum / length : result.normals[vertex];
        });
        result.normals = std::move(smoothed);
    }

    // Each vertex's working frame (u, v) of its tangent plane.
    std::vector<glm::dvec3> frameU(vertexCount), frameV(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        frameU[vertex] = perpendicularTo(result.normals[vertex]);
        frameV[vertex] = glm::cross(result.normals[vertex], frameU[vertex]);
    }
    auto cornerWeight = [&](std::size_t face, int corner) {
        const double pointArea = result.pointAreas[result.triangles[face][corner]];
        return pointArea > 0.0 ? cornerAreas[face][corner] / pointArea : 0.0;
    };

    // 3 and 4. II per face by least squares, carried to the vertices.
    std::vector<Tensor2> vertexTensors(vertexCount);
    std::vector<double> tensorWeights(vertexCount, 0.0);
    for (std::size_t face = 0; face < faceCount; ++face) {
        const FaceFrame& frame = frames[face];
        const glm::uvec3& corners = result.triangles[face];
        // Unknowns (L, M, N) of II = [[L, M], [M, N]]; per edge e = (x, y) in the face frame and the change dn of
        // the normal along it: x L + y M = dn.t and x M + y N = dn.b.
        std::array<std::array<double, 3>, 3> normalMatrix{};
        std::array<double, 3> rightSide{};
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 e = frame.inPlane(frame.edges[i]);
            const glm::dvec2 dn =
                frame.inPlane(result.normals[corners[(i + 2) % 3]] - result.normals[corners[(i + 1) % 3]]);
            normalMatrix[0][0] += e.x * e.x;
            normalMatrix[0][1] += e.x * e.y;
            normalMatrix[1][1] += e.x * e.x + e.y * e.y;
            normalMatrix[1][2] += e.x * e.y;
            normalMatrix[2][2] += e.y * e.y;
            rightSide[0] += e.x * dn.x;
            rightSide[1] += e.y * dn.x + e.x * dn.y;
            rightSide[2] += e.y * dn.y;
        }
        normalMatrix[1][0] = normalMatrix[0][1];
        normalMatrix[2][1] = normalMatrix[1][2];
        std::array<double, 3> solution{};
        if (!solveSymmetric(normalMatrix, rightSide, solution)) {
            ++result.counts.singularCurvatureFits;
            continue;
        }
        const Tensor2 faceTensor{solution[0], solution[1], solution[2]};
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t vertex = corners[corner];
            glm::dvec3 u = frameU[vertex], v = frameV[vertex];
            rotateFrame(u, v, result.normals[vertex], frame.normal);
            const glm::dvec2 uf = frame.inPlane(u), vf = frame.inPlane(v);
            const double weight = cornerWeight(face, corner);
            Tensor2& tensor = vertexTensors[vertex];
            tensor.xx += weight * evaluate(faceTensor, uf, uf);
            tensor.xy += weight * evaluate(faceTensor, uf, vf);
            tensor.yy += weight * evaluate(faceTensor, vf, vf);
            tensorWeights[vertex] += weight;
        }
    }

    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        Tensor2& tensor = vertexTensors[vertex];
        if (tensorWeights[vertex] > 0.0) {
            // Faces whose fit failed left the weights short of 1: the rest stand for the whole neighbourhood.
            tensor.xx /= tensorWeights[vertex];
            tensor.xy /= tensorWeights[vertex];
            tensor.yy /= tensorWeights[vertex];
        } else {
            ++result.counts.isolatedVertices;
        }
    }
    if (neighbourhoods) {
        // rtsc's diffuse_curv: each neighbour's tensor carried into this vertex's frame. Vertices no fit reached
        // have no tensor and take no part.
        std::vector<Tensor2> smoothed(vertexCount);
        neighbourhoods->forEveryVertex([&](GaussianNeighbourhoods::Flood& flood, std::uint32_t vertex) {
            if (!(tensorWeights[vertex] > 0.0)) return;
            Tensor2 sum;
            double total = 0.0;
            flood.forEach(vertex, [&](std::uint32_t other, double weight) {
                if (!(tensorWeights[other] > 0.0) || !(weight > 0.0)) return;
                const auto [x, y] = frameChange(frameU[other], frameV[other], result.normals[other], frameU[vertex],
                                                frameV[vertex], result.normals[vertex]);
                const Tensor2& tensor = vertexTensors[other];
                sum.xx += weight * evaluate(tensor, x, x);
                sum.xy += weight * evaluate(tensor, x, y);
                sum.yy += weight * evaluate(tensor, y, y);
                total += weight;
            });
            if (total > 0.0) smoothed[vertex] = {sum.xx / total, sum.xy / total, sum.yy / total};
        });
        vertexTensors = std::move(smoothed);
    }

    // 5. Principal curvatures: the Jacobi rotation that diagonalises each 2x2 tensor.
    result.curvature1.assign(vertexCount, 0.0);
    result.curvature2.assign(vertexCount, 0.0);
    result.direction1.resize(vertexCount);
    result.direction2.resize(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        const Tensor2 tensor = vertexTensors[vertex];
        const double angle = 0.5 * std::atan2(2.0 * tensor.xy, tensor.xx - tensor.yy);
        const double c = std::cos(angle), s = std::sin(angle);
        double larger = tensor.xx * c * c + 2.0 * tensor.xy * c * s + tensor.yy * s * s;
        double smaller = tensor.xx * s * s - 2.0 * tensor.xy * c * s + tensor.yy * c * c;
        glm::dvec3 largerDirection = c * frameU[vertex] + s * frameV[vertex];
        if (std::abs(smaller) > std::abs(larger)) {
            std::swap(larger, smaller);
            largerDirection = -s * frameU[vertex] + c * frameV[vertex];
        }
        result.curvature1[vertex] = larger;
        result.curvature2[vertex] = smaller;
        result.direction1[vertex] = largerDirection;
        result.direction2[vertex] = glm::cross(result.normals[vertex], largerDirection);
    }

    // 6. C per face from the change of the vertex tensors along the edges, carried to the vertices.
    std::vector<glm::dvec4> derivativeSums(vertexCount, glm::dvec4(0.0));
    std::vector<double> derivativeWeights(vertexCount, 0.0);
    for (std::size_t face = 0; face < faceCount; ++face) {
        const FaceFrame& frame = frames[face];
        const glm::uvec3& corners = result.triangles[face];
        std::array<Tensor2, 3> cornerTensors;
        std::array<glm::dvec2, 3> principal1, principal2; // each corner's principal frame in the face frame
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t vertex = corners[corner];
            glm::dvec3 d1 = result.direction1[vertex], d2 = result.direction2[vertex];
            rotateFrame(d1, d2, result.normals[vertex], frame.normal);
            principal1[corner] = frame.inPlane(d1);
            principal2[corner] = frame.inPlane(d2);
            const double k1 = result.curvature1[vertex], k2 = result.curvature2[vertex];
            const glm::dvec2 &p = principal1[corner], &q = principal2[corner];
            cornerTensors[corner] = {k1 * p.x * p.x + k2 * q.x * q.x, k1 * p.x * p.y + k2 * q.x * q.y,
                                     k1 * p.y * p.y + k2 * q.y * q.y};
        }
        // Unknowns (a, b, c, d) = (C_ttt, C_ttb, C_tbb, C_bbb); per edge e = (x, y) and the change dII along it:
        // x a + y b = dII_tt, x b + y c = dII_tb, x c + y d = dII_bb.
        std::array<std::array<double, 4>, 4> normalMatrix{};
        std::array<double, 4> rightSide{};
        for (int i = 0; i < 3; ++i) {
            const glm::dvec2 e = frame.inPlane(frame.edges[i]);
            const Tensor2& from = cornerTensors[(i + 1) % 3];
            const Tensor2& to = cornerTensors[(i + 2) % 3];
            const std::array<double, 3> change = {to.xx - from.xx, to.xy - from.xy, to.yy - from.yy};
            for (int row = 0; row < 3; ++row) {
                // Row `row` has x at unknown `row` and y at unknown `row + 1`.
                normalMatrix[row][row] += e.x * e.x;
                normalMatrix[row][row + 1] += e.x * e.y;
                normalMatrix[row + 1][row] += e.x * e.y;
                normalMatrix[row + 1][row + 1] += e.y * e.y;
                rightSide[row] += e.x * change[row];
                rightSide[row + 1] += e.y * change[row];
            }
        }
        std::array<double, 4> solution{};
        if (!solveSymmetric(normalMatrix, rightSide, solution)) {
            ++result.counts.singularDerivativeFits;
            continue;
        }
        const glm::dvec4 faceDerivative(solution[0], solution[1], solution[2], solution[3]);
        for (int corner = 0; corner < 3; ++corner) {
            const glm::dvec2 &p = principal1[corner], &q = principal2[corner];
            const double weight = cornerWeight(face, corner);
            derivativeSums[corners[corner]] +=
                weight * glm::dvec4(evaluate(faceDerivative, p, p, p), evaluate(faceDerivative, p, p, q),
                                    evaluate(faceDerivative, p, q, q), evaluate(faceDerivative, q, q, q));
            derivativeWeights[corners[corner]] += weight;
        }
    }
    result.derivative.resize(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex)
        result.derivative[vertex] =
            derivativeWeights[vertex] > 0.0 ? derivativeSums[vertex] / derivativeWeights[vertex] : glm::dvec4(0.0);
    if (neighbourhoods) {
        // rtsc's diffuse_dcurv: each neighbour's C carried into this vertex's principal frame.
        std::vector<glm::dvec4> smoothed(vertexCount, glm::dvec4(0.0));
        neighbourhoods->forEveryVertex([&](GaussianNeighbourhoods::Flood& flood, std::uint32_t vertex) {
            if (!(derivativeWeights[vertex] > 0.0)) return;
            glm::dvec4 sum(0.0);
            double total = 0.0;
            flood.forEach(vertex, [&](std::uint32_t other, double weight) {
                if (!(derivativeWeights[other] > 0.0) || !(weight > 0.0)) return;
                const auto [p, q] =
                    frameChange(result.direction1[other], result.direction2[other], result.normals[other],
                                result.direction1[vertex], result.direction2[vertex], result.normals[vertex]);
                const glm::dvec4& c = result.derivative[other];
                sum += weight * glm::dvec4(evaluate(c, p, p, p), evaluate(c, p, p, q), evaluate(c, p, q, q),
                                           evaluate(c, q, q, q));
                total += weight;
            });
            if (total > 0.0) smoothed[vertex] = sum / total;
        });
        result.derivative = std::move(smoothed);
    }
    return result;
}

} // namespace inkgraph
