#include "scene/mesh/MeshOps.h"

#include "scene/MessageText.h"
#include "scene/Warning.h"
#include "scene/mesh/OutwardWinding.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <tuple>
#include <utility>

namespace inkgraph {

namespace {

constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

/** Two unit normals closer than this (chord length, ~0.06 degrees) count as the same normal when welding:
 *  loose enough for text round-off, far tighter than any intended hard edge. */
constexpr double kNormalMatchDistance = 1e-3;

/** Grid cell coordinates; the cell size floor in weldVertices() keeps them below 2^31. */
struct CellKey {
    std::int32_t x = 0;
    std::int32_t y = 0;
    std::int32_t z = 0;
    bool operator==(const CellKey&) const = default;
};

std::uint64_t hashCell(const CellKey& key) {
    // Multiply-xor mixing, then the splitmix64 finaliser so neighbouring cells spread over the whole table.
    std::uint64_t h = std::uint64_t(std::uint32_t(key.x)) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(std::uint32_t(key.y)) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= std::uint64_t(std::uint32_t(key.z)) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
    return h;
}

/** Open-addressing map from a grid cell to the most recent representative vertex in it; the rest of the cell's
 *  representatives are chained through a separate `next` array. Sized once for the worst case (one cell per
 *  vertex) at load factor <= 0.5, so it never grows. Most lookups are for empty neighbour cells, so a small
 *  occupancy bitmap (16 bits per vertex) answers those without touching the large slot array. Callers pass each
 *  cell's hashCell() along, computed once for prefetch() and the lookup that follows it. */
class CellTable {
public:
    explicit CellTable(std::size_t maxCells) {
        std::size_t capacity = 16;
        while (capacity < maxCells * 2) {
            capacity *= 2;
        }
        mSlots.resize(capacity);
        mMask = capacity - 1;
        mOccupied.resize(capacity * 8 / 64);
        mOccupiedMask = capacity * 8 - 1;
    }

    std::uint32_t head(const CellKey& key, std::uint64_t hash) const {
        if (!isMarked(hash)) {
            return kNoVertex;
        }
        for (std::size_t i = hash & mMask;; i = (i + 1) & mMask) {
            const Slot& slot = mSlots[i];
            if (slot.head == kNoVertex) {
                return kNoVertex;
            }
            if (slot.key == key) {
                return slot.head;
            }
        }
    }

    /** Makes `vertex` the head of its cell's chain and returns the previous head (kNoVertex if the cell was new). */
    std::uint32_t push(const CellKey& key, std::uint64_t hash, std::uint32_t vertex) {
        mark(hash);
        for (std::size_t i = hash & mMask;; i = (i + 1) & mMask) {
            Slot& slot = mSlots[i];
            if (slot.head == kNoVertex) {
                slot.key = key;
                slot.head = vertex;
                return kNoVertex;
            }
            if (slot.key == key) {
                return std::exchange(slot.head, vertex);
            }
        }
    }

    /** Asks the memory for what head() and push() will read for this hash: its bitmap word and, when `slot`, its
     *  first slot. */
    void prefetch(std::uint64_t hash, bool slot) const {
        __builtin_prefetch(&mOccupied[bitOf(hash) / 64]);
        if (slot) __builtin_prefetch(&mSlots[hash & mMask]);
    }

private:
    struct Slot {
        CellKey key;
        std::uint32_t head = kNoVertex;
    };

    // The bitmap uses the hash's high bits so its false positives are independent of slot collisions.
    std::size_t bitOf(std::uint64_t hash) const { return std::size_t(hash >> 32 ^ hash >> 11) & mOccupiedMask; }
    bool isMarked(std::uint64_t hash) const {
        const std::size_t bit = bitOf(hash);
        return (mOccupied[bit / 64] >> (bit % 64)) & 1u;
    }
    void mark(std::uint64_t hash) {
        const std::size_t bit = bitOf(hash);
        mOccupied[bit / 64] |= std::uint64_t(1) << (bit % 64);
    }

    std::vector<Slot> mSlots;
    std::size_t mMask = 0;
    std::vector<std::uint64_t> mOccupied;
    std::size_t mOccupiedMask = 0;
};

glm::dvec3 faceCross(std::span<const glm::vec3> positions, const glm::uvec3& triangle) {
    const glm::dvec3 a(positions[triangle.x]);
    const glm::dvec3 b(positions[triangle.y]);
    const glm::dvec3 c(positions[triangle.z]);
    return glm::cross(b - a, c - a);
}

/** Below this fraction of the summed face weights, a vertex's normal sum is cancellation noise, not a direction. */
constexpr double kCancelledNormalRelative = 1e-9;

} // namespace

glm::dvec3 normalizedOrZero(const glm::dvec3& v) {
    const double length = glm::length(v);
    if (!std::isfinite(length) || length <= 0.0) {
        return glm::dvec3(0.0);
    }
    return v / length;
}

BoundingBox computeBoundingBox(std::span<const glm::vec3> positions) {
    BoundingBox box;
    for (const glm::vec3& p : positions) {
        box.add(glm::dvec3(p));
    }
    return box;
}

WeldMap weldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, double distance,
                     std::span<const std::uint32_t> attributeClasses) {
    if (!normals.empty() && normals.size() != positions.size()) {
        throw std::logic_error("weldVertices(): normals must be empty or one per position");
    }
    if (!attributeClasses.empty() && attributeClasses.size() != positions.size()) {
        throw std::logic_error("weldVertices(): attribute classes must be empty or one per position");
    }
    if (positions.size() >= kNoVertex) {
        throw std::length_error("weldVertices(): too many vertices for 32-bit indices");
    }
    WeldMap map;
    map.outputOf.resize(positions.size());
    map.kept.reserve(positions.size());
    if (positions.empty()) {
        return map;
    }

    distance = std::max(distance, 0.0);
    const BoundingBox box = computeBoundingBox(positions);
    // Cells wider than 2 x distance mean a match lies in the vertex's own cell or the neighbour on the side the vertex
    // is nearer to, per axis: 8 cells instead of 27. The floor (box diagonal / 1e9) keeps cell coordinates within
    // int32 when the distance is tiny or zero (zero welds exact duplicates only).
    double cellSize = std::max(2.5 * distance, box.diagonal() * 1e-9);
    if (!(cellSize > 0.0)) {
        cellSize = 1.0;
    }
    const double maxDistanceSquared = distance * distance;
    const bool matchNormals = !normals.empty();

    CellTable table(positions.size());
    std::vector<std::uint32_t> nextInCell;
    nextInCell.reserve(positions.size());

    // The 8 cells a vertex looks in: its own, then the neighbours on the sides it is nearer to (corner c moves along x
    // if c & 1, y if c & 2, z if c & 4). Made kLookAhead vertices early, when their table memory is prefetched: the
    // loop is otherwise a string of cache misses (a large model's table is far bigger than the cache), and the
    // addresses do not depend on what the vertices before decide.
    struct Lookup {
        CellKey cells[8];
        std::uint64_t hashes[8];
    };
    constexpr std::uint32_t kLookAhead = 16;
    Lookup lookups[kLookAhead];
    const auto prepare = [&](std::uint32_t input) {
        Lookup& lookup = lookups[input % kLookAhead];
        const glm::dvec3 scaled = (glm::dvec3(positions[input]) - box.min) / cellSize;
        const glm::dvec3 cellFloor = glm::floor(scaled);
        const CellKey home{std::int32_t(cellFloor.x), std::int32_t(cellFloor.y), std::int32_t(cellFloor.z)};
        const glm::dvec3 fraction = scaled - cellFloor;
        const std::int32_t stepX = fraction.x < 0.5 ? -1 : 1;
        const std::int32_t stepY = fraction.y < 0.5 ? -1 : 1;
        const std::int32_t stepZ = fraction.z < 0.5 ? -1 : 1;
        for (int corner = 0; corner < 8; ++corner) {
            lookup.cells[corner] = {home.x + ((corner & 1) ? stepX : 0), home.y + ((corner & 2) ? stepY : 0),
                                    home.z + ((corner & 4) ? stepZ : 0)};
            lookup.hashes[corner] = hashCell(lookup.cells[corner]);
            table.prefetch(lookup.hashes[corner], corner == 0);
        }
    };
    const auto count = std::uint32_t(positions.size());
    for (std::uint32_t input = 0; input < std::min(count, kLookAhead); ++input) prepare(input);

    for (std::uint32_t input = 0; input < count; ++input) {
        const Lookup lookup = lookups[input % kLookAhead]; // a copy: prepare() below reuses the slot
        if (input + kLookAhead < count) prepare(input + kLookAhead);
        const glm::dvec3 point(positions[input]);

        std::uint32_t best = kNoVertex;
        double bestDistanceSquared = maxDistanceSquared;
        for (int corner = 0; corner < 8; ++corner) {
            for (std::uint32_t candidate = table.head(lookup.cells[corner], lookup.hashes[corner]);
                 candidate != kNoVertex; candidate = nextInCell[candidate]) {
                const std::uint32_t candidateInput = map.kept[candidate];
                const glm::dvec3 delta = glm::dvec3(positions[candidateInput]) - point;
                const double distanceSquared = glm::dot(delta, delta);
                const bool fartherThanBest =
                    distanceSquared > bestDistanceSquared ||
                    (best != kNoVertex && distanceSquared == bestDistanceSquared); // ties keep the first found
                if (fartherThanBest) {
                    continue;
                }
                if (!attributeClasses.empty() && attributeClasses[candidateInput] != attributeClasses[input]) {
                    continue;
                }
                if (matchNormals) {
                    const glm::dvec3 normalDelta = glm::dvec3(normals[candidateInput]) - glm::dvec3(normals[input]);
                    if (glm::dot(normalDelta, normalDelta) > kNormalMatchDistance * kNormalMatchDistance) {
                        map.splitByNormals = true;
                        continue;
                    }
                }
                best = candidate;
                bestDistanceSquared = distanceSquared;
            }
        }

        if (best != kNoVertex) {
            map.outputOf[input] = best;
            continue;
        }
        const auto output = std::uint32_t(map.kept.size());
        map.kept.push_back(input);
        map.outputOf[input] = output;
        nextInCell.push_back(table.push(lookup.cells[0], lookup.hashes[0], output));
    }
    return map;
}

std::vector<glm::vec3> computeSmoothNormals(std::span<const glm::vec3> positions,
                                            std::span<const glm::uvec3> triangles) {
    std::vector<glm::dvec3> sums(positions.size(), glm::dvec3(0.0));
    std::vector<double> weights(positions.size(), 0.0); // sum of |cross|, the scale to judge a sum against
    for (const glm::uvec3& triangle : triangles) {
        if (glm::any(glm::greaterThanEqual(triangle, glm::uvec3(std::uint32_t(positions.size()))))) {
            throw std::out_of_range("computeSmoothNormals(): triangle index out of range");
        }
        const glm::dvec3 cross = faceCross(positions, triangle);
        const double weight = glm::length(cross);
        for (int corner = 0; corner < 3; ++corner) {
            sums[triangle[corner]] += cross;
            weights[triangle[corner]] += weight;
        }
    }

    std::vector<glm::vec3> normals(positions.size());
    std::vector<std::uint8_t> fallback; // per vertex, once one needs it: its sum gave no direction
    for (std::size_t vertex = 0; vertex < positions.size(); ++vertex) {
        const bool cancelled = glm::length(sums[vertex]) <= kCancelledNormalRelative * weights[vertex];
        const glm::dvec3 normal = cancelled ? glm::dvec3(0.0) : normalizedOrZero(sums[vertex]);
        if (normal == glm::dvec3(0.0)) {
            if (fallback.empty()) fallback.assign(positions.size(), 0);
            fallback[vertex] = 1;
        }
        normals[vertex] = glm::vec3(normal);
    }
    if (fallback.empty()) return normals;
    // Rare (opposite faces cancelling, or only degenerate faces): such a vertex takes the direction of its first face
    // (in face order) that has one, else (0, 0, 1). A second pass over the faces rather than a fallback kept for
    // every vertex in the first.
    for (const glm::uvec3& triangle : triangles) {
        const glm::dvec3 faceNormal = normalizedOrZero(faceCross(positions, triangle));
        if (faceNormal == glm::dvec3(0.0)) continue;
        for (int corner = 0; corner < 3; ++corner) {
            if (fallback[triangle[corner]] != 1) continue;
            normals[triangle[corner]] = glm::vec3(faceNormal);
            fallback[triangle[corner]] = 2; // set
        }
    }
    for (std::size_t vertex = 0; vertex < positions.size(); ++vertex)
        if (fallback[vertex] == 1) normals[vertex] = glm::vec3(0.0f, 0.0f, 1.0f);
    return normals;
}

SortedCorners sortedCorners(const glm::uvec3& triangle) {
    SortedCorners corners{triangle, false};
    const auto order = [&](int i, int j) {
        if (corners.sorted[j] < corners.sorted[i]) {
            std::swap(corners.sorted[i], corners.sorted[j]);
            corners.odd = !corners.odd;
        }
    };
    order(0, 1);
    order(1, 2);
    order(0, 1);
    return corners;
}

namespace {

/** Which later triangle on the same three vertices as an earlier one is a repeat: one wound the same way (a face the
 *  file gives twice) or the other way (a back-to-back twin). */
enum class RepeatWinding { same, opposite };

std::vector<std::uint32_t> laterRepeats(std::span<const glm::uvec3> triangles, RepeatWinding winding) {
    const std::size_t count = triangles.size();
    if (count < 2) return {};
    // Triangles bucketed by their lowest vertex (a counting sort, stable: each bucket in triangle order). A file's
    // triangles mostly name nearby vertices in turn, so the buckets fill nearly in order (a hash of all three corners
    // scattered them: 2.5 times the time).
    std::uint32_t highest = 0;
    for (const glm::uvec3& triangle : triangles) highest = std::max({highest, triangle.x, triangle.y, triangle.z});
    std::vector<std::uint32_t> start(std::size_t(highest) + 2, 0);
    for (const glm::uvec3& triangle : triangles)
        ++start[std::size_t(std::min({triangle.x, triangle.y, triangle.z})) + 1];
    for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> order(count);
    {
        std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
        for (std::size_t t = 0; t < count; ++t) {
            const glm::uvec3& triangle = triangles[t];
            order[next[std::min({triangle.x, triangle.y, triangle.z})]++] = std::uint32_t(t);
        }
    }
    std::vector<std::uint32_t> twins;
    std::vector<std::pair<SortedCorners, std::uint32_t>> members;
    const auto key = [](const std::pair<SortedCorners, std::uint32_t>& member) {
        return std::tuple(member.first.sorted.y, member.first.sorted.z, member.second);
    };
    for (std::size_t v = 0; v + 1 < start.size(); ++v) {
        if (start[v + 1] - start[v] < 2) continue;
        members.clear();
        for (std::uint32_t i = start[v]; i < start[v + 1]; ++i)
            members.emplace_back(sortedCorners(triangles[order[i]]), order[i]);
        // Most buckets hold a few triangles with no corners in common beyond the lowest: passed over unsorted.
        if (members.size() <= 8) {
            bool repeated = false;
            for (std::size_t a = 0; a < members.size() && !repeated; ++a)
                for (std::size_t b = a + 1; b < members.size() && !repeated; ++b)
                    repeated = members[a].first.sorted == members[b].first.sorted;
            if (!repeated) continue;
        }
        // Equal corners side by side, each run in triangle order; in a run, each triangle takes the earliest unmatched
        // one of the other winding before it, so a hostile file of many repeats costs no more than once each.
        std::sort(members.begin(), members.end(), [&](const auto& a, const auto& c) { return key(a) < key(c); });
        for (std::size_t runStart = 0; runStart < members.size();) {
            std::size_t runEnd = runStart + 1;
            while (runEnd < members.size() && members[runEnd].first.sorted == members[runStart].first.sorted) ++runEnd;
            std::size_t waiting[2] = {0, 0}; // unmatched earlier triangles of each winding in this run
            for (std::size_t m = runStart; m < runEnd; ++m) {
                const int parity = members[m].first.odd ? 1 : 0;
                if (winding == RepeatWinding::same) {
                    // Every later one of a winding repeats the first of it.
                    if (waiting[parity] > 0)
                        twins.push_back(members[m].second);
                    else
                        waiting[parity] = 1;
                } else if (waiting[1 - parity] > 0) {
                    --waiting[1 - parity];
                    twins.push_back(members[m].second);
                } else {
                    ++waiting[parity];
                }
            }
            runStart = runEnd;
        }
    }
    std::sort(twins.begin(), twins.end());
    return twins;
}

} // namespace

std::vector<std::uint32_t> backToBackTwins(std::span<const glm::uvec3> triangles) {
    return laterRepeats(triangles, RepeatWinding::opposite);
}

std::vector<std::uint32_t> repeatedTriangles(std::span<const glm::uvec3> triangles) {
    return laterRepeats(triangles, RepeatWinding::same);
}

WeldMap weldMeshPositions(const Mesh& mesh, double distance) {
    if (!mesh.positionsWeldedAt || !(distance <= *mesh.positionsWeldedAt))
        return weldVertices(mesh.positions, {}, distance);
    // Every two positions are farther apart than the loader's distance (each vertex it kept was out of reach of every
    // earlier one), so a weld at this distance keeps all of them, in order.
    WeldMap map;
    map.kept.resize(mesh.positions.size());
    for (std::size_t vertex = 0; vertex < map.kept.size(); ++vertex) map.kept[vertex] = std::uint32_t(vertex);
    map.outputOf = map.kept;
    return map;
}

std::vector<glm::vec3> computePositionWeldedNormals(std::span<const glm::vec3> positions,
                                                    std::span<const glm::uvec3> triangles, double weldDistance) {
    return computePositionWeldedNormals(positions, triangles, weldVertices(positions, {}, weldDistance));
}

std::vector<glm::vec3> computePositionWeldedNormals(std::span<const glm::vec3> positions,
                                                    std::span<const glm::uvec3> triangles, const WeldMap& weld) {
    if (weld.outputOf.size() != positions.size())
        throw std::invalid_argument("computePositionWeldedNormals(): the weld maps " +
                                    std::to_string(weld.outputOf.size()) + " vertices, not the " +
                                    std::to_string(positions.size()) + " 'positions'");
    std::vector<glm::vec3> weldedPositions(weld.kept.size());
    for (std::size_t output = 0; output < weld.kept.size(); ++output) {
        weldedPositions[output] = positions[weld.kept[output]];
    }
    std::vector<glm::uvec3> weldedTriangles(triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        const glm::uvec3& triangle = triangles[i];
        if (glm::any(glm::greaterThanEqual(triangle, glm::uvec3(std::uint32_t(positions.size()))))) {
            throw std::out_of_range("computePositionWeldedNormals(): triangle index out of range");
        }
        // A triangle that welding collapses has a zero cross product and so adds nothing to the sums.
        weldedTriangles[i] =
            glm::uvec3(weld.outputOf[triangle.x], weld.outputOf[triangle.y], weld.outputOf[triangle.z]);
    }
    // A back-to-back pair's normals cancel (a double-faced card's hull would fold through it): its first face alone.
    removeTriangles(weldedTriangles, backToBackTwins(weldedTriangles));
    const std::vector<glm::vec3> weldedNormals = computeSmoothNormals(weldedPositions, weldedTriangles);
    std::vector<glm::vec3> normals(positions.size());
    for (std::size_t input = 0; input < positions.size(); ++input) {
        normals[input] = weldedNormals[weld.outputOf[input]];
    }
    return normals;
}

bool isPointInsideMesh(const Mesh& mesh, glm::dvec3 point) {
    const BoundingBox box = computeBoundingBox(mesh.positions);
    if (box.empty() || glm::any(glm::lessThan(point, box.min)) || glm::any(glm::greaterThan(point, box.max))) {
        return false;
    }
    // Directions with no simple ratio between their components, so they miss the axis-aligned and diagonal
    // structure of procedural and CAD meshes (rays through shared edges and vertices) on all but unlucky inputs; each
    // with its opposite, so a point under an open roof (its rays up cross it once, its rays down never) is not
    // taken for inside.
    const glm::dvec3 skewed[3] = {glm::normalize(glm::dvec3(0.5773, 0.3141, 0.7541)),
                                  glm::normalize(glm::dvec3(-0.6180, 0.7071, -0.2718)),
                                  glm::normalize(glm::dvec3(0.1414, -0.8660, -0.4472))};
    const glm::dvec3 directions[6] = {skewed[0], -skewed[0], skewed[1], -skewed[1], skewed[2], -skewed[2]};
    int insideVotes = 0;
    for (const glm::dvec3& direction : directions) {
        std::size_t crossings = 0;
        for (const glm::uvec3& triangle : mesh.triangles) {
            // Moller-Trumbore in double; the barycentric bounds are inclusive, so a ray through a shared edge counts
            // it twice: the other two rays outvote that.
            const glm::dvec3 a(mesh.positions[triangle.x]);
            const glm::dvec3 edge1 = glm::dvec3(mesh.positions[triangle.y]) - a;
            const glm::dvec3 edge2 = glm::dvec3(mesh.positions[triangle.z]) - a;
            const glm::dvec3 p = glm::cross(direction, edge2);
            const double determinant = glm::dot(edge1, p);
            if (determinant == 0.0) {
                continue; // the ray is parallel to the triangle's plane
            }
            const double inverse = 1.0 / determinant;
            const glm::dvec3 toPoint = point - a;
            const double u = glm::dot(toPoint, p) * inverse;
            if (u < 0.0 || u > 1.0) {
                continue;
            }
            const glm::dvec3 q = glm::cross(toPoint, edge1);
            const double v = glm::dot(direction, q) * inverse;
            if (v < 0.0 || u + v > 1.0) {
                continue;
            }
            if (glm::dot(edge2, q) * inverse > 0.0) {
                ++crossings;
            }
        }
        insideVotes += int(crossings % 2);
    }
    // Inside a closed mesh every ray crosses it an odd number of times; one that grazes an edge or a vertex
    // (counted twice, or not at all) may be outvoted.
    return insideVotes >= 5;
}

std::vector<std::uint32_t> degenerateTriangles(std::span<const glm::vec3> positions,
                                               std::span<const glm::uvec3> triangles, double minArea) {
    std::vector<std::uint32_t> degenerate;
    for (std::size_t index = 0; index < triangles.size(); ++index) {
        const glm::uvec3& t = triangles[index];
        if (t.x == t.y || t.y == t.z || t.x == t.z || !(0.5 * glm::length(faceCross(positions, t)) > minArea))
            degenerate.push_back(std::uint32_t(index));
    }
    return degenerate;
}

namespace {

/** A texture on a coordinate set the mesh does not have would sample one texel everywhere: it is dropped, with a
 *  warning that names the mesh, the texture and the set. */
void dropTexturesWithoutCoordinates(RawMesh& raw, LoadReport& report) {
    auto check = [&](TextureRef& texture, const char* role, glm::vec3* emission = nullptr) {
        if (!texture.present() || !raw.texcoords[texture.texCoord == 1 ? 1 : 0].empty()) return;
        // Said in glTF's words, which the readers map their coordinates to; an OBJ's own name is given too.
        const std::string coordinatesInOtherFormats = texture.texCoord == 0 ? " (an OBJ's 'vt')" : "";
        report.warnings.push_back(makeWarning(WarningKind::TextureCoordinatesMissing,
                                              "mesh '" + raw.name + "': its " + role + " reads TEXCOORD_" +
                                                  std::to_string(texture.texCoord) + coordinatesInOtherFormats +
                                                  ", which the mesh does not have; drawn without that texture" +
                                                  (emission != nullptr ? " and its emission" : ""),
                                              "", raw.name));
        texture = TextureRef{};
        // The emissive factor multiplies the image, often as 1 1 1: alone it would draw the mesh white.
        if (emission != nullptr) *emission = glm::vec3(0.0f);
    };
    check(raw.material.baseColorTexture, "base colour texture");
    if (!raw.material.baseColorTexture.present() && raw.material.baseColorFactorWithoutTexture) {
        raw.material.baseColorFactor = *raw.material.baseColorFactorWithoutTexture; // the file's colour, not the map's
        raw.material.baseColorFactorWithoutTexture.reset();
    }
    check(raw.material.emissiveTexture, "emissive texture", &raw.material.emissiveFactor);
    if (raw.material.mtoon) {
        check(raw.material.mtoon->shadeMultiplyTexture, "MToon shade texture");
        check(raw.material.mtoon->outlineWidthMultiplyTexture, "MToon outline width texture");
    }
}

/** One class per distinct (texcoords, colour) tuple, compared exactly; empty when the mesh has no such attributes. */
std::vector<std::uint32_t> vertexAttributeClasses(const RawMesh& raw) {
    if (raw.texcoords[0].empty() && raw.texcoords[1].empty() && raw.colors.empty()) return {};
    // Hashed, not ordered: a textured scan has a million vertices. +0 and -0 are one value, as == says.
    struct KeyHash {
        std::size_t operator()(const std::array<float, 8>& key) const {
            std::size_t hash = 0;
            for (const float value : key) hash = hash * 1000003u ^ std::hash<float>{}(value == 0.0f ? 0.0f : value);
            return hash;
        }
    };
    std::unordered_map<std::array<float, 8>, std::uint32_t, KeyHash> classOf;
    classOf.reserve(raw.positions.size());
    std::vector<std::uint32_t> classes(raw.positions.size());
    for (std::size_t vertex = 0; vertex < raw.positions.size(); ++vertex) {
        std::array<float, 8> key{};
        for (int set = 0; set < 2; ++set) {
            if (raw.texcoords[set].empty()) continue;
            key[2 * set] = raw.texcoords[set][vertex].x;
            key[2 * set + 1] = raw.texcoords[set][vertex].y;
        }
        if (!raw.colors.empty()) {
            for (int channel = 0; channel < 4; ++channel) key[4 + channel] = raw.colors[vertex][channel];
        }
        classes[vertex] = classOf.emplace(key, std::uint32_t(classOf.size())).first->second;
    }
    return classes;
}

/** Within this of -1, a face's normal and a vertex's largest face's are opposed: two sheets lie on each other there
 *  (2.6 degrees from antiparallel; a blade's edge that sharp is better shaded hard too). */
constexpr double kOpposedSheetsCosine = -0.999;

/** Where sheets that lie on each other meet (a double-faced card, a closed mesh a node's scale of 0 flattens onto a
 *  plane), a smooth normal sums opposite faces: nearly nothing, or one sheet's direction for both, so one side shades
 *  dark or in wedges. Judged at each place (`positionWeld`'s output vertex, or each vertex when it is null: the
 *  load's weld was by position): opposed when one of its faces lies within kOpposedSheetsCosine of antiparallel to its
 *  largest face. There the faces that look against the canonical direction (that largest face's normal, turned so
 *  that its largest component is positive: the same for every vertex at the place) form the back sheet. A vertex used
 *  by both sheets gets a copy (same position and attributes) for the back sheet's faces. Returns the class of every
 *  vertex afterwards, 1 for the back sheet's and 0 for the rest (empty when no place is opposed): in a position weld
 *  with these classes each sheet sums its own normals. */
std::vector<std::uint32_t> splitOpposedSheets(Mesh& mesh, const WeldMap* positionWeld) {
    const std::size_t count = mesh.positions.size();
    const auto placeOf = [&](std::uint32_t vertex) {
        return positionWeld != nullptr ? positionWeld->outputOf[vertex] : vertex;
    };
    const std::size_t places = positionWeld != nullptr ? positionWeld->kept.size() : count;
    // Floats: a load's transient arrays stay within what the load budget charges per triangle and vertex, and the
    // test against kOpposedSheetsCosine needs no more.
    std::vector<float> largestArea(places, 0.0f);
    std::vector<glm::vec3> reference(places, glm::vec3(0.0f));
    std::vector<glm::vec3> faceNormals(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::dvec3 cross = faceCross(mesh.positions, mesh.triangles[t]);
        faceNormals[t] = glm::vec3(normalizedOrZero(cross));
        const auto area = float(glm::length(cross));
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t place = placeOf(mesh.triangles[t][corner]);
            if (area > largestArea[place]) {
                largestArea[place] = area;
                reference[place] = faceNormals[t];
            }
        }
    }
    std::vector<std::uint8_t> opposed(places, 0);
    bool any = false;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t place = placeOf(mesh.triangles[t][corner]);
            if (glm::dot(faceNormals[t], reference[place]) < kOpposedSheetsCosine) opposed[place] = any = true;
        }
    }
    if (!any) return {};
    for (std::size_t place = 0; place < places; ++place) {
        if (!opposed[place]) continue;
        const glm::vec3 magnitude = glm::abs(reference[place]);
        const int axis = magnitude.x >= magnitude.y && magnitude.x >= magnitude.z ? 0
                         : magnitude.y >= magnitude.z                             ? 1
                                                                                  : 2;
        if (reference[place][axis] < 0.0f) reference[place] = -reference[place];
    }
    const auto onBackSheet = [&](std::size_t t, int corner) {
        const std::uint32_t place = placeOf(mesh.triangles[t][corner]);
        return opposed[place] && glm::dot(faceNormals[t], reference[place]) < 0.0f;
    };
    // Per vertex: 1 when a front face uses it, 2 when a back face does.
    std::vector<std::uint8_t> sheets(count, 0);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int corner = 0; corner < 3; ++corner) sheets[mesh.triangles[t][corner]] |= onBackSheet(t, corner) ? 2 : 1;
    std::vector<std::uint32_t> copyOf(count, kNoVertex);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t vertex = mesh.triangles[t][corner];
            if (sheets[vertex] != 3 || !onBackSheet(t, corner)) continue;
            if (copyOf[vertex] == kNoVertex) {
                copyOf[vertex] = std::uint32_t(mesh.positions.size());
                const glm::vec3 position = mesh.positions[vertex];
                mesh.positions.push_back(position);
                for (std::vector<glm::vec2>& texcoords : mesh.texcoords) {
                    if (texcoords.empty()) continue;
                    const glm::vec2 texcoord = texcoords[vertex];
                    texcoords.push_back(texcoord);
                }
                if (!mesh.colors.empty()) {
                    const glm::vec4 colour = mesh.colors[vertex];
                    mesh.colors.push_back(colour);
                }
            }
            mesh.triangles[t][corner] = copyOf[vertex];
        }
    }
    std::vector<std::uint32_t> classes(mesh.positions.size(), 0);
    for (std::size_t vertex = 0; vertex < count; ++vertex)
        if (sheets[vertex] == 2) classes[vertex] = 1;
    std::fill(classes.begin() + std::ptrdiff_t(count), classes.end(), 1u);
    return classes;
}

} // namespace

Mesh finalizeMesh(RawMesh raw, double modelDiagonal, const LoadOptions& options, LoadReport& report) {
    const bool fileHasNormals = !raw.normals.empty();
    if (fileHasNormals && raw.normals.size() != raw.positions.size()) {
        throw std::logic_error("finalizeMesh(): normals must be empty or one per position");
    }
    report.trianglesRead += raw.triangles.size();
    report.verticesBeforeWeld += raw.positions.size();

    // Normalise before welding so "same normal" means same direction; zero normals are repaired after welding.
    bool someNormalsUnusable = false;
    for (glm::vec3& normal : raw.normals) {
        normal = glm::vec3(normalizedOrZero(glm::dvec3(normal)));
        someNormalsUnusable = someNormalsUnusable || normal == glm::vec3(0.0f);
    }

    for (const auto* perVertex : {&raw.texcoords[0], &raw.texcoords[1]}) {
        if (!perVertex->empty() && perVertex->size() != raw.positions.size()) {
            throw std::logic_error("finalizeMesh(): texture coordinates must be empty or one per position");
        }
    }
    if (!raw.colors.empty() && raw.colors.size() != raw.positions.size()) {
        throw std::logic_error("finalizeMesh(): colours must be empty or one per position");
    }
    if (!raw.cornersSwapped.empty() && raw.cornersSwapped.size() != raw.triangles.size()) {
        throw std::logic_error("finalizeMesh(): swapped corners must be empty or one per triangle");
    }
    dropTexturesWithoutCoordinates(raw, report);
    // A texture seam or a colour border keeps its split vertices: only vertices with exactly equal attributes weld.
    const std::vector<std::uint32_t> attributeClasses = vertexAttributeClasses(raw);
    const WeldMap weld =
        weldVertices(raw.positions, raw.normals, options.weldTolerance * modelDiagonal, attributeClasses);
    // Kept in first-seen order, so keeping them all is the identity: the raw arrays serve as they are (a scan's file
    // vertices are usually distinct already).
    const bool keptAll = weld.kept.size() == raw.positions.size();
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    if (keptAll) {
        positions = std::move(raw.positions);
        normals = std::move(raw.normals);
    } else {
        positions.resize(weld.kept.size());
        normals.resize(fileHasNormals ? weld.kept.size() : 0);
        for (std::size_t output = 0; output < weld.kept.size(); ++output) {
            positions[output] = raw.positions[weld.kept[output]];
            if (fileHasNormals) {
                normals[output] = raw.normals[weld.kept[output]];
            }
        }
    }
    std::vector<glm::uvec3> triangles = std::move(raw.triangles);
    std::size_t weldedAway = 0; // triangles of distinct corners that the weld collapsed
    if (!keptAll) {
        for (glm::uvec3& triangle : triangles) {
            const glm::uvec3 welded(weld.outputOf[triangle.x], weld.outputOf[triangle.y], weld.outputOf[triangle.z]);
            if ((welded.x == welded.y || welded.y == welded.z || welded.z == welded.x) &&
                raw.positions[triangle.x] != raw.positions[triangle.y] &&
                raw.positions[triangle.y] != raw.positions[triangle.z] &&
                raw.positions[triangle.z] != raw.positions[triangle.x]) {
                ++weldedAway;
            }
            triangle = welded;
        }
    }
    // A few slivers of a scan collapse unseen; a share this large is detail the model's size swallowed (a small part
    // far from the rest, a character on a ground a thousand times its size).
    if (weldedAway > 0 && double(weldedAway) > kWeldedAwayShareToWarn * double(triangles.size())) {
        std::ostringstream message;
        message << "mesh '" << detail::excerptForMessage(raw.name) << "': " << weldedAway << " of " << triangles.size()
                << " triangles are smaller than the weld distance (" << options.weldTolerance * modelDiagonal
                << " units, " << options.weldTolerance
                << " of the model's size) and were dropped when their corners merged: details that small are lost "
                   "(--weld-distance 0 keeps them)";
        report.warnings.push_back(makeWarning(WarningKind::DetailsMerged, message.str(), "", raw.name));
    }

    // Each kept triangle's index among the file's, so triangle ids can name the file's triangles (Mesh::fileTriangles).
    const std::size_t fileTriangleCount = triangles.size();
    std::vector<std::uint32_t> fileTriangles;
    std::vector<std::uint8_t> cornersSwapped = std::move(raw.cornersSwapped);
    const auto drop = [&](std::span<const std::uint32_t> ascending) {
        if (ascending.empty()) return;
        if (fileTriangles.empty()) {
            fileTriangles.resize(triangles.size());
            std::iota(fileTriangles.begin(), fileTriangles.end(), std::uint32_t(0));
        }
        removeTriangles(triangles, ascending);
        removeTriangles(fileTriangles, ascending);
        if (!cornersSwapped.empty()) removeTriangles(cornersSwapped, ascending);
    };
    const std::vector<std::uint32_t> degenerate =
        degenerateTriangles(positions, triangles, kDegenerateAreaRelative * modelDiagonal * modelDiagonal);
    drop(degenerate);
    report.degenerateDropped += degenerate.size();
    // The triangles on vertices that differ in position or attributes, not in normal: the surface a face lies on.
    // Unless normals kept some copies of a corner apart, the weld's vertices are the surface's already.
    std::optional<WeldMap> sameSurface; // made once, when first needed
    const auto onSurface = [&]() -> std::vector<glm::uvec3> {
        if (!weld.splitByNormals) return triangles;
        if (!sameSurface) {
            std::vector<std::uint32_t> classes;
            if (!attributeClasses.empty()) {
                classes.resize(weld.kept.size());
                for (std::size_t vertex = 0; vertex < classes.size(); ++vertex)
                    classes[vertex] = attributeClasses[weld.kept[vertex]];
            }
            sameSurface = weldVertices(positions, {}, options.weldTolerance * modelDiagonal, classes);
        }
        std::vector<glm::uvec3> surface(triangles.size());
        for (std::size_t t = 0; t < triangles.size(); ++t)
            surface[t] = glm::uvec3(sameSurface->outputOf[triangles[t].x], sameSurface->outputOf[triangles[t].y],
                                    sameSurface->outputOf[triangles[t].z]);
        return surface;
    };
    // A face the file gives twice draws nothing the first does not, but it makes each of its edges one of four faces,
    // so the border and the non-manifold edges would draw every edge of a mesh given twice (a wireframe). Found on
    // the surface: a copy with normals of its own (a flat and a smooth copy) is the same face; the first's stay.
    const std::vector<std::uint32_t> repeated = repeatedTriangles(onSurface());
    drop(repeated);
    report.repeatedDropped += repeated.size();
    // A two-sided material draws the back of each face, so a face's back-to-back twin adds nothing but harm: the
    // pair's smooth normals cancel (a double-faced card shaded in black wedges) and both sheets fight for depth.
    // Twins are found on the surface too: a card's back sheet carries the opposite normals, which the material's back
    // face draws anyway.
    if (raw.material.doubleSided) {
        const std::vector<std::uint32_t> twins = backToBackTwins(onSurface());
        drop(twins);
        report.backToBackDropped += twins.size();
    }

    // Drop vertices no surviving triangle uses (unreferenced in the file, or only used by degenerate triangles), so
    // bounds and vertex counts describe the visible surface. Survivors keep their order.
    std::vector<std::uint32_t> compactIndex(positions.size(), kNoVertex);
    for (const glm::uvec3& triangle : triangles) {
        compactIndex[triangle.x] = compactIndex[triangle.y] = compactIndex[triangle.z] = 0;
    }
    Mesh mesh;
    mesh.name = std::move(raw.name);
    mesh.material = std::move(raw.material);
    mesh.nodePath = std::move(raw.nodePath);
    mesh.nodeInstance = raw.nodeInstance;
    mesh.fileTriangles = std::move(fileTriangles);
    mesh.fileTriangleCount = fileTriangleCount;
    mesh.cornersSwapped = std::move(cornersSwapped);
    const bool noAttributes = raw.texcoords[0].empty() && raw.texcoords[1].empty() && raw.colors.empty();
    if (keptAll && noAttributes &&
        std::find(compactIndex.begin(), compactIndex.end(), kNoVertex) == compactIndex.end()) {
        // Every vertex kept and used, in order: nothing to compact.
        mesh.positions = std::move(positions);
        mesh.normals = std::move(normals);
        mesh.triangles = std::move(triangles);
    } else {
        mesh.positions.reserve(positions.size());
        mesh.normals.reserve(normals.size());
        for (std::size_t vertex = 0; vertex < positions.size(); ++vertex) {
            if (compactIndex[vertex] == kNoVertex) {
                continue;
            }
            compactIndex[vertex] = std::uint32_t(mesh.positions.size());
            mesh.positions.push_back(positions[vertex]);
            if (fileHasNormals) {
                mesh.normals.push_back(normals[vertex]);
            }
            const std::uint32_t input = weld.kept[vertex];
            for (int set = 0; set < 2; ++set) {
                if (!raw.texcoords[set].empty()) mesh.texcoords[set].push_back(raw.texcoords[set][input]);
            }
            if (!raw.colors.empty()) mesh.colors.push_back(raw.colors[input]);
        }
        mesh.triangles = std::move(triangles);
        for (glm::uvec3& triangle : mesh.triangles) {
            triangle = glm::uvec3(compactIndex[triangle.x], compactIndex[triangle.y], compactIndex[triangle.z]);
        }
    }

    // A closed surface wound inside out is turned outward before the normals are computed from the winding; a one-sided
    // material's winding is the author's choice of what is culled (a baked inverted-hull outline) and stays.
    if (mesh.material.doubleSided) {
        // First each surface wound one way, so that the inside-out test below sees whole surfaces.
        const std::vector<std::uint32_t> mixed =
            turnMixedWinding(mesh.positions, mesh.triangles, mesh.normals, options.weldTolerance * modelDiagonal);
        if (!mixed.empty())
            report.warnings.push_back(makeWarning(
                WarningKind::WindingMixed,
                "mesh '" + detail::excerptForMessage(mesh.name) + "': " + std::to_string(mixed.size()) + " of " +
                    std::to_string(mesh.triangles.size()) + " triangles were wound against their neighbours (" +
                    (fileHasNormals ? "and their given normals" : "and most of their surface") +
                    "); turned so each surface is wound one way",
                "", mesh.name));
        const OutwardTurn turn =
            orientMeshOutward(mesh.positions, mesh.triangles, mesh.normals, options.weldTolerance * modelDiagonal);
        if ((!turn.turnedTriangles.empty() || !mixed.empty()) && mesh.cornersSwapped.empty())
            mesh.cornersSwapped.resize(mesh.triangles.size(), 0);
        for (const std::uint32_t triangle : mixed) mesh.cornersSwapped[triangle] ^= 1;
        for (const std::uint32_t triangle : turn.turnedTriangles) mesh.cornersSwapped[triangle] ^= 1;
        // A mirrored surface turned back outward has the file's corners again.
        if (std::find(mesh.cornersSwapped.begin(), mesh.cornersSwapped.end(), 1) == mesh.cornersSwapped.end())
            mesh.cornersSwapped.clear();
        if (turn.windingReversed)
            report.warnings.push_back(makeWarning(WarningKind::MeshInsideOut,
                                                  "mesh '" + detail::excerptForMessage(mesh.name) +
                                                      "': a closed surface wound inside out (clockwise seen from " +
                                                      "outside); its winding " +
                                                      (turn.normalsFlipped ? "and its normals were" : "was") +
                                                      " reversed so its silhouette and outline are drawn",
                                                  "", mesh.name));
        // Then normals given against the (outward) winding nearly everywhere are turned along it.
        if (const std::size_t turned = turnNormalsAlongWinding(mesh.positions, mesh.triangles, mesh.normals))
            report.warnings.push_back(makeWarning(
                WarningKind::NormalsInward,
                "mesh '" + detail::excerptForMessage(mesh.name) + "': its given normals point against its faces' " +
                    "winding (inward, as the faces are counter-clockwise seen from the front); " +
                    std::to_string(turned) + " of " + std::to_string(mesh.normals.size()) +
                    " turned round so lighting and the lines that read n . v see them outward",
                "", mesh.name));
    }

    // Texture seams and colour borders split vertices the normals weld again by position: the sheets are judged on
    // that weld. Without attributes the load's weld was by position already.
    const double weldDistance = options.weldTolerance * modelDiagonal;
    const bool weldedByPosition = attributeClasses.empty();
    WeldMap positionWeld;
    if (!fileHasNormals && !weldedByPosition) positionWeld = weldVertices(mesh.positions, {}, weldDistance);
    const std::vector<std::uint32_t> sheetClasses =
        fileHasNormals ? std::vector<std::uint32_t>{}
                       : splitOpposedSheets(mesh, weldedByPosition ? nullptr : &positionWeld);
    // Nothing but position decided this weld: the kept vertices are pairwise out of its reach, which derived data
    // welded at the same distance can rely on (weldMeshPositions()).
    if (!fileHasNormals && weldedByPosition && sheetClasses.empty()) mesh.positionsWeldedAt = weldDistance;
    if (!fileHasNormals) {
        // Smooth across texture seams and colour borders: the copies of a vertex that only its attributes split share
        // one normal, as they would have without the attributes; each of two opposed sheets keeps its own.
        if (weldedByPosition)
            mesh.normals = computeSmoothNormals(mesh.positions, mesh.triangles);
        else
            mesh.normals = computePositionWeldedNormals(
                mesh.positions, mesh.triangles,
                sheetClasses.empty() ? positionWeld : weldVertices(mesh.positions, {}, weldDistance, sheetClasses));
        mesh.normalsAreSmooth = attributeClasses.empty();
        report.normalsComputed = true;
    } else if (someNormalsUnusable) {
        const std::vector<glm::vec3> smooth = computeSmoothNormals(mesh.positions, mesh.triangles);
        for (std::size_t vertex = 0; vertex < mesh.normals.size(); ++vertex) {
            if (mesh.normals[vertex] == glm::vec3(0.0f)) {
                mesh.normals[vertex] = smooth[vertex];
            }
        }
    }
    report.verticesAfterWeld += mesh.positions.size();
    return mesh;
}

} // namespace inkgraph
