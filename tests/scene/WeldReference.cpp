#include "WeldReference.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace inkgraph::test {
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
 *  occupancy bitmap (16 bits per vertex, cache-resident) answers those without touching the large slot array. */
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

    std::uint32_t head(const CellKey& key) const {
        const std::uint64_t hash = hashCell(key);
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
    std::uint32_t push(const CellKey& key, std::uint32_t vertex) {
        const std::uint64_t hash = hashCell(key);
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

} // namespace

WeldMap referenceWeldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, double distance,
                              std::span<const std::uint32_t> attributeClasses) {
    if (!normals.empty() && normals.size() != positions.size()) {
        throw std::logic_error("referenceWeldVertices(): normals must be empty or one per position");
    }
    if (!attributeClasses.empty() && attributeClasses.size() != positions.size()) {
        throw std::logic_error("referenceWeldVertices(): attribute classes must be empty or one per position");
    }
    if (positions.size() >= kNoVertex) {
        throw std::length_error("referenceWeldVertices(): too many vertices for 32-bit indices");
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

    for (std::uint32_t input = 0; input < positions.size(); ++input) {
        const glm::dvec3 point(positions[input]);
        const glm::dvec3 scaled = (point - box.min) / cellSize;
        const glm::dvec3 cellFloor = glm::floor(scaled);
        const CellKey home{std::int32_t(cellFloor.x), std::int32_t(cellFloor.y), std::int32_t(cellFloor.z)};
        const glm::dvec3 fraction = scaled - cellFloor;
        const std::int32_t stepX = fraction.x < 0.5 ? -1 : 1;
        const std::int32_t stepY = fraction.y < 0.5 ? -1 : 1;
        const std::int32_t stepZ = fraction.z < 0.5 ? -1 : 1;

        std::uint32_t best = kNoVertex;
        double bestDistanceSquared = maxDistanceSquared;
        for (int corner = 0; corner < 8; ++corner) {
            const CellKey cell{home.x + ((corner & 1) ? stepX : 0), home.y + ((corner & 2) ? stepY : 0),
                               home.z + ((corner & 4) ? stepZ : 0)};
            for (std::uint32_t candidate = table.head(cell); candidate != kNoVertex;
                 candidate = nextInCell[candidate]) {
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
        nextInCell.push_back(table.push(home, output));
    }
    return map;
}

} // namespace inkgraph::test
