// libFuzzer target: --shademap files: the PNG chunk filter and libpng behind app/ImageFiles' readPngImage(), the
// header checks before allocation, shadeMapFromImage() and the specular band table the comic shader gets. The bytes
// are written to a file named .png, as a user's map would be (the seeds include other formats under that name).
#include "app/Render.h"
#include "passes/shade/ShadeMap.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <unistd.h>

namespace {

/** One scratch file per process, rewritten for each input. */
const std::string& scratchPath() {
    static const std::string path = [] {
        char name[] = "/tmp/inkgraph-fuzz-shademap-XXXXXX.png";
        const int descriptor = ::mkstemps(name, 4);
        if (descriptor < 0) throw std::runtime_error("FuzzShadeMap: cannot create a scratch file in /tmp");
        ::close(descriptor);
        return std::string(name);
    }();
    return path;
}

void writeScratch(const std::uint8_t* data, std::size_t size) {
    std::FILE* file = std::fopen(scratchPath().c_str(), "wb");
    // fwrite's buffer must not be null even for no bytes (UBSan: the empty input arrives as a null pointer).
    if (file == nullptr || (size > 0 && std::fwrite(data, 1, size, file) != size) || std::fclose(file) != 0)
        throw std::runtime_error("FuzzShadeMap: cannot write '" + scratchPath() + "'");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    writeScratch(data, size);
    for (const bool oneDimensional : {false, true}) {
        try {
            const inkgraph::ShadeMap map = inkgraph::readShadeMapFile(scratchPath(), oneDimensional);
            if (map.texels.type() != CV_8UC4 || map.texels.empty())
                throw std::logic_error("FuzzShadeMap: a checked map is not non-empty CV_8UC4");
            for (const double shininess : {0.0, 1.0, 32.0, 1e6}) inkgraph::specularRowBands(map, shininess);
        } catch (const inkgraph::InputFileError&) {
        }
    }
    return 0;
}
