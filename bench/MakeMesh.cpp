// Writes a mesh as OBJ, for whole-process benchmarks on sizes no bundled model has:
//   inkgraph_make_mesh sphere|torus TRIANGLES OUT.obj     a procedural mesh of about TRIANGLES triangles
//   inkgraph_make_mesh subdivide K IN OUT.obj            every triangle of IN split into K x K (the same surface,
//                                                        K^2 times the triangles: a scan at a production density)
#include "bench/LargeMesh.h"
#include "scene/mesh/Procedural.h"
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
using inkgraph::bench::subdivided;
using inkgraph::bench::writeObj;

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
    if (!writeObj(meshes, outputPath)) {
        std::fprintf(stderr, "%s: cannot write '%s'\n", argv[0], outputPath);
        return 1;
    }
    std::size_t triangleCount = 0, vertexCount = 0;
    for (const Mesh& mesh : meshes) {
        triangleCount += mesh.triangles.size();
        vertexCount += mesh.positions.size();
    }
    std::printf("%s: %zu triangles, %zu vertices\n", outputPath, triangleCount, vertexCount);
    return 0;
}
