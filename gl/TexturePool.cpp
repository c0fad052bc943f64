#include "gl/TexturePool.h"

namespace inkgraph {

GlTexture TexturePool::acquire(Format format, int width, int height, std::string_view label, int samples) {
    for (auto it = mFree.begin(); it != mFree.end(); ++it) {
        if (it->format() == format && it->width() == width && it->height() == height && it->samples() == samples) {
            GlTexture texture = std::move(*it);
            mFree.erase(it);
            texture.relabel(label);
            ++mReusedCount;
            return texture;
        }
    }
    ++mCreatedCount;
    return GlTexture(format, width, height, label, samples);
}

void TexturePool::release(GlTexture texture) { mFree.push_back(std::move(texture)); }

} // namespace inkgraph
