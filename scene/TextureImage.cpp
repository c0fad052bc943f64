#include "scene/TextureImage.h"

#include "scene/MessageText.h"
#include "scene/Scene.h"
#include "scene/formats/FormatReaders.h"

#include "codecs/JpegCodec.h"
#include "codecs/PngChunks.h"
#include "codecs/PngCodec.h"
#include "codecs/WebpCodec.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <new>
#include <set>
#include <string_view>
#include <vector>

namespace inkgraph {
namespace {

struct Failure {
    const std::string& label;
    const std::string& modelPath;

    /** The image cannot be used at all (corrupt, truncated, unsupported, empty): the caller may draw without it. */
    [[noreturn]] void operator()(const std::string& problem) const {
        throw ImageUnusableError(message(problem), problem, ImageUnusableError::Reason::Undecodable);
    }
    /** Its file is not there to read. */
    [[noreturn]] void missing(const std::string& problem) const {
        throw ImageUnusableError(message(problem), problem, ImageUnusableError::Reason::Missing);
    }
    /** The image is fine but the memory limit cannot hold it: an error of the run's size, not of the model. */
    [[noreturn]] void overLimit(const std::string& problem) const { throw SceneError(message(problem)); }

    std::string message(const std::string& problem) const {
        return "decodeSceneImage(): '" + modelPath + "' " + label + ": " + problem;
    }
};

constexpr std::string_view kPngSignature("\x89PNG\r\n\x1a\n", 8);
constexpr std::string_view kJpegSignature("\xff\xd8\xff", 3);

std::string limitText(std::size_t byteLimit) {
    return std::to_string(byteLimit) + " bytes the memory limit leaves for textures (raise --memory-limit)";
}

/** The external file's bytes, after checking that it is a regular file the limit can hold: a FIFO would block, a
 *  device or /proc file never end, a sparse 20 GB file exhaust memory. */
std::vector<unsigned char> readImageFile(const SceneImage& image, std::size_t byteLimit, const Failure& fail) {
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(image.path, error);
    if (error || !std::filesystem::exists(status)) {
        if (const std::optional<std::string> why = detail::whyFileIsMissing(image.path))
            fail.missing("its file '" + image.path + "' " + *why);
        fail.missing("its file '" + image.path + "' cannot be found" + (error ? " (" + error.message() + ")" : ""));
    }
    if (!std::filesystem::is_regular_file(status)) fail.missing("its file '" + image.path + "' is not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(image.path, error);
    if (error) fail("cannot read the size of '" + image.path + "' (" + error.message() + ")");
    if (size > byteLimit)
        fail.overLimit("its file '" + image.path + "' is " + std::to_string(size) + " bytes, more than the " +
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

bool startsWith(const std::vector<unsigned char>& bytes, std::string_view prefix) {
    return bytes.size() >= prefix.size() && std::memcmp(bytes.data(), prefix.data(), prefix.size()) == 0;
}

/** The pixels of a texture: width x height x 4 bytes, allocated only after the caller's check has passed. */
struct PixelBuffer {
    std::shared_ptr<unsigned char> pixels;
    std::vector<unsigned char*> rows;
    std::vector<unsigned char*> allocate(std::uint32_t width, std::uint32_t height) {
        const std::size_t rowBytes = std::size_t(width) * 4;
        pixels = std::shared_ptr<unsigned char>(new unsigned char[rowBytes * height],
                                                std::default_delete<unsigned char[]>());
        rows.resize(height);
        for (std::uint32_t row = 0; row < height; ++row) rows[row] = pixels.get() + rowBytes * row;
        return rows;
    }
};

/** The formats stb_image reads besides PNG and JPEG (BMP, TGA, GIF, PSD, HDR, PIC; not PNM, below). stb allocates a
 * whole image of its own before converting it to 8-bit RGBA: the file's samples (32-bit float for HDR, up to 16-bit for
 * PSD, 4 channels), freed after the conversion, or for a GIF its background and history beside the frame. */
std::size_t stbDecoderBytes(const std::vector<unsigned char>& bytes, int width, int height) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const bool floatSamples = stbi_is_hdr_from_memory(bytes.data(), int(bytes.size())) != 0;
    return pixels * (floatSamples ? 16 : 8);
}

using AdmitImage = std::function<void(std::uint64_t, std::uint64_t, std::size_t)>;

DecodedImage decodeWithStb(const std::vector<unsigned char>& bytes, const std::string& declared,
                           const AdmitImage& admit, const Failure& fail) {
    if (bytes.size() > std::size_t(INT_MAX))
        fail("is " + std::to_string(bytes.size()) + " bytes, more than stb_image reads (2 GiB)");
    const int byteCount = int(bytes.size());
    // stb_image's PNM reader is not safe on other people's files (fuzz_texture): it converts a 16-bit file's samples
    // with its 8-bit conversion and then reads twice the bytes that buffer holds, and it leaves the pixels of a
    // truncated file uninitialised. PNM is no texture format of glTF's or of the tools that write OBJ materials.
    if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '6'))
        fail("is a PNM image, which is not read as a texture (stb_image's PNM reader over-reads 16-bit files and "
             "leaves truncated ones undecoded); convert it to PNG" +
             declared);
    int width = 0, height = 0, channels = 0;
    if (stbi_info_from_memory(bytes.data(), byteCount, &width, &height, &channels) == 0)
        fail(std::string("cannot be decoded: not a ") + kTextureFormatNames +
             " image, or one stb_image finds corrupt or too large" + declared + " (" + stbReason() + ")");
    admit(std::uint64_t(std::max(width, 0)), std::uint64_t(std::max(height, 0)), stbDecoderBytes(bytes, width, height));
    int decodedWidth = 0, decodedHeight = 0;
    unsigned char* pixels = stbi_load_from_memory(bytes.data(), byteCount, &decodedWidth, &decodedHeight, &channels, 4);
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
    const std::string declared = image.mimeType.empty() ? "" : " (declared " + image.mimeType + ")";
    // The header is the file's claim; this judges it, with what the decoder itself will allocate on top of the
    // pixels, before anything of the image's size is allocated.
    const auto admit = [&](std::uint64_t width, std::uint64_t height, std::size_t decoderBytes) {
        if (width == 0 || height == 0) fail("has no pixels");
        const auto size = std::to_string(width) + "x" + std::to_string(height);
        if (width > std::uint64_t(INT_MAX) || height > std::uint64_t(INT_MAX) ||
            width * height > std::uint64_t(SIZE_MAX) / 32)
            fail.overLimit(size + " pixels declared, far more than the " + limitText(byteLimit));
        // An external file's bytes are held while it decodes; embedded ones were charged with the model.
        const std::size_t needed = decodedImageBytes(int(width), int(height)) + decoderBytes + fromFile.size();
        if (needed > byteLimit)
            fail.overLimit(size + " needs " + std::to_string(needed) +
                           " bytes to decode and upload with its mipmaps, more than the " + limitText(byteLimit));
    };
    DecodedImage decoded;
    PixelBuffer buffer;
    if (startsWith(*bytes, kPngSignature)) {
        // libpng, bounded: only the critical chunks reach it (no compressed text or profile), and it inflates the
        // image data row by row into the buffer and no further, however much the data would inflate to.
        try {
            const std::vector<unsigned char> png =
                criticalPngChunks(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
            decodePngBytes(png.data(), png.size(), PngExpansion::Rgba8, [&](const PngLayout& layout) {
                admit(layout.width, layout.height, 0);
                decoded.width = int(layout.width);
                decoded.height = int(layout.height);
                return buffer.allocate(layout.width, layout.height);
            });
        } catch (const std::invalid_argument& problem) {
            fail("cannot be decoded: a broken PNG" + declared + " (" + problem.what() + ")");
        } catch (const std::runtime_error& problem) {
            if (dynamic_cast<const SceneError*>(&problem) != nullptr) throw;
            fail("cannot be decoded: a corrupt or truncated PNG" + declared + " (" + problem.what() + ")");
        }
    } else if (startsWith(*bytes, kJpegSignature)) {
        try {
            decodeJpegRgba8(bytes->data(), bytes->size(), [&](const JpegLayout& layout) {
                admit(layout.width, layout.height, layout.decoderBytes);
                decoded.width = int(layout.width);
                decoded.height = int(layout.height);
                return buffer.allocate(layout.width, layout.height);
            });
        } catch (const std::runtime_error& problem) {
            if (dynamic_cast<const SceneError*>(&problem) != nullptr) throw;
            fail("cannot be decoded: a corrupt, truncated or unsupported JPEG" + declared + " (" + problem.what() +
                 ")");
        }
    } else if (looksLikeWebp(bytes->data(), bytes->size())) {
        // EXT_texture_webp's images: libwebp decodes into the buffer; what it holds of its own (a lossless image's
        // whole ARGB) is judged with the pixels before either is allocated.
        try {
            decodeWebpRgba8(bytes->data(), bytes->size(), [&](const WebpLayout& layout) {
                admit(layout.width, layout.height, layout.decoderBytes);
                decoded.width = int(layout.width);
                decoded.height = int(layout.height);
                return buffer.allocate(layout.width, layout.height).front();
            });
        } catch (const std::runtime_error& problem) {
            if (dynamic_cast<const SceneError*>(&problem) != nullptr) throw;
            fail("cannot be decoded: a corrupt, truncated or unsupported WebP" + declared + " (" + problem.what() +
                 ")");
        }
    } else {
        return decodeWithStb(*bytes, declared, admit, fail);
    }
    decoded.rgba = std::move(buffer.pixels);
    return decoded;
}

namespace {

/** The bytes a header says the image takes to decode, or 0 when there is no header to read. */
std::size_t headerBytes(const SceneImage& image) {
    int width = 0, height = 0, channels = 0;
    std::vector<unsigned char> head;
    const std::vector<unsigned char>* bytes = image.encoded.get();
    if (bytes == nullptr) {
        std::error_code error;
        if (image.path.empty() || !std::filesystem::is_regular_file(image.path, error)) return 0;
        // A JPEG's frame header may follow its metadata (an EXIF thumbnail, an ICC profile); 256 KiB reaches it in
        // the files cameras and painting programs write without reading a whole texture.
        std::ifstream file(image.path, std::ios::binary);
        head.resize(std::size_t(256) << 10);
        file.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
        head.resize(std::size_t(std::max<std::streamsize>(file.gcount(), 0)));
        bytes = &head;
    }
    if (bytes->empty() || bytes->size() > std::size_t(INT_MAX)) return 0;
    if (looksLikeWebp(bytes->data(), bytes->size())) {
        // libwebp reads the header and hands its layout to the pixel provider, which stops it there.
        struct HeaderRead {
            WebpLayout layout;
        };
        try {
            decodeWebpRgba8(bytes->data(), bytes->size(),
                            [](const WebpLayout& layout) -> unsigned char* { throw HeaderRead{layout}; });
        } catch (const HeaderRead& header) {
            return decodedImageBytes(int(std::min<std::uint32_t>(header.layout.width, INT_MAX)),
                                     int(std::min<std::uint32_t>(header.layout.height, INT_MAX))) +
                   header.layout.decoderBytes;
        } catch (const std::exception&) {
        }
        return 0;
    }
    if (stbi_info_from_memory(bytes->data(), int(bytes->size()), &width, &height, &channels) == 0 || width <= 0 ||
        height <= 0)
        return 0;
    const bool ownDecoder = startsWith(*bytes, kPngSignature) || startsWith(*bytes, kJpegSignature);
    return decodedImageBytes(width, height) + (ownDecoder ? 0 : stbDecoderBytes(*bytes, width, height));
}

} // namespace

std::size_t estimatedTextureBytes(const Scene& scene) {
    std::set<int> named;
    for (const Mesh& mesh : scene.meshes)
        for (const TextureRef* reference : textureRefsOf(mesh.material))
            if (reference->present() && std::size_t(reference->image) < scene.images.size())
                named.insert(reference->image);
    std::size_t bytes = 0;
    for (const int index : named) bytes += headerBytes(scene.images[std::size_t(index)]);
    return bytes;
}

} // namespace inkgraph
