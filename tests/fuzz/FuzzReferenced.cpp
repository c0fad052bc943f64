// libFuzzer target: scene::referencedFiles(), the batch's pre-pass that names the files a model reads besides itself
// (glTF buffers, images and shade maps; a GLB's or VRM's JSON chunk; an OBJ's material libraries and their textures).
// The first byte picks the model's kind: 'b' GLB, 'v' VRM, 'o' OBJ, anything else glTF; the rest is the file. For an
// OBJ, the bytes after the first NUL (when there is one) are written beside it as "m.mtl", the library the seeds
// name. The files are written to a private, otherwise empty folder. referencedFiles() is best effort and throws
// nothing: any exception fails, as does a named file that is empty.
#include "scene/Scene.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace {

/** One folder per process, emptied before each input. */
const std::filesystem::path& scratchFolder() {
    static const std::filesystem::path folder = [] {
        char name[] = "/tmp/inkgraph-fuzz-referenced-XXXXXX";
        if (::mkdtemp(name) == nullptr) throw std::runtime_error("FuzzReferenced: cannot create a folder in /tmp");
        return std::filesystem::path(name);
    }();
    return folder;
}

void writeFile(const std::filesystem::path& path, std::string_view bytes) {
    std::ofstream file(path, std::ios::binary);
    file.write(bytes.data(), std::streamsize(bytes.size()));
    if (!file.flush()) throw std::runtime_error("FuzzReferenced: cannot write '" + path.string() + "'");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const char kind = char(data[0]);
    std::string_view model(reinterpret_cast<const char*>(data) + 1, size - 1);
    const std::filesystem::path& folder = scratchFolder();
    for (const auto& entry : std::filesystem::directory_iterator(folder)) std::filesystem::remove_all(entry.path());
    const char* extension = kind == 'b' ? ".glb" : kind == 'v' ? ".vrm" : kind == 'o' ? ".obj" : ".gltf";
    const std::filesystem::path path = folder / (std::string("fuzz") + extension);
    if (kind == 'o') {
        if (const std::size_t nul = model.find('\0'); nul != std::string_view::npos) {
            writeFile(folder / "m.mtl", model.substr(nul + 1));
            model = model.substr(0, nul);
        }
    }
    writeFile(path, model);
    for (const std::string& file : inkgraph::referencedFiles(path.string()))
        if (file.empty()) throw std::logic_error("FuzzReferenced: an empty file name");
    return 0;
}
