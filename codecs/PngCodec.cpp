#include "codecs/PngCodec.h"

#include <png.h>

#include <bit>
#include <cstring>
#include <exception>
#include <functional>
#include <utility>
#include <stdexcept>
#include <string>

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

/** What one decode holds between libpng's callbacks. libpng reads progressively (png_process_data): the caller pushes
 *  the file's bytes, libpng calls back with the header and each row. Pushing rather than pulling is what bounds a
 *  decode: once the last row is delivered, libpng stops inflating and skips whatever image data follows ("extra
 *  compressed data"), where the pulling reader inflates it all to find the stream's end (a 500 KB file can hold
 *  512 MiB of it). */
struct ProgressiveDecode {
    PngExpansion expansion = PngExpansion::AsStored;
    const PngRowProvider* rowsFor = nullptr;
    PngLayout layout;
    std::vector<unsigned char*> rows;
    std::exception_ptr refusal; ///< thrown by rowsFor inside a callback, rethrown once libpng has returned
    bool ended = false;         ///< libpng reached IEND
    bool truncated = false;     ///< libpng warned that the image data ended before the last row
    std::uint32_t rowsDelivered = 0;
};

/** The header: the expansions, the layout, and the caller's rows. A callback of libpng's: nothing may throw out. */
void onHeader(png_structp png, png_infop info) {
    auto* decode = static_cast<ProgressiveDecode*>(png_get_progressive_ptr(png));
    // OpenImageIO's expansion, so the pixels do not depend on which reader read them: palettes to RGB, grey below 8
    // bits to 8, a tRNS chunk to an alpha channel.
    png_set_expand(png);
    if (decode->expansion == PngExpansion::Rgba8) {
        png_set_scale_16(png); // 16 to 8 bits, rounded: never a buffer of 16-bit samples
        png_set_gray_to_rgb(png);
        png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER); // only where the file has no alpha
    } else if constexpr (std::endian::native == std::endian::little) {
        png_set_swap(png); // PNG stores 16-bit big-endian
    }
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    PngLayout& layout = decode->layout;
    layout.width = png_get_image_width(png, info);
    layout.height = png_get_image_height(png, info);
    layout.bitDepth = png_get_bit_depth(png, info);
    layout.channels = png_get_channels(png, info);
    if ((layout.bitDepth != 8 && layout.bitDepth != 16) || layout.channels < 1 || layout.channels > 4 ||
        (decode->expansion == PngExpansion::Rgba8 && (layout.bitDepth != 8 || layout.channels != 4)))
        png_error(png, "the expanded pixels are not 1 to 4 channels of 8 or 16 bits");
    // The header is the file's claim: the provider judges it before anything of its size is allocated. Its refusal
    // is kept and rethrown once libpng has returned (never longjmp out of a catch block: the exception would be lost
    // half-handled).
    try {
        decode->rows = (*decode->rowsFor)(layout);
        if (decode->rows.size() != layout.height)
            throw std::logic_error("decodePngBytes(): the row provider gave the wrong row count");
    } catch (...) {
        decode->refusal = std::current_exception();
    }
    if (decode->refusal) png_error(png, "refused by the caller");
}

void onRow(png_structp png, png_bytep newRow, png_uint_32 rowNumber, int) {
    auto* decode = static_cast<ProgressiveDecode*>(png_get_progressive_ptr(png));
    if (rowNumber >= decode->rows.size()) png_error(png, "a row beyond the image");
    // Interlaced passes fill a row in several visits; a pass that leaves a row alone passes no data.
    png_progressive_combine_row(png, decode->rows[rowNumber], newRow);
    ++decode->rowsDelivered;
}

void onEnd(png_structp png, png_infop) { static_cast<ProgressiveDecode*>(png_get_progressive_ptr(png))->ended = true; }

/** Warnings change no pixel (a bad CRC in an ancillary chunk, which libpng then skips; data after the last row), except
 *  image data that ends before the last row, which would leave rows undecoded: that one fails the decode. */
void onDecodeWarning(png_structp png, png_const_charp message) {
    auto* decode = static_cast<ProgressiveDecode*>(png_get_progressive_ptr(png));
    if (decode != nullptr && message != nullptr && std::strstr(message, "runcated") != nullptr)
        decode->truncated = true;
}

bool startDecode(png_structp png, png_infop info, ProgressiveDecode* decode) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_progressive_read_fn(png, decode, onHeader, onRow, onEnd);
    png_set_error_fn(png, png_get_error_ptr(png), onPngError, onDecodeWarning);
    (void)info;
    return true;
}

bool pushBytes(png_structp png, png_infop info, png_bytep bytes, std::size_t byteCount) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_process_data(png, info, bytes, byteCount);
    return true;
}

/** Pushes what `nextPiece` returns (pointer and size; 0 bytes at the end) until libpng reaches IEND. */
void decode(PngExpansion expansion, const PngRowProvider& rowsFor,
            const std::function<std::pair<const unsigned char*, std::size_t>()>& nextPiece) {
    PngReader reader;
    ProgressiveDecode state;
    state.expansion = expansion;
    state.rowsFor = &rowsFor;
    if (!startDecode(reader.png, reader.info, &state)) throw pngError(reader.failure);
    while (!state.ended) {
        const auto [bytes, byteCount] = nextPiece();
        if (byteCount == 0) throw std::runtime_error("libpng: truncated PNG: the data ends early");
        // libpng's interface is not const-qualified; it only reads the bytes.
        if (!pushBytes(reader.png, reader.info, const_cast<png_bytep>(bytes), byteCount)) {
            if (state.refusal) std::rethrow_exception(state.refusal);
            throw pngError(reader.failure);
        }
    }
    // A zlib stream may end, complete, before the last row: libpng then goes on to IEND and leaves the rest of the
    // rows as they were. Every row of a plain file must have come, and an interlaced one must have finished its
    // seventh pass.
    const bool interlaced = png_get_interlace_type(reader.png, reader.info) != PNG_INTERLACE_NONE;
    const bool complete =
        interlaced ? png_get_current_pass_number(reader.png) >= 7 : state.rowsDelivered == state.layout.height;
    if (state.truncated || state.rows.empty() || !complete)
        throw std::runtime_error("libpng: truncated PNG: the image data ends before the last row");
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

// How hard to compress, measured on the comic stills of the batch (bench/PngEncodeSweep.cpp over the nine models'
// 1024x1024 cel + lines pictures, decoded once; CPU ms to encode one, median of 5, and the nine's bytes; issue 38;
// docs/performance.md has the table):
//   zlib level 3, Up filter, memory level 8 (before)     10.7 ms  737,657 B
//   level 3, no filter, memory level 8                    9.0 ms  700,836 B
//   level 3, no filter, memory level 5 (chosen)           7.6 ms  691,759 B
//   level 1 / 2, no filter, memory level 5                7.4 / 7.5 ms  750,218 / 723,331 B
//   level 3, Up, memory level 5                           9.4 ms  730,242 B
//   Z_RLE + Up 10.4 ms 832,196 B; Z_FILTERED = default at levels 1-3 (zlib's fast deflate ignores it); Sub and Paeth
//   11.2 and 16.0 ms; every filter (libpng picks per row) 28.7 ms 729,120 B; stored (level 0) 10.1 ms, 37.8 MB.
// The time is mostly zlib's bookkeeping, not the search: level 0 costs more than level 3 (it moves 4 MB per still),
// a smaller window costs far more (each slide rehashes the whole hash table), and the memory level sets the hash
// table and the block size: 5 (2,048 hash heads, blocks of 2,048 symbols) beats the default 8 in time and size on
// every picture tried. adler32 over the raw rows (16-19% of the encode) is the zlib format's and stays; a larger
// compression buffer (png_set_compression_buffer_size) changed nothing measurable.
// Flat cel shading compresses best unfiltered, gradients (phong, gouraud: 30-46% larger unfiltered) with Up, so
// the filter is chosen per picture from a sample of its rows (rowFilterFor()). On 1024x1024 pictures of other looks,
// before -> after (ms, bytes): bunny phong 24.1 / 198,369 -> 23.1 / 196,796 (Up), armadillo gouraud 21.6 / 205,171
// -> 20.5 / 204,070 (Up), the fox glTF 9.5 / 45,836 -> 6.5 / 45,261, godette MToon 18.7 / 193,398 -> 13.3 / 189,413
// (none). OpenImageIO's default (level 3, every filter) took 30.2 ms for the cel bunny.
constexpr int kCompressionLevel = 3;
constexpr int kMemoryLevel = 5;

/** Sampled rows for rowFilterFor(): every 16th, enough to tell the looks apart (0.3-3% of a comic still's pixels
 *  are gradient pixels against 12-15% on phong or gouraud shading, in the sample as in the whole picture). */
constexpr std::uint32_t kFilterSampleStride = 16;

/** The share of gradient pixels above which rows are Up-filtered: between the comic stills (0.3-3%) and MToon's
 *  soft shades (5.7%, still smaller unfiltered) below and phong and gouraud (12-15%) above. */
constexpr double kGradientShareForUp = 0.08;

/** How many pixels of one row differ from both their left and their upper neighbour (a flat area's pixels equal both,
 *  an edge's one of them), the first pixel left out. A fixed pixel size, so the comparisons unroll. */
template <std::size_t PixelBytes>
std::uint64_t gradientPixels(const unsigned char* here, const unsigned char* above, std::uint32_t width) {
    std::uint64_t gradients = 0;
    for (std::size_t offset = PixelBytes; offset < std::size_t(width) * PixelBytes; offset += PixelBytes) {
        bool differsFromLeft = false;
        bool differsFromAbove = false;
        for (std::size_t byte = offset; byte < offset + PixelBytes; ++byte) {
            differsFromLeft |= here[byte] != here[byte - PixelBytes];
            differsFromAbove |= here[byte] != above[byte];
        }
        gradients += differsFromLeft && differsFromAbove ? 1 : 0;
    }
    return gradients;
}

/** PNG_FILTER_UP for pictures of gradients, PNG_FILTER_NONE for flat ones, by the share of gradient pixels in the
 *  sampled rows, which costs about 0.1 ms on a 1024x1024 still. */
int rowFilterFor(const PngLayout& layout, const png_bytep* rows) {
    std::uint64_t sampled = 0;
    std::uint64_t gradients = 0;
    for (std::uint32_t row = kFilterSampleStride; row < layout.height; row += kFilterSampleStride) {
        switch (layout.channels) {
        case 1: gradients += gradientPixels<1>(rows[row], rows[row - 1], layout.width); break;
        case 2: gradients += gradientPixels<2>(rows[row], rows[row - 1], layout.width); break;
        case 3: gradients += gradientPixels<3>(rows[row], rows[row - 1], layout.width); break;
        default: gradients += gradientPixels<4>(rows[row], rows[row - 1], layout.width); break;
        }
        sampled += layout.width - 1;
    }
    return double(gradients) > kGradientShareForUp * double(sampled) ? PNG_FILTER_UP : PNG_FILTER_NONE;
}

bool writeRows(png_structp png, png_infop info, const PngLayout* layout, png_bytepp rows,
               std::vector<unsigned char>* bytes) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, bytes, appendBytes, flushNothing);
    png_set_IHDR(png, info, layout->width, layout->height, 8, pngColorType(layout->channels), PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // 8-bit pictures are display colour: the sRGB chunk with gAMA and cHRM for readers that predate it, as
    // OpenImageIO wrote them.
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    png_set_compression_level(png, kCompressionLevel);
    png_set_compression_mem_level(png, kMemoryLevel);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, rowFilterFor(*layout, rows));
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    return true;
}

} // namespace

void decodePngBytes(const unsigned char* bytes, std::size_t byteCount, PngExpansion expansion,
                    const PngRowProvider& rowsFor) {
    bool pushed = false;
    decode(expansion, rowsFor, [&]() -> std::pair<const unsigned char*, std::size_t> {
        if (pushed) return {nullptr, 0};
        pushed = true;
        return {bytes, byteCount};
    });
}

void decodePngStream(std::FILE* file, PngExpansion expansion, const PngRowProvider& rowsFor) {
    std::vector<unsigned char> piece(std::size_t(1) << 16);
    decode(expansion, rowsFor, [&]() -> std::pair<const unsigned char*, std::size_t> {
        const std::size_t read = std::fread(piece.data(), 1, piece.size(), file);
        if (read == 0 && std::ferror(file)) throw std::runtime_error("the file cannot be read");
        return {piece.data(), read};
    });
}

std::vector<unsigned char> encodePngRows(std::uint32_t width, std::uint32_t height, int channels,
                                         const unsigned char* const* rows) {
    if (width == 0 || height == 0 || channels < 1 || channels > 4)
        throw std::runtime_error("only non-empty 8-bit images of 1 to 4 channels are written as PNG");
    PngWriter writer;
    PngLayout layout;
    layout.width = width;
    layout.height = height;
    layout.bitDepth = 8;
    layout.channels = channels;
    // libpng only reads the rows it is given; its interface is not const-qualified.
    std::vector<png_bytep> rowPointers(height);
    for (std::uint32_t row = 0; row < height; ++row) rowPointers[row] = const_cast<png_bytep>(rows[row]);
    std::vector<unsigned char> bytes;
    if (!writeRows(writer.png, writer.info, &layout, rowPointers.data(), &bytes)) throw pngError(writer.failure);
    return bytes;
}

} // namespace inkgraph
