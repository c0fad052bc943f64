#pragma once
// Meshes at production densities for benchmarks, shared by inkgraph_make_mesh and inkgraph_bench: a model
// subdivided, written as OBJ.
#include "scene/Scene.h"

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace inkgraph::bench {

/** Each triangle split into k x k by its barycentric grid. A point on an edge is made once, from the edge's
 *  lower-numbered end, so the two triangles that share the edge share its points and the surface stays closed. */
inline Mesh subdivided(const Mesh& input, int k) {
    Mesh mesh;
    mesh.positions = input.positions;
    std::map<std::pair<unsigned, unsigned>, unsigned> edgeStart; // (low, high) -> index of its first inner point
    const auto edgePoint = [&](unsigned a, unsigned b, int step) -> unsigned { // step 1..k-1 from a toward b
        if (step == 0) return a;
        if (step == k) return b;
        const bool flipped = a > b;
        const unsigned low = flipped ? b : a, high = flipped ? a : b;
        auto [at, inserted] = edgeStart.try_emplace({low, high}, unsigned(mesh.positions.size()));
        if (inserted)
            for (int i = 1; i < k; ++i)
                mesh.positions.push_back(input.positions[low] +
                                         (input.positions[high] - input.positions[low]) * (float(i) / float(k)));
        return at->second + unsigned((flipped ? k - step : step) - 1);
    };
    for (const glm::uvec3& t : input.triangles) {
        // grid[i][j]: the point i steps from corner x toward y and j toward z (i + j <= k).
        std::vector<std::vector<unsigned>> grid(size_t(k) + 1);
        for (int i = 0; i <= k; ++i) {
            grid[size_t(i)].resize(size_t(k - i) + 1);
            for (int j = 0; i + j <= k; ++j) {
                unsigned index;
                if (j == 0)
                    index = edgePoint(t.x, t.y, i);
                else if (i == 0)
                    index = edgePoint(t.x, t.z, j);
                else if (i + j == k)
                    index = edgePoint(t.y, t.z, j);
                else {
                    index = unsigned(mesh.positions.size());
                    const glm::vec3 x = input.positions[t.x], y = input.positions[t.y], z = input.positions[t.z];
                    mesh.positions.push_back(x + (y - x) * (float(i) / float(k)) + (z - x) * (float(j) / float(k)));
                }
                grid[size_t(i)][size_t(j)] = index;
            }
        }
        for (int i = 0; i < k; ++i)
            for (int j = 0; i + j < k; ++j) {
                mesh.triangles.push_back(
                    {grid[size_t(i)][size_t(j)], grid[size_t(i) + 1][size_t(j)], grid[size_t(i)][size_t(j) + 1]});
                if (i + j + 1 < k)
                    mesh.triangles.push_back({grid[size_t(i) + 1][size_t(j)], grid[size_t(i) + 1][size_t(j) + 1],
                                              grid[size_t(i)][size_t(j) + 1]});
            }
    }
    return mesh;
}

/** Writes `meshes` as one OBJ (positions at 7 significant digits, faces 1-based); false when the file cannot be
 *  written. */
inline bool writeObj(const std::vector<Mesh>& meshes, const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "w");
    if (file == nullptr) return false;
    std::size_t base = 1;
    for (const Mesh& mesh : meshes) {
        for (const auto& p : mesh.positions) std::fprintf(file, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
        for (const auto& t : mesh.triangles) std::fprintf(file, "f %zu %zu %zu\n", t.x + base, t.y + base, t.z + base);
        base += mesh.positions.size();
    }
    return std::fclose(file) == 0;
}

} // namespace inkgraph::bench
