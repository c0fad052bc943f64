#pragma once
/** @file One move-only wrapper per GL object kind we use, each labelled at creation. */

#include "gl/GlHandle.h"
#include "graph/Resource.h"

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace inkgraph {

/** The driver could not allocate a texture: the frame is too large for this machine. */
class GlOutOfMemoryError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** "GL_OUT_OF_MEMORY" and the like, or the number in hex. */
std::string glErrorName(GLenum error);

/** GL storage for a graph Format. */
struct GlFormat {
    GLenum internalFormat;
    GLenum pixelFormat;
    GLenum pixelType;
    int channelCount;
};
GlFormat glFormatOf(Format format);

/** An immutable-storage 2-D texture, one level, nearest filtering, clamped to the edge; with `samples` above 1 a
 *  multisampled one (GL_TEXTURE_2D_MULTISAMPLE, fixed sample locations), which shaders read per sample and
 *  readTexture() resolves. */
class GlTexture {
public:
    GlTexture(Format format, int width, int height, std::string_view label, int samples = 1);

    GLuint id() const { return mHandle.id(); }
    Format format() const { return mFormat; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int samples() const { return mSamples; }
    const std::string& label() const { return mLabel; }
    /** Re-labels a pooled texture for the resource now using it. */
    void relabel(std::string_view label);

private:
    GlHandle<TextureDeleter> mHandle;
    Format mFormat = Format::RGBA8;
    int mWidth = 0;
    int mHeight = 0;
    int mSamples = 1;
    std::string mLabel;
};

/** A depth attachment private to a pass (never a graph resource); multisampled with `samples` above 1. */
class GlDepthTexture {
public:
    GlDepthTexture(int width, int height, std::string_view label, int samples = 1);
    GLuint id() const { return mHandle.id(); }

private:
    GlHandle<TextureDeleter> mHandle;
};

/** A pass's own depth attachment, kept between runs of the same size (batches, benchmarks: reallocating 4 MiB per
 *  run cost 8-10 ms) and remade when the size changes. */
class PassDepthBuffer {
public:
    explicit PassDepthBuffer(std::string label) : mLabel(std::move(label)) {}
    /** The depth texture of this size and sample count, made on first use or when either changed. */
    const GlDepthTexture& sized(int width, int height, int samples = 1);

private:
    std::string mLabel;
    std::unique_ptr<GlDepthTexture> mDepth;
    int mWidth = 0;
    int mHeight = 0;
    int mSamples = 1;
};

/** The most samples a multisampled colour or depth texture may have in the current context: the least of
 *  GL_MAX_SAMPLES, GL_MAX_COLOR_TEXTURE_SAMPLES and GL_MAX_DEPTH_TEXTURE_SAMPLES. */
int maxSamples();

/** Depth convention of every pass: reversed-Z (docs/stability.md, "far/near ratio"). The projection maps the near
 *  plane to window depth 1 and the far plane to 0 (FrameParams::clipFromView), glClipControl(GL_LOWER_LEFT,
 *  GL_ZERO_TO_ONE) keeps that [0, 1] range without OpenGL's [-1, 1] -> [0, 1] halving, and depth buffers are
 *  DEPTH_COMPONENT32F. Float spacing is then relative near 0, where the far depths are, so depth resolves about
 *  1e-7 of the distance at any far/near ratio, where the standard mapping loses 2^-24 x far/near.
 *  Nearer fragments have the GREATER depth. */
inline constexpr GLenum kDepthNearer = GL_GREATER;
inline constexpr GLenum kDepthNearerOrEqual = GL_GEQUAL;
inline constexpr float kFarDepth = 0.0f;
/** glPolygonOffset(kOnePixelFartherFactor, kOnePixelFartherUnits) pushes a face's fragments one pixel of the face's
 *  own depth slope plus one resolvable depth step away from the eye. Negative: farther is smaller here. For a float
 *  depth buffer one unit is 2^(e - 23) of the fragment's own exponent e, a relative step, so the push stays a fixed
 *  fraction of the depth at any far/near. */
inline constexpr GLfloat kOnePixelFartherFactor = -1.0f;
inline constexpr GLfloat kOnePixelFartherUnits = -1.0f;
/** While it lives, filled faces are drawn one pixel farther (glPolygonOffset(kOnePixelFartherFactor,
 *  kOnePixelFartherUnits)); the offset is off again when it goes, a draw that throws included, so the next pass starts
 *  without it. */
class OnePixelFartherFill {
public:
    OnePixelFartherFill() {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(kOnePixelFartherFactor, kOnePixelFartherUnits);
    }
    ~OnePixelFartherFill() {
        glPolygonOffset(0.0f, 0.0f);
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
    OnePixelFartherFill(const OnePixelFartherFill&) = delete;
    OnePixelFartherFill& operator=(const OnePixelFartherFill&) = delete;
};
/** Sets the clip control reversed-Z needs; part of every pass's starting state (GraphExecutor) and of a new context. */
void useReversedDepthClipControl();

/** Clears the bound framebuffer's first `colorSlots` colour attachments to zero and its depth to the far plane
 *  (kFarDepth). */
void clearColorAndDepth(int colorSlots);

/** A framebuffer with up to 8 colour attachments and an optional depth attachment. */
class GlFramebuffer {
public:
    explicit GlFramebuffer(std::string_view label);
    GLuint id() const { return mHandle.id(); }
    void attachColor(int slot, const GlTexture& texture);
    void attachDepth(const GlDepthTexture& depth);
    /** A graph texture of Format::Depth32F as the depth attachment; throws std::logic_error for another format. */
    void attachDepth(const GlTexture& depth);
    /** Sets draw buffers to the attached slots in order and throws if the framebuffer is incomplete. */
    void finish(const std::vector<int>& drawSlots);
    void bind() const;

private:
    GlHandle<FramebufferDeleter> mHandle;
    std::string mLabel;
};

class GlBuffer {
public:
    GlBuffer(const void* data, std::size_t byteCount, std::string_view label);
    /** Uninitialised storage with glNamedBufferStorage's `flags` (GL_MAP_READ_BIT: a buffer the CPU reads back). */
    GlBuffer(std::size_t byteCount, GLbitfield flags, std::string_view label);
    GLuint id() const { return mHandle.id(); }
    std::size_t byteCount() const { return mByteCount; }

private:
    GlHandle<BufferDeleter> mHandle;
    std::size_t mByteCount = 0;
};

class GlVertexArray {
public:
    explicit GlVertexArray(std::string_view label);
    GLuint id() const { return mHandle.id(); }
    /** Binds `buffer` as a tightly packed float vec3 attribute at `location`. */
    void setVec3Attribute(GLuint location, const GlBuffer& buffer);
    /** Binds `buffer` as a tightly packed float vec2 attribute at `location`. */
    void setVec2Attribute(GLuint location, const GlBuffer& buffer);
    /** Binds `buffer` as a tightly packed float vec4 attribute at `location`. */
    void setVec4Attribute(GLuint location, const GlBuffer& buffer);
    void setIndexBuffer(const GlBuffer& buffer);
    void bind() const;

private:
    GlHandle<VertexArrayDeleter> mHandle;
};

/** A linked program. Copies share the one GL program (deleted with the last copy), so a ShaderLibrary that keeps
 *  programs can hand the same one to the passes of every still a process renders. */
class GlProgram {
public:
    GlProgram(GLuint id, std::string label);
    GLuint id() const { return mHandle->id(); }
    void use() const;
    /** Uniform location by name; -1 (ignored by glUniform) when the compiler removed it. Asked of GL once per name:
     *  the materials' uniforms are set per draw (passes/material/SceneMaterials.h), many meshes times many passes. */
    GLint uniform(const char* name) const;

private:
    /** Hashes std::string and std::string_view alike, so a lookup by a C string allocates nothing. */
    struct NameHash {
        using is_transparent = void;
        std::size_t operator()(std::string_view name) const { return std::hash<std::string_view>{}(name); }
    };
    using Locations = std::unordered_map<std::string, GLint, NameHash, std::equal_to<>>;

    std::shared_ptr<const GlHandle<ProgramDeleter>> mHandle;
    std::shared_ptr<Locations> mLocations; ///< shared by copies, like the program itself
    std::string mLabel;
};

} // namespace inkgraph
