// libFuzzer target: the PLY reader, ASCII and binary of either byte order (scene/formats/PlyReader.cpp), and what the
// line passes derive from its meshes.
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    inkgraph::fuzz::loadAndDerive("fuzz.ply", inkgraph::fuzz::bytesOf(data, size));
    return 0;
}
