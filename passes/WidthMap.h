#pragma once
/** @file Where the outlines' widths come from per vertex (--outline-width-map, docs/lines.md "Width from the model"):
 *  a channel of the mesh's vertex colour COLOR_0, or a channel of an image sampled at the vertex's TEXCOORD_0. The
 *  outline, silhouette and MToon-outline bands are scaled by it (shaders/common/width_map.glsl), so an artist can
 *  thin lines at the fingertips or hide them on the face. Plain data and its parser; no GL. */

#include <string>

namespace inkgraph {

struct WidthMap {
    enum class Source {
        None,        ///< widths as the flags say
        VertexColor, ///< `color:C`: COLOR_0's channel (linear, clamped to [0, 1])
        Texture,     ///< `texture:NAME:C`: an image's channel at TEXCOORD_0 (stored values / 255, not sRGB-decoded)
    };
    Source source = Source::None;
    int channel = 0; ///< 0 R, 1 G, 2 B, 3 A
    /** Source::Texture: an image file's path (PNG or JPEG, relative to the working directory), or, when no file is
     *  there, the name of an image of the model (glTF images[].name). */
    std::string texture;

    bool enabled() const { return source != Source::None; }
    /** The flag's value that gives this map: "none", "color:R", "texture:ramp.png:G". */
    std::string text() const;
    bool operator==(const WidthMap&) const = default;
};

/** Parses --outline-width-map's value: `none`, `color:C` or `texture:NAME:C` with C one of R, G, B, A (upper or lower
 *  case); NAME may hold colons (the channel is after the last one). Throws std::invalid_argument "--outline-width-map:
 *  ..." quoting the value for anything else. Nothing is read from disk here. */
WidthMap parseWidthMap(const std::string& text);

} // namespace inkgraph
