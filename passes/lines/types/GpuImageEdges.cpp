#include "passes/lines/types/GpuImageEdges.h"

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <stdexcept>

namespace inkgraph {
namespace {

/** One event of shaders/post/neighbour_pairs.comp, as std430 lays out its uvec4. */
struct PairEvent {
    std::uint32_t pair;   ///< 2 (row x width + col) of the pair's first pixel, + 1 for the pair below
    std::uint32_t marksQ; ///< 1: the second pixel (right or below) is marked; 0: the first
    std::uint32_t along;  ///< the bits of the float `along`
    std::uint32_t unused;
};
static_assert(sizeof(PairEvent) == 16);

/** The counter's 16 bytes (a uint and its padding to the array's uvec4 alignment) before the events. */
constexpr std::size_t kHeaderBytes = 16;
constexpr int kGroupSide = 16; ///< the shader's local_size_x and local_size_y

/** Room for a closed line around a quarter of the frame, as the CPU kernels reserve; a longer one grows the buffer. */
std::size_t expectedEventCount(int width, int height) { return 4 * std::size_t(width + height); }

void requireFiniteNonNegative(float value, const char* name) {
    if (!std::isfinite(value) || value < 0.0f)
        throw std::invalid_argument(std::string("GpuNeighbourPairsKernel(): '") + name +
                                    "' must be finite and non-negative");
}

} // namespace

GpuNeighbourPairsKernel::GpuNeighbourPairsKernel(Kind kind, std::string gbuffer, float depthJump,
                                                 ShaderLibrary& shaders)
    : mKind(kind), mGBuffer(std::move(gbuffer)), mDepthJump(depthJump), mShaders(shaders) {
    requireFiniteNonNegative(depthJump, "settings.depthJump");
}

GpuNeighbourPairsKernel::GpuNeighbourPairsKernel(std::string gbuffer, ContourSettings settings, ShaderLibrary& shaders)
    : GpuNeighbourPairsKernel(Kind::Contour, std::move(gbuffer), settings.depthJump, shaders) {}

GpuNeighbourPairsKernel::GpuNeighbourPairsKernel(std::string gbuffer, DepthEdgeSettings settings,
                                                 ShaderLibrary& shaders)
    : GpuNeighbourPairsKernel(Kind::DepthEdge, std::move(gbuffer), settings.relativeJump, shaders) {}

GpuNeighbourPairsKernel::GpuNeighbourPairsKernel(std::string gbuffer, NormalEdgeSettings settings,
                                                 ShaderLibrary& shaders)
    : GpuNeighbourPairsKernel(Kind::NormalEdge, std::move(gbuffer), settings.depthJump, shaders) {
    if (!(settings.creaseAngleDegrees >= 0.0f && settings.creaseAngleDegrees <= 180.0f))
        throw std::invalid_argument("GpuNeighbourPairsKernel(): 'settings.creaseAngleDegrees' must lie in [0, 180]");
    mNormalEdge = settings;
}

std::vector<std::string> GpuNeighbourPairsKernel::inputs() const {
    switch (mKind) {
    case Kind::Contour: return {mGBuffer + ".nDotV", mGBuffer + ".depth"};
    case Kind::DepthEdge: return {mGBuffer + ".depth"};
    case Kind::NormalEdge: return {mGBuffer + ".normal", mGBuffer + ".depth"};
    }
    return {};
}

void GpuNeighbourPairsKernel::prepare() {
    if (mProgram) return;
    ProgramDesc desc;
    desc.computeFile = "post/neighbour_pairs.comp";
    switch (mKind) {
    case Kind::Contour:
        desc.label = "contour-gpu";
        desc.defines = {"CONTOUR 1"};
        break;
    case Kind::DepthEdge:
        desc.label = "depth-edge-gpu";
        desc.defines = {"DEPTH_EDGE 1"};
        break;
    case Kind::NormalEdge:
        desc.label = "normal-edge-gpu";
        desc.defines = {"NORMAL_EDGE 1"};
        break;
    }
    mProgram.emplace(mShaders.build(desc));
}

LineSkeleton GpuNeighbourPairsKernel::find(const std::vector<cv::Mat>& inputs) {
    switch (mKind) {
    case Kind::Contour: return extractContours(inputs.at(0), inputs.at(1), ContourSettings{mDepthJump});
    case Kind::DepthEdge: return extractDepthEdges(inputs.at(0), DepthEdgeSettings{mDepthJump});
    case Kind::NormalEdge: return extractNormalEdges(inputs.at(0), inputs.at(1), mNormalEdge);
    }
    return {};
}

void GpuNeighbourPairsKernel::allocateEvents(std::size_t capacity) {
    mEvents.reset();
    mEvents.emplace(nullptr, kHeaderBytes + capacity * sizeof(PairEvent), "post-stage pair events");
    mCapacity = capacity;
}

std::size_t GpuNeighbourPairsKernel::dispatch(const std::vector<const GlTexture*>& inputs, int width, int height) {
    const GLuint program = mProgram->id();
    const GLuint zero = 0;
    glClearNamedBufferSubData(mEvents->id(), GL_R32UI, 0, sizeof(GLuint), GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glUseProgram(program);
    glProgramUniform2i(program, mProgram->uniform("size"), width, height);
    glProgramUniform1f(program, mProgram->uniform("depthJump"), mDepthJump);
    glProgramUniform1ui(program, mProgram->uniform("capacity"), GLuint(mCapacity));
    if (mKind == Kind::NormalEdge) {
        // As extractNormalEdges() derives them, in double then rounded, so both kernels compare the same floats.
        const double crease = double(mNormalEdge.creaseAngleDegrees) * std::numbers::pi / 180.0;
        const float cosCrease = float(std::cos(crease));
        const float sinCrease = mNormalEdge.creaseAngleDegrees >= 180.0f ? 0.0f : float(std::sin(crease));
        glProgramUniform1f(program, mProgram->uniform("cosCreaseSigned"), cosCrease * std::abs(cosCrease));
        glProgramUniform1f(program, mProgram->uniform("sinCreaseSquared"), sinCrease * sinCrease);
        glProgramUniform1i(program, mProgram->uniform("zeroCrease"), mNormalEdge.creaseAngleDegrees == 0.0f);
    }
    // Units 0 and 1: the surface field (n.v or the normal) and the depth; a depth-edge reads the depth alone.
    glBindTextureUnit(1, inputs.back()->id());
    if (inputs.size() == 2) glBindTextureUnit(0, inputs.front()->id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mEvents->id());
    glDispatchCompute(GLuint((width + kGroupSide - 1) / kGroupSide), GLuint((height + kGroupSide - 1) / kGroupSide), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindTextureUnit(0, 0);
    glBindTextureUnit(1, 0);
    glUseProgram(0);
    GLuint count = 0;
    glGetNamedBufferSubData(mEvents->id(), 0, sizeof(GLuint), &count);
    return count;
}

LineSkeleton GpuNeighbourPairsKernel::findInTextures(const std::vector<const GlTexture*>& inputs) {
    const std::size_t expected = mKind == Kind::DepthEdge ? 1 : 2;
    if (inputs.size() != expected || std::find(inputs.begin(), inputs.end(), nullptr) != inputs.end())
        throw std::invalid_argument("GpuNeighbourPairsKernel::findInTextures(): expected " + std::to_string(expected) +
                                    " textures (" + std::to_string(inputs.size()) + " given)");
    const int width = inputs.front()->width();
    const int height = inputs.front()->height();
    for (const GlTexture* input : inputs) {
        if (input->width() != width || input->height() != height)
            throw std::invalid_argument("GpuNeighbourPairsKernel::findInTextures(): '" + input->label() +
                                        "' is not the size of '" + inputs.front()->label() + "'");
        if (input->samples() > 1)
            throw std::invalid_argument("GpuNeighbourPairsKernel::findInTextures(): '" + input->label() +
                                        "' is multisampled");
    }
    prepare();
    if (!mEvents) allocateEvents(expectedEventCount(width, height));
    std::size_t count = dispatch(inputs, width, height);
    if (count > mCapacity) { // a frame full of lines: room for all of them, and once more
        allocateEvents(count + count / 4);
        count = dispatch(inputs, width, height);
    }
    mLastEvents = count;
    std::vector<PairEvent> events(count);
    if (count > 0)
        glGetNamedBufferSubData(mEvents->id(), GLintptr(kHeaderBytes), GLsizeiptr(count * sizeof(PairEvent)),
                                events.data());

    // The CPU kernels visit the pairs row by row, column by column, the right pair before the one below: the
    // pair's number orders them the same way, so the points come in the same order.
    std::sort(events.begin(), events.end(), [](const PairEvent& a, const PairEvent& b) { return a.pair < b.pair; });
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(height, width, CV_8UC1);
    skeleton.points.reserve(count);
    for (const PairEvent& event : events) {
        const std::uint32_t pixel = event.pair >> 1;
        const bool below = (event.pair & 1) != 0;
        const int row = int(pixel / std::uint32_t(width));
        const int col = int(pixel % std::uint32_t(width));
        const int otherRow = below ? row + 1 : row;
        const int otherCol = below ? col : col + 1;
        float along = 0.0f;
        std::memcpy(&along, &event.along, sizeof(float));
        if (event.marksQ)
            skeleton.mask.ptr<uchar>(otherRow)[otherCol] = 255;
        else
            skeleton.mask.ptr<uchar>(row)[col] = 255;
        skeleton.points.push_back(
            {{float(col) + along * float(otherCol - col), float(row) + along * float(otherRow - row)}, 1.0f});
    }
    return skeleton;
}

void GpuNeighbourPairsKernel::describe(nlohmann::ordered_json& entry) const {
    entry["device"] = "gpu";
    entry["events"] = mLastEvents;
}

} // namespace inkgraph
