#include "gl/GlObjects.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace inkgraph {
namespace {

/** Throws for a failed allocation: GlOutOfMemoryError when the driver ran out of memory. */
void checkAllocation(const char* function, const std::string& what, GLenum error) {
    if (error == GL_NO_ERROR) return;
    const std::string message = std::string(function) + ": cannot allocate " + what + " (" + glErrorName(error) + ")";
    if (error == GL_OUT_OF_MEMORY) throw GlOutOfMemoryError(message);
    throw std::runtime_error(message);
}

} // namespace

void labelObject(GLenum identifier, GLuint id, std::string_view label) {
    // GL_KHR_debug is core in 4.3; labels longer than GL_MAX_LABEL_LENGTH (>= 256) would be an error.
    const auto length = static_cast<GLsizei>(std::min<std::size_t>(label.size(), 255));
    glObjectLabel(identifier, id, length, label.data());
}

std::string glErrorName(GLenum error) {
    switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: {
        char buffer[16];
        std::snprintf(buffer, sizeof buffer, "0x%04X", error);
        return buffer;
    }
    }
}

GlFormat glFormatOf(Format format) {
    switch (format) {
    case Format::RGBA32F: return {GL_RGBA32F, GL_RGBA, GL_FLOAT, 4};
    case Format::R32F: return {GL_R32F, GL_RED, GL_FLOAT, 1};
    case Format::RGBA8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4};
    case Format::R8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1};
    // Half floats are read back and uploaded as float32: GL converts, so the CPU never handles float16.
    case Format::RGBA16F: return {GL_RGBA16F, GL_RGBA, GL_FLOAT, 4};
    case Format::R16F: return {GL_R16F, GL_RED, GL_FLOAT, 1};
    case Format::Depth32F: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 1};
    }
    throw std::logic_error("glFormatOf(): unknown format");
}

GlTexture::GlTexture(Format format, int width, int height, std::string_view label, int samples)
    : mFormat(format), mWidth(width), mHeight(height), mSamples(samples), mLabel(label) {
    const std::string what = std::to_string(width) + "x" + std::to_string(height) + " " +
                             std::string(formatName(format)) + " texture '" + std::string(label) + "'";
    GLuint id = 0;
    if (samples > 1) {
        glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &id);
        mHandle = GlHandle<TextureDeleter>(id);
        // Fixed sample locations: every texture of the same count samples the same points, so a layer drawn by one
        // pass lines up sample for sample with the target another lays it into.
        glTextureStorage2DMultisample(id, samples, glFormatOf(format).internalFormat, width, height, GL_TRUE);
        checkAllocation("GlTexture()", what + " of " + std::to_string(samples) + " samples", glGetError());
        labelObject(GL_TEXTURE, id, label);
        return; // read by texelFetch per sample: a multisampled texture has no filtering or wrapping
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    mHandle = GlHandle<TextureDeleter>(id);
    glTextureStorage2D(id, 1, glFormatOf(format).internalFormat, width, height);
    checkAllocation("GlTexture()", what, glGetError());
    // Data textures are sampled texel-exactly: never blend a normal or a depth with its neighbour.
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    labelObject(GL_TEXTURE, id, label);
}

void GlTexture::relabel(std::string_view label) {
    mLabel = label;
    labelObject(GL_TEXTURE, id(), label);
}

GlDepthTexture::GlDepthTexture(int width, int height, std::string_view label, int samples) {
    GLuint id = 0;
    glCreateTextures(samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D, 1, &id);
    mHandle = GlHandle<TextureDeleter>(id);
    if (samples > 1)
        glTextureStorage2DMultisample(id, samples, GL_DEPTH_COMPONENT32F, width, height, GL_TRUE);
    else
        glTextureStorage2D(id, 1, GL_DEPTH_COMPONENT32F, width, height);
    checkAllocation("GlDepthTexture()",
                    std::to_string(width) + "x" + std::to_string(height) + " depth texture '" + std::string(label) +
                        "'" + (samples > 1 ? " of " + std::to_string(samples) + " samples" : std::string()),
                    glGetError());
    labelObject(GL_TEXTURE, id, label);
}

GlFramebuffer::GlFramebuffer(std::string_view label) : mLabel(label) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    mHandle = GlHandle<FramebufferDeleter>(id);
    labelObject(GL_FRAMEBUFFER, id, label);
}

void GlFramebuffer::attachColor(int slot, const GlTexture& texture) {
    glNamedFramebufferTexture(id(), GL_COLOR_ATTACHMENT0 + slot, texture.id(), 0);
}

void GlFramebuffer::attachDepth(const GlDepthTexture& depth) {
    glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

void GlFramebuffer::attachDepth(const GlTexture& depth) {
    if (depth.format() != Format::Depth32F)
        throw std::logic_error("GlFramebuffer::attachDepth(): texture '" + depth.label() + "' of framebuffer '" +
                               mLabel + "' is " + std::string(formatName(depth.format())) + ", not depth32f");
    glNamedFramebufferTexture(id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
}

void GlFramebuffer::finish(const std::vector<int>& drawSlots) {
    std::vector<GLenum> buffers;
    for (int slot : drawSlots) buffers.push_back(GL_COLOR_ATTACHMENT0 + slot);
    glNamedFramebufferDrawBuffers(id(), static_cast<GLsizei>(buffers.size()), buffers.data());
    const GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("GlFramebuffer::finish(): framebuffer '" + mLabel + "' is incomplete (status " +
                                 glErrorName(status) + ")");
}

void GlFramebuffer::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }

GlBuffer::GlBuffer(const void* data, std::size_t byteCount, std::string_view label) : mByteCount(byteCount) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    mHandle = GlHandle<BufferDeleter>(id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(byteCount), data, 0);
    labelObject(GL_BUFFER, id, label);
}

GlBuffer::GlBuffer(std::size_t byteCount, GLbitfield flags, std::string_view label) : mByteCount(byteCount) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    mHandle = GlHandle<BufferDeleter>(id);
    glNamedBufferStorage(id, static_cast<GLsizeiptr>(byteCount), nullptr, flags);
    labelObject(GL_BUFFER, id, label);
}

GlVertexArray::GlVertexArray(std::string_view label) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    mHandle = GlHandle<VertexArrayDeleter>(id);
    labelObject(GL_VERTEX_ARRAY, id, label);
}

void GlVertexArray::setVec3Attribute(GLuint location, const GlBuffer& buffer) {
    glVertexArrayVertexBuffer(id(), location, buffer.id(), 0, 3 * sizeof(float));
    glVertexArrayAttribFormat(id(), location, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), location, location);
    glEnableVertexArrayAttrib(id(), location);
}

void GlVertexArray::setVec2Attribute(GLuint location, const GlBuffer& buffer) {
    glVertexArrayVertexBuffer(id(), location, buffer.id(), 0, 2 * sizeof(float));
    glVertexArrayAttribFormat(id(), location, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), location, location);
    glEnableVertexArrayAttrib(id(), location);
}

void GlVertexArray::setVec4Attribute(GLuint location, const GlBuffer& buffer) {
    glVertexArrayVertexBuffer(id(), location, buffer.id(), 0, 4 * sizeof(float));
    glVertexArrayAttribFormat(id(), location, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), location, location);
    glEnableVertexArrayAttrib(id(), location);
}

void GlVertexArray::setIndexBuffer(const GlBuffer& buffer) { glVertexArrayElementBuffer(id(), buffer.id()); }

void GlVertexArray::bind() const { glBindVertexArray(id()); }

GlProgram::GlProgram(GLuint id, std::string label)
    : mHandle(std::make_shared<const GlHandle<ProgramDeleter>>(id)), mLocations(std::make_shared<Locations>()),
      mLabel(std::move(label)) {
    labelObject(GL_PROGRAM, id, mLabel);
}

void GlProgram::use() const { glUseProgram(id()); }

GLint GlProgram::uniform(const char* name) const {
    const std::string_view key(name);
    if (auto found = mLocations->find(key); found != mLocations->end()) return found->second;
    return mLocations->emplace(std::string(key), glGetUniformLocation(id(), name)).first->second;
}

const GlDepthTexture& PassDepthBuffer::sized(int width, int height, int samples) {
    if (!mDepth || mWidth != width || mHeight != height || mSamples != samples) {
        mDepth.reset(); // the old one goes first, so two never exist at once
        mDepth = std::make_unique<GlDepthTexture>(width, height, mLabel, samples);
        mWidth = width;
        mHeight = height;
        mSamples = samples;
    }
    return *mDepth;
}

int maxSamples() {
    GLint most = 0;
    GLint color = 0;
    GLint depth = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &most);
    glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &color);
    glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &depth);
    return std::min({most, color, depth});
}

void clearColorAndDepth(int colorSlots) {
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int slot = 0; slot < colorSlots; ++slot) glClearBufferfv(GL_COLOR, slot, zero);
    glClearBufferfv(GL_DEPTH, 0, &kFarDepth);
}

void useReversedDepthClipControl() { glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); }

} // namespace inkgraph
