#include "codecs/JpegCodec.h"

#include <cstdio>
// jpeglib.h needs FILE and size_t declared first.
#include <jerror.h>
#include <jpeglib.h>

#include <csetjmp>
#include <cstring>
#include <stdexcept>
#include <string>

namespace inkgraph {
namespace {

// How libjpeg's errors reach us: as with libpng (codecs/PngCodec.cpp), the C library's error handler must not return
// and a C++ exception must not unwind its frames, so the handler keeps the message in a fixed buffer and longjmps
// back to the step that set the return point. Those steps hold no object with a destructor.

struct JpegFailure {
    jpeg_error_mgr manager{}; ///< first, so libjpeg's pointer to it is a pointer to the whole
    std::jmp_buf returnPoint{};
    char reason[JMSG_LENGTH_MAX] = "unknown error";
    bool truncated = false; ///< libjpeg met the end of the data early and would fill the rest with grey
};

[[noreturn]] void onJpegError(j_common_ptr info) {
    auto* failure = reinterpret_cast<JpegFailure*>(info->err);
    info->err->format_message(info, failure->reason);
    std::longjmp(failure->returnPoint, 1);
}

/** Warnings: a file that ends early decodes to grey below the cut, a silently wrong texture; it is refused once the
 *  decode returns. Other warnings (extraneous bytes before a marker) change no pixel. */
void onJpegMessage(j_common_ptr info, int level) {
    auto* failure = reinterpret_cast<JpegFailure*>(info->err);
    if (level < 0 && info->err->msg_code == JWRN_JPEG_EOF) {
        failure->truncated = true;
        info->err->format_message(info, failure->reason);
    }
}

/** libjpeg's decompressor, destroyed on every path. Not movable: libjpeg holds the address of `failure`. */
class JpegReader {
public:
    JpegReader() {
        info.err = jpeg_std_error(&failure.manager);
        failure.manager.error_exit = onJpegError;
        failure.manager.emit_message = onJpegMessage;
        if (setjmp(failure.returnPoint)) throw std::runtime_error(std::string("libjpeg: ") + failure.reason);
        jpeg_create_decompress(&info);
        created = true;
    }
    ~JpegReader() {
        if (created) jpeg_destroy_decompress(&info);
    }
    JpegReader(const JpegReader&) = delete;
    JpegReader& operator=(const JpegReader&) = delete;

    JpegFailure failure;
    jpeg_decompress_struct info{};
    bool created = false;
};

bool readHeader(jpeg_decompress_struct* info, JpegFailure* failure, const unsigned char* bytes, std::size_t byteCount,
                JpegLayout* layout) {
    if (setjmp(failure->returnPoint)) return false;
    jpeg_mem_src(info, bytes, static_cast<unsigned long>(byteCount));
    jpeg_read_header(info, TRUE);
    layout->width = info->image_width;
    layout->height = info->image_height;
    layout->components = info->num_components;
    layout->multipleScans = jpeg_has_multiple_scans(info) != 0;
    // Row buffers, upsampling and tables: a few rows of each component at full width, and 1 MiB for the rest.
    std::size_t bytesOfRows = 0;
    std::size_t coefficientBytes = 0;
    for (int c = 0; c < info->num_components; ++c) {
        const jpeg_component_info& component = info->comp_info[c];
        const std::size_t blocksWide = (std::size_t(component.width_in_blocks) + std::size_t(component.h_samp_factor)) /
                                       std::size_t(component.h_samp_factor) * std::size_t(component.h_samp_factor);
        const std::size_t blocksHigh =
            (std::size_t(component.height_in_blocks) + std::size_t(component.v_samp_factor)) /
            std::size_t(component.v_samp_factor) * std::size_t(component.v_samp_factor);
        coefficientBytes += blocksWide * blocksHigh * sizeof(JBLOCK);
        bytesOfRows += (blocksWide * DCTSIZE + 64) * std::size_t(info->max_v_samp_factor) * DCTSIZE * 4;
    }
    layout->decoderBytes = (layout->multipleScans ? coefficientBytes : 0) + bytesOfRows + (std::size_t(1) << 20);
    return true;
}

bool startDecode(jpeg_decompress_struct* info, JpegFailure* failure, long memoryForLibjpeg) {
    if (setjmp(failure->returnPoint)) return false;
    // CMYK and YCCK have no RGB conversion in libjpeg: they come as CMYK and are converted here (cmykToRgba).
    const bool cmyk = info->jpeg_color_space == JCS_CMYK || info->jpeg_color_space == JCS_YCCK;
    info->out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    // libjpeg's whole-image buffers may not exceed what the caller admitted; past it libjpeg fails instead of
    // allocating (it has no backing store).
    info->mem->max_memory_to_use = memoryForLibjpeg;
    jpeg_start_decompress(info);
    return true;
}

bool readScanlines(jpeg_decompress_struct* info, JpegFailure* failure, unsigned char* const* rows) {
    if (setjmp(failure->returnPoint)) return false;
    while (info->output_scanline < info->output_height) {
        JSAMPROW row = rows[info->output_scanline];
        if (jpeg_read_scanlines(info, &row, 1) != 1) return false;
    }
    jpeg_finish_decompress(info);
    return true;
}

/** Adobe's inverted CMYK (as libjpeg gives it) to RGBA in place: both take four bytes a pixel. */
void cmykToRgba(unsigned char* row, std::uint32_t width) {
    for (std::uint32_t x = 0; x < width; ++x) {
        unsigned char* pixel = row + std::size_t(x) * 4;
        const unsigned key = pixel[3];
        for (int c = 0; c < 3; ++c) pixel[c] = static_cast<unsigned char>((pixel[c] * key + 127) / 255);
        pixel[3] = 255;
    }
}

} // namespace

void decodeJpegRgba8(const unsigned char* bytes, std::size_t byteCount, const JpegRowProvider& rowsFor) {
    JpegReader reader;
    const auto failed = [&] { return std::runtime_error(std::string("libjpeg: ") + reader.failure.reason); };
    JpegLayout layout;
    if (!readHeader(&reader.info, &reader.failure, bytes, byteCount, &layout)) throw failed();
    const std::vector<unsigned char*> rows = rowsFor(layout);
    if (rows.size() != layout.height)
        throw std::logic_error("decodeJpegRgba8(): the row provider gave the wrong count");
    if (!startDecode(&reader.info, &reader.failure, long(layout.decoderBytes))) throw failed();
    if (reader.info.output_width != layout.width || reader.info.output_height != layout.height ||
        reader.info.output_components != 4)
        throw std::runtime_error("libjpeg decodes " + std::to_string(reader.info.output_width) + "x" +
                                 std::to_string(reader.info.output_height) + " pixels of " +
                                 std::to_string(reader.info.output_components) + " components, not the header's " +
                                 std::to_string(layout.width) + "x" + std::to_string(layout.height) + " RGBA");
    if (!readScanlines(&reader.info, &reader.failure, rows.data())) throw failed();
    if (reader.failure.truncated) throw std::runtime_error(std::string("libjpeg: ") + reader.failure.reason);
    if (reader.info.out_color_space == JCS_CMYK)
        for (unsigned char* row : rows) cmykToRgba(row, layout.width);
}

} // namespace inkgraph
