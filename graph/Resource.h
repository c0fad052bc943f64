#pragma once
/** @file Resource descriptions the graph reasons about. No GL: gl/ maps Format to GLenum. */

#include <string>
#include <string_view>

namespace inkgraph {

enum class Format {
    RGBA32F, ///< four float32 channels
    R32F,    ///< one float32 channel
    RGBA8,   ///< four unorm8 channels (final colour)
    R8,      ///< one unorm8 channel (line masks)
    RGBA16F, ///< four float16 channels (read back as float32)
    R16F,    ///< one float16 channel (read back as float32)
    /** A depth attachment: GL's window depth as float32 (reversed-Z, gl/GlObjects.h), read back as one float32
     *  channel. Passes that draw the model again test against it instead of drawing its depth once more. */
    Depth32F,
};

/** Bytes per pixel, and a short name ("rgba32f") for plans and manifests. */
int bytesPerPixel(Format format);
std::string_view formatName(Format format);
/** True for the float formats (32- and 16-bit): their images are float32 on the CPU and dump as EXR. */
bool isFloatFormat(Format format);

/** Every graph texture is frame-sized, scaled by `scale` (supersampling renders data buffers larger) over `divisor` (a
 *  field sampled coarser than the picture: the suggestive contours' G-buffer, about 1024 rows at every size). `samples`
 *  above 1 makes it multisampled (--msaa): each pixel holds that many samples, which a reader takes one by one (GLSL's
 *  sampler2DMS) and a read-back resolves to one value per pixel. */
struct TextureDesc {
    Format format = Format::RGBA32F;
    int scale = 1;
    int samples = 1;
    int divisor = 1; ///< the frame's sides times `scale` must be whole multiples of it (scaledSide())
    bool operator==(const TextureDesc&) const = default;
};

/** A side of a resource at `scale` / `divisor` of a frame side of `frameSide` pixels. Throws std::invalid_argument
 *  when `scale` or `divisor` is under 1 or `divisor` does not divide frameSide x scale (a pass that samples coarser
 *  chooses a divisor of the frame: its pixels must cover the frame's exactly). */
int scaledSide(int frameSide, int scale, int divisor);

/** What a resource holds: a frame-sized texture (its pixels on the GPU, the CPU or both), or a typed CPU object (a
 *  line skeleton with sub-pixel points, the strokes, scene-derived data) that only its writer's and readers' backend
 *  knows the C++ type of. */
enum class ResourceKind { Texture, Object };

/** A CPU object resource as its writer declares it. The compiler checks that every reader names the same `type`;
 *  the memory budget charges `bytesPerPixel` per pixel of the frame at `scale` while it lives; `picture` is the format
 *  of the image --dump and the contact sheet show of it (a skeleton's mask), none for data without one. */
struct ObjectDesc {
    std::string type;              ///< "line-skeleton": the reader's readObject() must name the same
    std::size_t bytesPerPixel = 0; ///< its size at most, per pixel at `scale` (0: charged elsewhere, e.g. the scene)
    int scale = 1;                 ///< the resolution it was made at (a skeleton: the data resolution) ...
    int divisor = 1;               ///< ... over this (a skeleton found on a coarser field: TextureDesc::divisor)
    bool hasPicture = false;       ///< it has a picture, of `pictureFormat` at `scale` (GlPassContext::outputPicture())
    Format pictureFormat = Format::R8;
    bool operator==(const ObjectDesc&) const = default;
};

/** What a resource's pixels mean, for the pictures made of it outside the graph (--contact-sheet's tiles). Auto: judged
 *  from the format (8-bit RGBA a colour, 8-bit one channel ink lines, floats data). */
enum class Appearance { Auto, Color, Lines, Mask, UnitVector, SignedScalar, Depth, Data };

/** How a written resource is shown and named outside the graph, declared by its writer so that a new output needs no
 *  table elsewhere. */
struct Presentation {
    std::string fileName; ///< --dump's file name ("normal.exr"); empty: "<pass>-<field>.exr" (floats) or ".png"
    Appearance appearance = Appearance::Auto;
    /** What the pixels hold, in a phrase of plain text, for the --dump table of README.md (app/GeneratedDocs.h);
     *  empty: the table says the format alone. */
    std::string meaning{};
};

/** Whether a written field must be produced, or only when something consumes it. */
enum class Need { Required, Optional };

/** Which pixels of a texture a pass reads (PassBuilder::read()). */
enum class ReadExtent {
    WholeImage, ///< any pixel, the ones its writer leaves at the clear value included (the default)
    /** Only where its writer covered the frame (drew a surface there), as the reader tells from another texture of
     *  that writer it reads whole (the G-buffer's depth > 0): the other pixels never reach what the pass writes. When
     *  every reader of a texture says so and nothing requests it, the writer may leave those pixels uncleared
     *  (PlannedResource::backgroundRead; passes/gbuffer/GBufferPass.cpp does). */
    CoveredPixels
};

/** A rectangle of a texture's pixels in GL's window coordinates: x from the left column, y from the BOTTOM row, as
 *  glScissor() and glGetTextureSubImage() take it. */
struct PixelRect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;
    bool operator==(const PixelRect&) const = default;
};

/** "gbuffer.normal" -> {"gbuffer", "normal"}; a name without exactly one dot gives empty parts. */
struct ResourceName {
    std::string pass;
    std::string field;
    static ResourceName split(std::string_view resource);
    std::string joined() const { return pass + "." + field; }
};

} // namespace inkgraph
