// Writes a procedural mesh as OBJ, for whole-process benchmarks on sizes no bundled model has:
//   inkgraph_make_mesh sphere|torus TRIANGLES OUT.obj
#include "scene/Procedural.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s sphere|torus TRIANGLES OUT.obj\n", argv[0]);
        return 2;
    }
    const std::string shape = argv[1];
    const long triangles = std::strtol(argv[2], nullptr, 10);
    if ((shape != "sphere" && shape != "torus") || triangles < 8) {
        std::fprintf(stderr, "%s: shape must be sphere or torus and TRIANGLES at least 8\n", argv[0]);
        return 2;
    }
    const int side = std::max(3, int(std::sqrt(triangles / 4.0)));
    const inkgraph::Mesh mesh = shape == "sphere" ? inkgraph::makeUvSphere({0, 0, 0}, 1.0f, 2 * side, side)
                                                  : inkgraph::makeTorus(1.0f, 0.35f, 2 * side, side);
    std::FILE* file = std::fopen(argv[3], "w");
    if (file == nullptr) {
        std::fprintf(stderr, "%s: cannot write '%s'\n", argv[0], argv[3]);
        return 1;
    }
    for (const auto& p : mesh.positions) std::fprintf(file, "v %.7g %.7g %.7g\n", p.x, p.y, p.z);
    for (const auto& t : mesh.triangles) std::fprintf(file, "f %u %u %u\n", t.x + 1, t.y + 1, t.z + 1);
    const bool written = std::fclose(file) == 0;
    std::printf("%s: %zu triangles, %zu vertices\n", argv[3], mesh.triangles.size(), mesh.positions.size());
    return written ? 0 : 1;
}
