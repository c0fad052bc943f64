#pragma once
/** @file Reuses textures between resources whose lifetimes do not overlap (keyed on format, size and samples), the only
 *  aliasing an offline renderer needs, and the pixel-pack buffers of early read-backs (keyed on size). */

#include "gl/GlObjects.h"

#include <cstddef>
#include <vector>

namespace inkgraph {

class TexturePool {
public:
    /** A texture of this format, size and sample count, re-labelled for its new user; reuses a released one when it
     *  can. */
    GlTexture acquire(Format format, int width, int height, std::string_view label, int samples = 1);
    void release(GlTexture texture);
    /** A buffer the CPU maps for reading (GL_MAP_READ_BIT) of `byteCount` bytes; reuses a released one of that size,
     *  so a batch does not make and free one per field and still (with region-only copies: 1.04-1.10x on an H200's
     *  comic batch, docs/performance.md). */
    GlBuffer acquireReadbackBuffer(std::size_t byteCount);
    void releaseReadbackBuffer(GlBuffer buffer);
    /** Deletes the released textures and buffers (those in use stay with their users). */
    void dropFree() {
        mFree.clear();
        mFreeReadbackBuffers.clear();
    }
    /** dropFree(), and the driver made to let go of them: Mesa keeps the last framebuffer's attachments referenced in
     *  its state until something is drawn again, so deleting them frees nothing until then (an idle drawing thread of
     *  a batch kept about 150 MiB that way at 2048x2048). A 1x1 target is cleared in their place, then the driver
     *  finishes. On the thread that holds the context. */
    void returnFreeMemory();

    std::size_t createdCount() const { return mCreatedCount; }
    std::size_t reusedCount() const { return mReusedCount; }
    std::size_t readbackBuffersCreated() const { return mReadbackBuffersCreated; }

private:
    std::vector<GlTexture> mFree;
    std::vector<GlBuffer> mFreeReadbackBuffers;
    std::size_t mCreatedCount = 0;
    std::size_t mReusedCount = 0;
    std::size_t mReadbackBuffersCreated = 0;
};

} // namespace inkgraph
