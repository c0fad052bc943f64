#include "scene/TextureImage.h"

#include "scene/FormatReaders.h"
#include "scene/Scene.h"

#include <stb/stb_image.h>

#include <climits>
#include <fstream>
#include <iterator>
#include <memory>

namespace inkgraph {
namespace {

[[noreturn]] void fail(const SceneImage& image, const std::string& modelPath, const std::string& problem) {
    throw SceneError("decodeSceneImage(): '" + modelPath + "' image '" + detail::excerptForMessage(image.name) +
                     "': " + problem);
}

std::vector<unsigned char> readImageFile(const SceneImage& image, const std::string& modelPath) {
    std::ifstream file(image.path, std::ios::binary);
    if (!file) fail(image, modelPath, "cannot open '" + image.path + "'");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (file.bad()) fail(image, modelPath, "cannot read '" + image.path + "'");
    return bytes;
}

struct StbFree {
    void operator()(unsigned char* pixels) const { stbi_image_free(pixels); }
};

} // namespace

std::size_t decodedImageBytes(int width, int height) {
    const std::size_t base = std::size_t(width) * std::size_t(height) * 4;
    return base + base / 3;
}

DecodedImage decodeSceneImage(const SceneImage& image, const std::string& modelPath, std::size_t byteLimit) {
    std::vector<unsigned char> fromFile;
    const std::vector<unsigned char>* bytes = image.encoded.get();
    if (bytes == nullptr) {
        if (image.path.empty()) fail(image, modelPath, "has neither data nor a file");
        fromFile = readImageFile(image, modelPath);
        bytes = &fromFile;
    }
    if (bytes->empty() || bytes->size() > std::size_t(INT_MAX))
        fail(image, modelPath, "has " + std::to_string(bytes->size()) + " bytes, not an image stb_image can read");
    const int byteCount = int(bytes->size());
    int width = 0, height = 0, channels = 0;
    // The header alone first: a 60000 x 60000 PNG of a few kilobytes must be refused before 14 GB are allocated.
    if (stbi_info_from_memory(bytes->data(), byteCount, &width, &height, &channels) == 0)
        fail(image, modelPath,
             std::string("cannot be decoded (stb_image: ") + (stbi_failure_reason() ? stbi_failure_reason() : "?") +
                 (image.mimeType.empty() ? ")" : "; declared " + image.mimeType + ")"));
    if (width <= 0 || height <= 0) fail(image, modelPath, "has no pixels");
    const std::size_t needed = decodedImageBytes(width, height);
    if (needed > byteLimit)
        fail(image, modelPath,
             std::to_string(width) + "x" + std::to_string(height) + " decodes to " + std::to_string(needed) +
                 " bytes with its mipmaps, more than the " + std::to_string(byteLimit) +
                 " bytes the memory limit leaves for textures (raise --memory-limit)");
    int decodedWidth = 0, decodedHeight = 0;
    std::unique_ptr<unsigned char, StbFree> pixels(
        stbi_load_from_memory(bytes->data(), byteCount, &decodedWidth, &decodedHeight, &channels, 4));
    if (!pixels || decodedWidth != width || decodedHeight != height)
        fail(image, modelPath,
             std::string("cannot be decoded (stb_image: ") + (stbi_failure_reason() ? stbi_failure_reason() : "?") +
                 ")");
    DecodedImage decoded;
    decoded.width = width;
    decoded.height = height;
    decoded.rgba.assign(pixels.get(), pixels.get() + std::size_t(width) * std::size_t(height) * 4);
    return decoded;
}

} // namespace inkgraph
