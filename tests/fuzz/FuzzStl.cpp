// libFuzzer target: the STL reader, binary and ASCII, (scene/formats/StlReader.cpp) and what the line passes derive
// from its meshes.
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    inkgraph::fuzz::loadAndDerive("fuzz.stl", inkgraph::fuzz::bytesOf(data, size));
    return 0;
}
