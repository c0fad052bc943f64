#include "app/PngFiles.h"

#include <png.h>

#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace inkgraph {
namespace {

// How libpng's errors reach us. libpng is C: on an error it calls the error handler, which must not return, and a C++
// exception thrown there would unwind libpng's C frames. So the handler keeps the reason in a fixed buffer (no
// allocation, nothing that can throw) and longjmps back to the libpng step that set the return point. Each step below
// is a function of its own holding no object with a destructor (longjmp would skip it) and changing no local after
// setjmp; the objects with destructors (the structures, the image, the row table) live in its caller.

struct PngFailure {
    char reason[256] = "unknown error";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp reason) {
    auto* failure = static_cast<PngFailure*>(png_get_error_ptr(png));
    std::snprintf(failure->reason, sizeof failure->reason, "%s", reason != nullptr ? reason : "unknown error");
    png_longjmp(png, 1);
}

/** Warnings (a bad CRC in an ancillary chunk, which libpng then skips) change no pixel we read or write. */
void onPngWarning(png_structp, png_const_charp) {}

std::runtime_error pngError(const PngFailure& failure) {
    return std::runtime_error(std::string("libpng: ") + failure.reason);
}

/** Where decoding reads from: bytes in memory, or a file read as libpng asks. */
struct PngSource {
    const unsigned char* bytes = nullptr;
    std::size_t byteCount = 0;
    std::size_t offset = 0;
    std::FILE* file = nullptr;
};

void readFromSource(png_structp png, png_bytep out, std::size_t wanted) {
    auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
    if (source->file != nullptr) {
        if (std::fread(out, 1, wanted, source->file) == wanted) return;
        png_error(png, std::ferror(source->file) ? "the file cannot be read" : "truncated PNG: the file ends early");
    }
    if (source->byteCount - source->offset < wanted) png_error(png, "truncated PNG: the data ends early");
    std::memcpy(out, source->bytes + source->offset, wanted);
    source->offset += wanted;
}

/** libpng's read structures, destroyed on every path. Not movable: libpng holds the address of `failure`. */
class PngReader {
public:
    PngReader() {
        png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &failure, onPngError, onPngWarning);
        if (png == nullptr) throw std::runtime_error("libpng: cannot create a reader");
        info = png_create_info_struct(png);
        if (info == nullptr) {
            png_destroy_read_struct(&png, nullptr, nullptr);
            throw std::runtime_error("libpng: cannot create a reader");
        }
    }
    ~PngReader() { png_destroy_read_struct(&png, &info, nullptr); }
    PngReader(const PngReader&) = delete;
    PngReader& operator=(const PngReader&) = delete;

    PngFailure failure;
    png_structp png = nullptr;
    png_infop info = nullptr;
};

/** What the header declares, after the expansions below. */
struct PngLayout {
    png_uint_32 width = 0;
    png_uint_32 height = 0;
    int bitDepth = 0;
    int channels = 0;
};

bool readLayout(png_structp png, png_infop info, PngSource* source, PngLayout* layout) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, source, readFromSource);
    png_read_info(png, info);
    // OpenImageIO's expansion, so the pixels do not depend on which reader read them: palettes to RGB, grey below 8
    // bits to 8, a tRNS chunk to an alpha channel.
    png_set_expand(png);
    if constexpr (std::endian::native == std::endian::little) png_set_swap(png); // PNG stores 16-bit big-endian
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    layout->width = png_get_image_width(png, info);
    layout->height = png_get_image_height(png, info);
    layout->bitDepth = png_get_bit_depth(png, info);
    layout->channels = png_get_channels(png, info);
    return true;
}

bool readRows(png_structp png, png_bytepp rows) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_read_image(png, rows);
    png_read_end(png, nullptr); // the chunks after the pixels, to IEND (a file cut after its last IDAT is an error)
    return true;
}

cv::Mat decode(PngSource& source, std::size_t maxPixels) {
    PngReader reader;
    PngLayout layout;
    if (!readLayout(reader.png, reader.info, &source, &layout)) throw pngError(reader.failure);
    // The header is the file's claim: a few bytes can declare gigapixels, so it is judged before any allocation.
    if (std::size_t(layout.width) * std::size_t(layout.height) > maxPixels)
        throw std::runtime_error("it declares " + std::to_string(layout.width) + "x" + std::to_string(layout.height) +
                                 " pixels, more than the " + std::to_string(maxPixels) + " allowed here");
    if ((layout.bitDepth != 8 && layout.bitDepth != 16) || layout.channels < 1 || layout.channels > 4)
        throw std::runtime_error("libpng gives " + std::to_string(layout.channels) + " channels of " +
                                 std::to_string(layout.bitDepth) + " bits; 1 to 4 of 8 or 16 bits are read");
    cv::Mat pixels(int(layout.height), int(layout.width),
                   CV_MAKETYPE(layout.bitDepth == 16 ? CV_16U : CV_8U, layout.channels));
    std::vector<png_bytep> rows(layout.height);
    for (int row = 0; row < pixels.rows; ++row) rows[row] = pixels.ptr(row);
    if (!readRows(reader.png, rows.data())) throw pngError(reader.failure);
    if (layout.bitDepth == 8) return pixels;
    // As OpenImageIO gave them: samples other than 8-bit as float, 65535 as 1.
    cv::Mat scaled(pixels.size(), CV_MAKETYPE(CV_32F, layout.channels));
    for (int row = 0; row < pixels.rows; ++row) {
        const auto* in = pixels.ptr<std::uint16_t>(row);
        float* out = scaled.ptr<float>(row);
        for (int i = 0; i < pixels.cols * layout.channels; ++i) out[i] = float(in[i]) / 65535.0f;
    }
    return scaled;
}

/** libpng's write structures, destroyed on every path. Not movable: libpng holds the address of `failure`. */
class PngWriter {
public:
    PngWriter() {
        png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, onPngError, onPngWarning);
        if (png == nullptr) throw std::runtime_error("libpng: cannot create a writer");
        info = png_create_info_struct(png);
        if (info == nullptr) {
            png_destroy_write_struct(&png, nullptr);
            throw std::runtime_error("libpng: cannot create a writer");
        }
    }
    ~PngWriter() { png_destroy_write_struct(&png, &info); }
    PngWriter(const PngWriter&) = delete;
    PngWriter& operator=(const PngWriter&) = delete;

    PngFailure failure;
    png_structp png = nullptr;
    png_infop info = nullptr;
};

/** Appends libpng's output to the vector. An exception must not leave this callback (libpng's frames are below it):
 *  a failed append becomes a libpng error, raised once the catch block is left. */
void appendBytes(png_structp png, png_bytep data, std::size_t length) {
    auto* bytes = static_cast<std::vector<unsigned char>*>(png_get_io_ptr(png));
    bool appended = false;
    try {
        bytes->insert(bytes->end(), data, data + length);
        appended = true;
    } catch (...) {
    }
    if (!appended) png_error(png, "out of memory for the encoded PNG");
}

void flushNothing(png_structp) {}

int pngColorType(int channels) {
    switch (channels) {
    case 1: return PNG_COLOR_TYPE_GRAY;
    case 2: return PNG_COLOR_TYPE_GRAY_ALPHA;
    case 3: return PNG_COLOR_TYPE_RGB;
    default: return PNG_COLOR_TYPE_RGB_ALPHA;
    }
}

// How hard to compress: zlib level 3 with the Up row filter alone. Measured on 1024x1024 pictures (CPU ms to encode,
// bytes): the cel-shaded bunny (the default look) 12.4 ms / 134,686 B, Phong-shaded 24.8 ms / 259,619 B, the fox
// glTF 9.3 ms / 45,898 B. libpng's default filtering (every filter tried on each row; level 3, as OpenImageIO was
// set) took 30.2 / 44.7 / 26.1 ms for 133,401 / 266,207 / 46,679 B: choosing the filters is most of its time. No
// filter is a little faster and 5% smaller on flat cel shading but 27% larger on gradients; level 1 saves a third
// of the time on gradients but is 10% larger there; level 4 takes 1.1-1.7x as long for sizes from 7% larger to 36%
// smaller (the fox); level 6 with every filter takes 3-3.6x as long.
constexpr int kCompressionLevel = 3;
constexpr int kRowFilters = PNG_FILTER_UP;

bool writeRows(png_structp png, png_infop info, const cv::Mat* image, png_bytepp rows,
               std::vector<unsigned char>* bytes) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, bytes, appendBytes, flushNothing);
    png_set_IHDR(png, info, png_uint_32(image->cols), png_uint_32(image->rows), 8, pngColorType(image->channels()),
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // 8-bit pictures are display colour: the sRGB chunk with gAMA and cHRM for readers that predate it, as
    // OpenImageIO wrote them.
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    png_set_compression_level(png, kCompressionLevel);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, kRowFilters);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    return true;
}

} // namespace

std::vector<unsigned char> encodePng(const cv::Mat& image) {
    if (image.empty() || image.depth() != CV_8U || image.channels() > 4)
        throw std::runtime_error(
            "only non-empty 8-bit images of 1 to 4 channels are written as PNG (float images go to .exr or .tif)");
    PngWriter writer;
    std::vector<png_bytep> rows(image.rows);
    // libpng only reads the rows it is given; its interface is not const-qualified.
    for (int row = 0; row < image.rows; ++row) rows[row] = const_cast<png_bytep>(image.ptr(row));
    std::vector<unsigned char> bytes;
    if (!writeRows(writer.png, writer.info, &image, rows.data(), &bytes)) throw pngError(writer.failure);
    return bytes;
}

cv::Mat decodePng(const unsigned char* bytes, std::size_t byteCount, std::size_t maxPixels) {
    PngSource source;
    source.bytes = bytes;
    source.byteCount = byteCount;
    return decode(source, maxPixels);
}

cv::Mat readPngFile(const std::filesystem::path& path, std::size_t maxPixels) {
    struct CloseFile {
        void operator()(std::FILE* file) const { std::fclose(file); }
    };
    const std::unique_ptr<std::FILE, CloseFile> file(std::fopen(path.c_str(), "rb"));
    if (!file) throw std::runtime_error(std::string("cannot open it: ") + std::strerror(errno));
    PngSource source;
    source.file = file.get();
    return decode(source, maxPixels);
}

} // namespace inkgraph
