// Writes a mesh as OBJ, for whole-process benchmarks on sizes no bundled model has:
//   inkgraph_make_mesh sphere|torus TRIANGLES OUT.obj     a procedural mesh of about TRIANGLES triangles
//   inkgraph_make_mesh subdivide K IN OUT.obj            every triangle of IN split into K x K (the same surface,
//                                                        K^2 times the triangles: a scan at a production density)
#include "scene/Procedural.h"
#include "scene/Scene.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <utility>

namespace {

using inkgraph::Mesh;

/** Each triangle split into k x k by its barycentric grid. A point on an edge is made once, from the edge's
 *  lower-numbered end, so the two triangles that share the edge share its points and the surface stays closed. */
Mesh subdivided(const Mesh& input, int k) {
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

int usage(const char* program) {
    std::fprintf(stderr, "usage: %s sphere|torus TRIANGLES OUT.obj\n       %s subdivide K IN OUT.obj\n", program,
                 program);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 4) return usage(argv[0]);
    const std::string shape = argv[1];
    std::vector<Mesh> meshes;
    const char* outputPath = argv[3];
    if (shape == "subdivide") {
        const long k = std::strtol(argv[2], nullptr, 10);
        if (argc != 5 || k < 1 || k > 64) return usage(argv[0]);
        outputPath = argv[4];
        try {
            const inkgraph::Scene scene = inkgraph::loadScene(argv[3]);
            for (const Mesh& mesh : scene.meshes) meshes.push_back(subdivided(mesh, int(k)));
        } catch (const std::exception& error) {
            std::fprintf(stderr, "%s: %s\n", argv[0], error.what());
            return 1;
        }
    } else {
        const long triangles = std::strtol(argv[2], nullptr, 10);
        if (argc != 4 || (shape != "sphere" && shape != "torus") || triangles < 8) return usage(argv[0]);
        const int side = std::max(3, int(std::sqrt(triangles / 4.0)));
        meshes.push_back(shape == "sphere" ? inkgraph::makeUvSphere({0, 0, 0}, 1.0f, 2 * side, side)
                                           : inkgraph::makeTorus(1.0f, 0.35f, 2 * side, side));
    }
    std::FILE* file = std::fopen(outputPath, "w");
    if (file == nullptr) {
        std::fprintf(stderr, "%s: cannot write '%s'\n", argv[0], outputPath);
        return 1;
    }
    std::size_t base = 1, triangleCount = 0, vertexCount = 0;
    for (const Mesh& mesh : meshes) {
        for (const auto& p : mesh.positions) std::fprintf(file, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
        for (const auto& t : mesh.triangles) std::fprintf(file, "f %zu %zu %zu\n", t.x + base, t.y + base, t.z + base);
        base += mesh.positions.size();
        triangleCount += mesh.triangles.size();
        vertexCount += mesh.positions.size();
    }
    const bool written = std::fclose(file) == 0;
    std::printf("%s: %zu triangles, %zu vertices\n", outputPath, triangleCount, vertexCount);
    return written ? 0 : 1;
}
