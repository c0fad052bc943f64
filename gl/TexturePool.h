#pragma once
/** @file Reuses textures between resources whose lifetimes do not overlap (keyed on format, size and samples), the only
 *  aliasing an offline renderer needs. */

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
    /** Deletes the released textures (those in use stay with their users). */
    void dropFree() { mFree.clear(); }

    std::size_t createdCount() const { return mCreatedCount; }
    std::size_t reusedCount() const { return mReusedCount; }

private:
    std::vector<GlTexture> mFree;
    std::size_t mCreatedCount = 0;
    std::size_t mReusedCount = 0;
};

} // namespace inkgraph
