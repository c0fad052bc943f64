// libFuzzer target: the OBJ reader (scene/formats/ObjReader.cpp) and what the line passes derive from its meshes.
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    inkgraph::fuzz::loadAndDerive("fuzz.obj", inkgraph::fuzz::bytesOf(data, size));
    return 0;
}
