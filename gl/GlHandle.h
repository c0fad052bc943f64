#pragma once
/** @file Move-only ownership of one GL object name (Magnum's model): the constructor takes a fresh name, the
 *  destructor deletes it, copying is deleted and moving zeroes the source. The deleter is a functor because GL
 *  entry points are resolved at run time. */

#include <epoxy/gl.h>

#include <string_view>
#include <utility>

namespace inkgraph {

template <class Deleter>
class GlHandle {
public:
    GlHandle() = default;
    explicit GlHandle(GLuint id) : mId(id) {}
    ~GlHandle() { reset(); }

    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;
    GlHandle(GlHandle&& other) noexcept : mId(std::exchange(other.mId, 0)) {}
    GlHandle& operator=(GlHandle&& other) noexcept {
        if (this != &other) {
            reset();
            mId = std::exchange(other.mId, 0);
        }
        return *this;
    }

    GLuint id() const { return mId; }
    explicit operator bool() const { return mId != 0; }

    void reset() {
        if (mId != 0) Deleter{}(mId);
        mId = 0;
    }
    /** Gives up ownership, for interoperating with a foreign owner. */
    GLuint release() { return std::exchange(mId, 0); }

private:
    GLuint mId = 0;
};

struct TextureDeleter {
    void operator()(GLuint id) const { glDeleteTextures(1, &id); }
};
struct FramebufferDeleter {
    void operator()(GLuint id) const { glDeleteFramebuffers(1, &id); }
};
struct BufferDeleter {
    void operator()(GLuint id) const { glDeleteBuffers(1, &id); }
};
struct VertexArrayDeleter {
    void operator()(GLuint id) const { glDeleteVertexArrays(1, &id); }
};
struct ShaderDeleter {
    void operator()(GLuint id) const { glDeleteShader(id); }
};
struct ProgramDeleter {
    void operator()(GLuint id) const { glDeleteProgram(id); }
};
struct SamplerDeleter {
    void operator()(GLuint id) const { glDeleteSamplers(1, &id); }
};

/** Names an object for RenderDoc/apitrace captures and debug messages. */
void labelObject(GLenum identifier, GLuint id, std::string_view label);

} // namespace inkgraph
