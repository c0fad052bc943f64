#pragma once
/** @file GL textures <-> cv::Mat. The ONLY place where GL's bottom-left origin is flipped to the top-left origin
 *  of images and OpenCV (row 0 at the top). Kernels and files never see GL conventions. */

#include "gl/GlObjects.h"
#include "graph/Resource.h"

#include <opencv2/core.hpp>

#include <optional>

namespace inkgraph {

/** OpenCV type for a graph format: CV_32FC4, CV_32FC1, CV_8UC4, CV_8UC1. */
int cvTypeOf(Format format);

/** Who turns GL's bottom-up rows over in readTexture(). */
enum class ReadbackFlip {
    Fastest, ///< the driver where it can (GL_MESA_pack_invert), else the CPU
    Cpu,     ///< always the CPU, as on drivers without the extension (for tests)
};

/** Reads the texture; row 0 of the result is the TOP row of the image. A multisampled texture is resolved first: a
 *  colour pixel is the average of its samples, a depth pixel one of them (GL's blit). With `region` (GL window
 *  coordinates, within the texture) the result is still the texture's size, but only the region's pixels are read:
 *  the others hold whatever the memory held, for a texture none of whose readers looks outside it. */
cv::Mat readTexture(const GlTexture& texture, ReadbackFlip flip = ReadbackFlip::Fastest,
                    std::optional<PixelRect> region = std::nullopt);

/** The bytes of a whole texture as a read-back holds them: the size of a PendingReadback's buffer. */
std::size_t readbackBytesOf(const GlTexture& texture);

/** A texture's read-back begun without waiting: the driver copies it into a pixel-pack buffer behind a fence, after
 *  the work queued before it, while the caller queues more (on a GPU the copy overlaps later passes). finish() waits
 *  for the fence and returns the image as readTexture() would, `region` included (only its pixels are copied: the
 *  others hold whatever the memory held). Single-sample textures only. The buffer, of readbackBytesOf(texture)
 *  bytes and mapped for reading, is the caller's (TexturePool::acquireReadbackBuffer()), for takeBuffer() to hand back
 *  once finished. */
class PendingReadback {
public:
    explicit PendingReadback(const GlTexture& texture);
    PendingReadback(const GlTexture& texture, GlBuffer buffer, std::optional<PixelRect> region);
    ~PendingReadback();
    PendingReadback(const PendingReadback&) = delete;
    PendingReadback& operator=(const PendingReadback&) = delete;
    /** Waits for the copy and returns it, row 0 at the top. Once. Throws std::runtime_error naming the texture when
     *  the wait or the mapping fails. */
    cv::Mat finish();
    /** The buffer, for reuse, once finish() has returned (std::logic_error before). */
    GlBuffer takeBuffer();

private:
    GlBuffer mBuffer;
    GLsync mFence = nullptr;
    Format mFormat;
    int mWidth;
    int mHeight;
    PixelRect mRegion; ///< GL window coordinates; its rows lie tightly packed in the buffer, bottom row first
    std::string mLabel;
    bool mFinished = false;
};

/** Uploads `image` (row 0 = top) into a texture of the same size and matching type. Throws on a mismatch and for a
 *  multisampled texture. */
void uploadImage(GlTexture& texture, const cv::Mat& image);

} // namespace inkgraph
