#include "gl/Readback.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace inkgraph {

int cvTypeOf(Format format) {
    switch (format) {
    case Format::RGBA32F: return CV_32FC4;
    case Format::R32F: return CV_32FC1;
    case Format::RGBA8: return CV_8UC4;
    case Format::R8: return CV_8UC1;
    case Format::RGBA16F: return CV_32FC4;
    case Format::R16F: return CV_32FC1;
    case Format::Depth32F: return CV_32FC1;
    }
    throw std::logic_error("cvTypeOf(): unknown format");
}

namespace {

// Transfers go in bands of rows: one glGetTextureImage call takes a GLsizei byte count, which overflows at 2 GiB.
constexpr std::size_t kBandBytes = std::size_t(64) << 20;

int rowsPerBand(const cv::Mat& image) {
    const std::size_t rowBytes = std::size_t(image.cols) * image.elemSize();
    return int(std::max<std::size_t>(1, kBandBytes / rowBytes));
}

void throwOnGlError(const char* function, const GlTexture& texture) {
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        throw std::runtime_error(std::string(function) + ": GL error " + glErrorName(error) + " on texture '" +
                                 texture.label() + "'");
}

/** GL_PACK_INVERT_MESA set for the life of the object: the driver writes rows top row first, and the state is back
 *  to GL's default however the read ends. */
class PackInverted {
public:
    PackInverted() { glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE); }
    ~PackInverted() { glPixelStorei(GL_PACK_INVERT_MESA, GL_FALSE); }
    PackInverted(const PackInverted&) = delete;
    PackInverted& operator=(const PackInverted&) = delete;
};

/** GL_PACK_ROW_LENGTH set for the life of the object, so a region's rows land `rowLength` pixels apart in the image;
 *  GL's default (0: the rows are as long as the region) again however the read ends. */
class PackRowLength {
public:
    explicit PackRowLength(int rowLength) { glPixelStorei(GL_PACK_ROW_LENGTH, rowLength); }
    ~PackRowLength() { glPixelStorei(GL_PACK_ROW_LENGTH, 0); }
    PackRowLength(const PackRowLength&) = delete;
    PackRowLength& operator=(const PackRowLength&) = delete;
};

/** Maps the pages of a fresh image in one call (Linux 5.14+) before the driver writes them: on the VM, faulting them
 *  in one by one as the copy first touches them costs about twice as much (a 1024^2 RGBA32F read in a fresh process:
 *  17-26 ms, against 7-16 ms). Where the call is missing or refused, the pages fault in during the copy, as before. */
void mapPagesAhead(cv::Mat& image) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
    const auto page = std::uintptr_t(sysconf(_SC_PAGESIZE));
    const std::uintptr_t begin = (std::uintptr_t(image.data) + page - 1) / page * page;
    const std::uintptr_t end = std::uintptr_t(image.dataend) / page * page;
    if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
#else
    (void)image;
#endif
}

/** A multisampled texture resolved into a single-sample one of the same format and size by GL's blit: colour is the
 *  average of a pixel's samples, depth (which GL does not average) one of them. */
GlTexture resolved(const GlTexture& texture) {
    GlTexture single(texture.format(), texture.width(), texture.height(), texture.label() + " resolved");
    const bool depth = texture.format() == Format::Depth32F;
    const GLenum attachment = depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0;
    GlFramebuffer source(texture.label() + " multisampled");
    GlFramebuffer target(texture.label() + " resolved");
    glNamedFramebufferTexture(source.id(), attachment, texture.id(), 0);
    glNamedFramebufferTexture(target.id(), attachment, single.id(), 0);
    if (!depth) {
        glNamedFramebufferReadBuffer(source.id(), GL_COLOR_ATTACHMENT0);
        glNamedFramebufferDrawBuffer(target.id(), GL_COLOR_ATTACHMENT0);
    }
    glBlitNamedFramebuffer(source.id(), target.id(), 0, 0, texture.width(), texture.height(), 0, 0, texture.width(),
                           texture.height(), depth ? GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT, GL_NEAREST);
    throwOnGlError("readTexture()", texture);
    return single;
}

/** `region`, or the whole texture without one. Throws std::invalid_argument starting with `function` unless it lies
 *  within the texture. */
PixelRect regionWithin(const GlTexture& texture, const std::optional<PixelRect>& region, const std::string& function) {
    const PixelRect read = region.value_or(PixelRect{0, 0, texture.width(), texture.height()});
    if (read.x < 0 || read.y < 0 || read.width < 0 || read.height < 0 || read.x + read.width > texture.width() ||
        read.y + read.height > texture.height())
        throw std::invalid_argument(function + ": the region (" + std::to_string(read.x) + ", " +
                                    std::to_string(read.y) + ", " + std::to_string(read.width) + " x " +
                                    std::to_string(read.height) + ") is not within texture '" + texture.label() + "'");
    return read;
}

} // namespace

cv::Mat readTexture(const GlTexture& texture, ReadbackFlip flip, std::optional<PixelRect> region) {
    // GL reads no multisampled texture back; --dump and the caller's buffers take one value per pixel.
    if (texture.samples() > 1) return readTexture(resolved(texture), flip, region);
    const PixelRect read = regionWithin(texture, region, "readTexture()");
    const GlFormat glFormat = glFormatOf(texture.format());
    cv::Mat image(texture.height(), texture.width(), cvTypeOf(texture.format()));
    if (read.width == 0 || read.height == 0) return image;
    // GL rows y .. y + h - 1 are image rows height - y - h .. height - 1 - y, reversed.
    const int topRow = texture.height() - read.y - read.height;
    cv::Mat readRows = image.rowRange(topRow, topRow + read.height);
    mapPagesAhead(readRows);
    const int band = rowsPerBand(image);
    // Each band lands in its final rows of the image: no staging copy, so the only memory touched is the result's
    // (first touches of fresh memory cost more than the copy on a VM). GL_MESA_pack_invert (every Mesa driver) has
    // the driver write them top row first; without it the band's rows are swapped in place.
    const bool driverFlips = flip == ReadbackFlip::Fastest && epoxy_has_gl_extension("GL_MESA_pack_invert");
    std::optional<PackInverted> inverted;
    if (driverFlips) inverted.emplace();
    const PackRowLength rowLength(texture.width());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int glRow = read.y; glRow < read.y + read.height; glRow += band) {
        const int rows = std::min(band, read.y + read.height - glRow);
        cv::Mat target = image(cv::Range(texture.height() - glRow - rows, texture.height() - glRow),
                               cv::Range(read.x, read.x + read.width));
        // The last row ends where the region does; GL counts the bytes it writes from the band's first pixel.
        const std::size_t bytes = std::size_t(rows - 1) * image.step[0] + std::size_t(read.width) * image.elemSize();
        glGetTextureSubImage(texture.id(), 0, read.x, glRow, 0, read.width, rows, 1, glFormat.pixelFormat,
                             glFormat.pixelType, GLsizei(bytes), target.data);
        throwOnGlError("readTexture()", texture);
        if (!driverFlips) cv::flip(target, target, 0);
    }
    return image;
}

std::size_t readbackBytesOf(const GlTexture& texture) {
    return std::size_t(texture.width()) * std::size_t(texture.height()) *
           std::size_t(CV_ELEM_SIZE(cvTypeOf(texture.format())));
}

PendingReadback::PendingReadback(const GlTexture& texture)
    : PendingReadback(texture, GlBuffer(readbackBytesOf(texture), GL_MAP_READ_BIT, texture.label() + " read-back"),
                      std::nullopt) {}

PendingReadback::PendingReadback(const GlTexture& texture, GlBuffer buffer, std::optional<PixelRect> region)
    : mBuffer(std::move(buffer)), mFormat(texture.format()), mWidth(texture.width()), mHeight(texture.height()),
      mRegion(regionWithin(texture, region, "PendingReadback()")), mLabel(texture.label()) {
    if (texture.samples() > 1)
        throw std::invalid_argument("PendingReadback(): texture '" + texture.label() + "' is multisampled");
    if (mBuffer.byteCount() < readbackBytesOf(texture))
        throw std::invalid_argument("PendingReadback(): the buffer of " + std::to_string(mBuffer.byteCount()) +
                                    " bytes is too small for texture '" + texture.label() + "'");
    const GlFormat glFormat = glFormatOf(texture.format());
    if (mRegion.width > 0 && mRegion.height > 0) {
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, mBuffer.id());
        // GL's rows, bottom first: finish() turns them over while it copies them out, which costs nothing extra.
        glGetTextureSubImage(texture.id(), 0, mRegion.x, mRegion.y, 0, mRegion.width, mRegion.height, 1,
                             glFormat.pixelFormat, glFormat.pixelType, GLsizei(mBuffer.byteCount()), nullptr);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    }
    if (const GLenum error = glGetError(); error == GL_OUT_OF_MEMORY)
        throw GlOutOfMemoryError("PendingReadback(): no memory for the read-back of '" + texture.label() + "'");
    else if (error != GL_NO_ERROR)
        throw std::runtime_error("PendingReadback(): GL error " + glErrorName(error) + " on texture '" +
                                 texture.label() + "'");
    mFence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
}

PendingReadback::~PendingReadback() {
    if (mFence != nullptr) glDeleteSync(mFence);
}

cv::Mat PendingReadback::finish() {
    if (mFence == nullptr) throw std::logic_error("PendingReadback::finish(): '" + mLabel + "' was finished already");
    GLenum waited = GL_TIMEOUT_EXPIRED;
    while (waited == GL_TIMEOUT_EXPIRED)
        waited = glClientWaitSync(mFence, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(1000000000));
    glDeleteSync(mFence);
    mFence = nullptr;
    if (waited == GL_WAIT_FAILED)
        throw std::runtime_error("PendingReadback::finish(): waiting for the read-back of '" + mLabel + "' failed");
    cv::Mat image(mHeight, mWidth, cvTypeOf(mFormat));
    mFinished = true;
    if (mRegion.width == 0 || mRegion.height == 0) return image;
    const std::size_t regionRowBytes = std::size_t(mRegion.width) * image.elemSize();
    const std::size_t regionBytes = regionRowBytes * std::size_t(mRegion.height);
    const auto* bytes = static_cast<const unsigned char*>(
        glMapNamedBufferRange(mBuffer.id(), 0, GLsizeiptr(regionBytes), GL_MAP_READ_BIT));
    if (bytes == nullptr)
        throw std::runtime_error("PendingReadback::finish(): the driver did not map the read-back of '" + mLabel +
                                 "' (" + glErrorName(glGetError()) + ")");
    // GL row y lands in image row height - 1 - y, at the region's columns.
    const int topRow = mHeight - mRegion.y - mRegion.height;
    cv::Mat regionRows = image.rowRange(topRow, topRow + mRegion.height);
    mapPagesAhead(regionRows);
    const std::size_t columnOffset = std::size_t(mRegion.x) * image.elemSize();
    for (int row = 0; row < mRegion.height; ++row)
        std::memcpy(image.ptr(mHeight - 1 - (mRegion.y + row)) + columnOffset,
                    bytes + std::size_t(row) * regionRowBytes, regionRowBytes);
    glUnmapNamedBuffer(mBuffer.id());
    return image;
}

GlBuffer PendingReadback::takeBuffer() {
    if (!mFinished)
        throw std::logic_error("PendingReadback::takeBuffer(): the read-back of '" + mLabel + "' is not finished");
    return std::move(mBuffer);
}

void uploadImage(GlTexture& texture, const cv::Mat& image) {
    if (texture.samples() > 1)
        throw std::invalid_argument("uploadImage(): texture '" + texture.label() + "' is multisampled (" +
                                    std::to_string(texture.samples()) + " samples); only a pass can draw it");
    if (image.cols != texture.width() || image.rows != texture.height() || image.type() != cvTypeOf(texture.format()))
        throw std::invalid_argument("uploadImage(): image of " + std::to_string(image.cols) + "x" +
                                    std::to_string(image.rows) + " does not match texture '" + texture.label() + "'");
    const GlFormat glFormat = glFormatOf(texture.format());
    // The staging band is no taller than the image: a shade map of a few rows staged in 64 MiB took a fresh mapping
    // and a cleared huge page for every still.
    const int band = std::min(rowsPerBand(image), image.rows);
    cv::Mat bottomUpBand(band, image.cols, image.type());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int glRow = 0; glRow < texture.height(); glRow += band) {
        const int rows = std::min(band, texture.height() - glRow);
        for (int i = 0; i < rows; ++i) image.row(texture.height() - 1 - glRow - i).copyTo(bottomUpBand.row(i));
        glTextureSubImage2D(texture.id(), 0, 0, glRow, texture.width(), rows, glFormat.pixelFormat, glFormat.pixelType,
                            bottomUpBand.data);
        throwOnGlError("uploadImage()", texture);
    }
}

} // namespace inkgraph
