#include "scene/TextureImage.h"

#include "scene/FormatReaders.h"
#include "scene/Scene.h"

#include <stb/stb_image.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <vector>

namespace inkgraph {
namespace {

struct Failure {
    const std::string& label;
    const std::string& modelPath;

    [[noreturn]] void operator()(const std::string& problem) const {
        throw SceneError("decodeSceneImage(): '" + modelPath + "' " + label + ": " + problem);
    }
};

std::string limitText(std::size_t byteLimit) {
    return std::to_string(byteLimit) + " bytes the memory limit leaves for textures (raise --memory-limit)";
}

/** The external file's bytes, after checking that it is a regular file the limit can hold: a FIFO would block, a
 *  device or /proc file never end, a sparse 20 GB file exhaust memory. */
std::vector<unsigned char> readImageFile(const SceneImage& image, std::size_t byteLimit, const Failure& fail) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(image.path, error);
    if (error || !std::filesystem::exists(status))
        fail("its file '" + image.path + "' cannot be found" + (error ? " (" + error.message() + ")" : ""));
    if (!std::filesystem::is_regular_file(status)) fail("its file '" + image.path + "' is not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(image.path, error);
    if (error) fail("cannot read the size of '" + image.path + "' (" + error.message() + ")");
    if (size > byteLimit)
        fail("its file '" + image.path + "' is " + std::to_string(size) + " bytes, more than the " +
             limitText(byteLimit));
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    std::ifstream file(image.path, std::ios::binary);
    if (!file) fail("cannot open '" + image.path + "' (" + std::strerror(errno) + ")");
    file.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    if (std::size_t(file.gcount()) != bytes.size())
        fail("cannot read '" + image.path + "' (" + std::to_string(file.gcount()) + " of " +
             std::to_string(bytes.size()) + " bytes read)");
    return bytes;
}

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return std::string("stb_image says \"") + (reason ? reason : "?") + "\"";
}

} // namespace

std::size_t decodedImageBytes(int width, int height) {
    const std::size_t base = std::size_t(width) * std::size_t(height) * 4;
    return base + base + base / 3;
}

DecodedImage decodeSceneImage(const SceneImage& image, std::size_t index, const std::string& modelPath,
                              std::size_t byteLimit) {
    const std::string label = "image " + std::to_string(index) +
                              (image.name.empty() ? std::string() : " '" + detail::excerptForMessage(image.name) + "'");
    const Failure fail{label, modelPath};
    std::vector<unsigned char> fromFile;
    const std::vector<unsigned char>* bytes = image.encoded.get();
    if (bytes == nullptr) {
        if (image.path.empty()) fail("has neither data nor a file");
        fromFile = readImageFile(image, byteLimit, fail);
        bytes = &fromFile;
    }
    if (bytes->empty()) fail("is empty (0 bytes)");
    if (bytes->size() > std::size_t(INT_MAX))
        fail("is " + std::to_string(bytes->size()) + " bytes, more than stb_image reads (2 GiB)");
    const int byteCount = int(bytes->size());
    const std::string declared = image.mimeType.empty() ? "" : " (declared " + image.mimeType + ")";
    int width = 0, height = 0, channels = 0;
    // The header alone first: a 60000 x 60000 PNG of a few kilobytes must be refused before 14 GB are allocated.
    if (stbi_info_from_memory(bytes->data(), byteCount, &width, &height, &channels) == 0)
        fail("cannot be decoded: not a PNG, JPEG, BMP, TGA, GIF, PSD, HDR, PIC or PNM image stb_image reads, or one it "
             "finds corrupt or too large" +
             declared + " (" + stbReason() + ")");
    if (width <= 0 || height <= 0) fail("has no pixels");
    const std::size_t needed = decodedImageBytes(width, height);
    if (needed > byteLimit)
        fail(std::to_string(width) + "x" + std::to_string(height) + " needs " + std::to_string(needed) +
             " bytes to decode and upload with its mipmaps, more than the " + limitText(byteLimit));
    int decodedWidth = 0, decodedHeight = 0;
    unsigned char* pixels =
        stbi_load_from_memory(bytes->data(), byteCount, &decodedWidth, &decodedHeight, &channels, 4);
    if (pixels == nullptr) {
        const char* reason = stbi_failure_reason();
        if (reason != nullptr && std::strcmp(reason, "outofmem") == 0) throw std::bad_alloc(); // the machine's limit
        fail("cannot be decoded: corrupt or truncated" + declared + " (" + stbReason() + ")");
    }
    DecodedImage decoded;
    decoded.rgba = std::shared_ptr<const unsigned char>(
        pixels, [](const unsigned char* p) { stbi_image_free(const_cast<unsigned char*>(p)); });
    if (decodedWidth != width || decodedHeight != height)
        fail("decodes to " + std::to_string(decodedWidth) + "x" + std::to_string(decodedHeight) +
             " although its header says " + std::to_string(width) + "x" + std::to_string(height));
    decoded.width = width;
    decoded.height = height;
    return decoded;
}

} // namespace inkgraph
