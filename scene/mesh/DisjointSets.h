#pragma once
/** @file Union-find over the ids 0..count-1, with path halving: the connected surfaces of a mesh (OutwardWinding.cpp)
 *  and the chains of its edges (EdgeAdjacency.cpp). Each set's root is its smallest id, so the roots do not depend
 *  on the order of the joins. */

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace inkgraph {

class DisjointSets {
public:
    /** `count` sets of one id each. */
    explicit DisjointSets(std::size_t count) : mParent(count) {
        std::iota(mParent.begin(), mParent.end(), std::uint32_t(0));
    }

    /** The root of the set holding `id`: its smallest id. */
    std::uint32_t find(std::uint32_t id) {
        while (mParent[id] != id) id = mParent[id] = mParent[mParent[id]];
        return id;
    }

    /** Merges the sets holding `a` and `b`. */
    void join(std::uint32_t a, std::uint32_t b) {
        a = find(a);
        b = find(b);
        if (a != b) mParent[std::max(a, b)] = std::min(a, b);
    }

private:
    std::vector<std::uint32_t> mParent; ///< a smaller id of the same set, or the id itself at a root
};

} // namespace inkgraph
