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

void TexturePool::returnFreeMemory() {
    dropFree();
    const GlTexture stand(Format::RGBA8, 1, 1, "released targets' stand-in");
    GlFramebuffer framebuffer("released targets' stand-in");
    framebuffer.attachColor(0, stand);
    framebuffer.finish({0});
    framebuffer.bind();
    glClear(GL_COLOR_BUFFER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();
}

GlBuffer TexturePool::acquireReadbackBuffer(std::size_t byteCount) {
    for (auto it = mFreeReadbackBuffers.begin(); it != mFreeReadbackBuffers.end(); ++it) {
        if (it->byteCount() == byteCount) {
            GlBuffer buffer = std::move(*it);
            mFreeReadbackBuffers.erase(it);
            return buffer;
        }
    }
    ++mReadbackBuffersCreated;
    return GlBuffer(byteCount, GL_MAP_READ_BIT, "read-back");
}

void TexturePool::releaseReadbackBuffer(GlBuffer buffer) { mFreeReadbackBuffers.push_back(std::move(buffer)); }

} // namespace inkgraph
