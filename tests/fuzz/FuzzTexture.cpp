// libFuzzer target: texture decoding (scene/TextureImage.h decodeSceneImage()) of an image a model embeds, as the
// passes that sample a material's texture decode it: the header check against the memory limit, then the decoder.
// Inputs of odd length declare "image/png", the others nothing, so both the declared and the sniffed path are driven.
#include "scene/Scene.h"
#include "scene/TextureImage.h"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

/** Small enough that a header of a few bytes can ask for more (8192 x 8192 RGBA with mipmaps is 341 MiB), so the
 *  limit's own path is fuzzed rather than the machine's memory. */
constexpr std::size_t kTextureByteLimit = std::size_t(256) << 20;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    inkgraph::SceneImage image;
    image.name = "fuzz.png";
    image.mimeType = size % 2 == 1 ? "image/png" : "";
    image.encoded = std::make_shared<const std::vector<unsigned char>>(data, data + size);
    try {
        const inkgraph::DecodedImage decoded = inkgraph::decodeSceneImage(image, 0, "fuzz.gltf", kTextureByteLimit);
        // A decoded image keeps decodeSceneImage()'s promises: pixels, within the limit.
        if (decoded.width <= 0 || decoded.height <= 0 || decoded.rgba == nullptr)
            throw std::logic_error("FuzzTexture: a decoded image without pixels");
        if (inkgraph::decodedImageBytes(decoded.width, decoded.height) > kTextureByteLimit)
            throw std::logic_error("FuzzTexture: a decoded image above the byte limit");
        // Touch the last pixel: the buffer must hold width x height x 4 bytes (ASan checks it).
        const std::size_t last = std::size_t(decoded.width) * std::size_t(decoded.height) * 4 - 1;
        volatile unsigned char sink = decoded.rgba.get()[last];
        (void)sink;
    } catch (const inkgraph::SceneError&) {
    }
    return 0;
}
