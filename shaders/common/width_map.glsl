// Width from the model (docs/lines.md "Width from the model"): the one function that turns a width map into a vertex's
// width factor, for the outline's edges (outline/outline.vert), the silhouette's hull (silhouette/hull.vert) and
// MToon's outline shells (mtoon/outline.vert), so --outline-width-map and MToon's outlineWidthMultiplyTexture mean the
// same thing in each. Needs common/material.glsl before it (the vertex's colour and texture coordinates).
#ifdef INKGRAPH_VERTEX_STAGE
// One width map's factor at this vertex, in [0, 1]: channel `channel` (0 R .. 3 A) of the vertex colour COLOR_0
// (source 1) or of `map` at `uv` (source 2, level 0: a vertex has no footprint to filter over); 1 with source 0.
float widthMapFactor(int source, int channel, sampler2D map, vec2 uv) {
    vec4 value = vec4(1.0);
    if (source == 1) value = inVertexColor;
    if (source == 2) value = textureLod(map, uv, 0.0);
    return clamp(value[channel], 0.0, 1.0);
}

// --outline-width-map (passes/material/SceneMaterials.h bindWidthMap()): 0 off, or for a mesh without what the map
// reads; 1 vertex colour; 2 the map's texture.
uniform int outlineWidthMapSource;
uniform int outlineWidthMapChannel;
layout(binding = 14) uniform sampler2D outlineWidthMapTexture; // data: stored values / 255

// The user's width map at this vertex. Sampled at TEXCOORD_0 as the mesh has it: the map is not the material's, so
// neither its KHR_texture_transform nor MToon's UV animation moves it.
float outlineWidthMapFactor() {
    return widthMapFactor(outlineWidthMapSource, outlineWidthMapChannel, outlineWidthMapTexture, inTexcoord0);
}
#endif
