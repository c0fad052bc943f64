#pragma once
/** @file A Draco-compressed mesh decoded to plain arrays, behind a boundary: this is the whole interface of the
 *  shared library inkgraph_draco, which links Debian's libdraco.a with every symbol of it hidden. Debian's libdraco
 *  (the .so and the .a alike) carries its own copy of tinygltf and stb; in the same link as Debian's libtinygltf, that
 *  copy replaces Debian's tinygltf in the executable (scene/CMakeLists.txt). No tinygltf or draco type crosses here. */

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#define INKGRAPH_DRACO_API __attribute__((visibility("default")))

namespace inkgraph::detail {

struct DracoMesh {
    struct Attribute {
        int components = 0;
        bool normalized = false;   ///< Draco stored normalized integers; `values` are already in [0, 1] / [-1, 1]
        std::vector<float> values; ///< components per point, converted to float by Draco
    };
    std::size_t pointCount = 0;
    std::vector<std::uint32_t> indices;            ///< three per face, each below pointCount
    std::map<std::uint32_t, Attribute> attributes; ///< by Draco unique id
    std::string error;                             ///< empty when decoded; else why not
};

/** What a Draco mesh's header declares, read without decoding: faces, and the vertices its connectivity encodes. */
struct DracoCounts {
    std::size_t points = 0;
    std::size_t faces = 0;
    std::string error; ///< empty when read; else why not (not Draco, a point cloud, cut short)
};

INKGRAPH_DRACO_API DracoCounts readDracoCounts(const unsigned char* data, std::size_t size);

/** Decodes `size` bytes of a Draco mesh. `admit(points, faces)` is called with the header's counts before Draco
 *  decodes anything, and once more with whatever the decoded mesh holds beyond them before anything is copied out
 *  (it may throw, e.g. a memory budget's refusal, which propagates). Failures of the data are reported in
 *  DracoMesh::error, not thrown. */
INKGRAPH_DRACO_API DracoMesh decodeDracoMesh(const unsigned char* data, std::size_t size,
                                             const std::function<void(std::size_t, std::size_t)>& admit);

} // namespace inkgraph::detail
