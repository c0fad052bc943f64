// The surface's material (passes/material/SceneMaterials.h binds it per mesh): base colour = factor x texture x vertex
// colour, in linear RGB with alpha; alpha cut-outs; emissive. Every pass that draws the surface includes this, so they
// agree on where the surface is. Needs common/color.glsl before it in the fragment stage.
// The attributes travel in one interface block, matched by its name, so a geometry stage between (the back-face
// outline) can pass them on (outline/outline.geom).
// KHR_texture_transform: uv' = transform * (u, v, 1).
vec2 materialTransformed(vec2 uv, mat3 transform) {
    return (transform * vec3(uv, 1.0)).xy;
}

// MToon's UV animation (VRMC_materials_mtoon-1.0 "UV Animation", docs/mtoon.md): the material's speeds (u and v scroll
// in uv units per second, rotation in radians per second about (0.5, 0.5)) times the render's time, each texel's share
// of it the mask texture's blue channel. It moves every texture of the material but the matcap, before the texture's
// own KHR_texture_transform, in every pass that draws the surface, so cut-outs move with the colour. Speeds of zero
// (every material without MToon) leave the coordinates as they are.
uniform float frameTime;                // seconds (--time): SceneMaterials::setTime()
uniform vec3 materialUvAnimationSpeed;  // (scroll u, scroll v, rotation)
uniform int materialUvAnimationMaskTextured;
uniform int materialUvAnimationMaskSet;
uniform mat3 materialUvAnimationMaskTransform;
layout(binding = 11) uniform sampler2D materialUvAnimationMaskTexture; // linear data: its blue channel

// `uv` animated with the mask value `mask`: the specification's transform order, scroll(t) x rotation(t) about the
// centre, with its rotation matrix [cos sin; -sin cos] (counter-clockwise in u-right, v-down space).
vec2 materialAnimated(vec2 uv, float mask) {
    vec3 phase = materialUvAnimationSpeed * (frameTime * mask);
    float c = cos(phase.z);
    float s = sin(phase.z);
    vec2 centred = uv - 0.5;
    return vec2(c * centred.x + s * centred.y, c * centred.y - s * centred.x) + 0.5 + phase.xy;
}

bool materialAnimates() {
    return materialUvAnimationSpeed != vec3(0.0);
}

#ifdef INKGRAPH_VERTEX_STAGE
layout(location = 2) in vec2 inTexcoord0;
layout(location = 3) in vec2 inTexcoord1;
layout(location = 4) in vec4 inVertexColor; // linear; (1, 1, 1, 1) for a mesh without colours
out MaterialVarying {
    vec2 texcoord0;
    vec2 texcoord1;
    vec4 vertexColor;
} materialOut;

void passMaterialAttributes() {
    materialOut.texcoord0 = inTexcoord0;
    materialOut.texcoord1 = inTexcoord1;
    materialOut.vertexColor = inVertexColor;
}

// The vertex's texture coordinates of set `set` (TEXCOORD_0 or _1), animated, through `transform`.
vec2 materialVertexTexcoord(int set, mat3 transform) {
    vec2 uv = set == 1 ? inTexcoord1 : inTexcoord0;
    if (materialAnimates()) {
        float mask = 1.0;
        if (materialUvAnimationMaskTextured != 0)
            mask = textureLod(materialUvAnimationMaskTexture,
                              materialTransformed(materialUvAnimationMaskSet == 1 ? inTexcoord1 : inTexcoord0,
                                                  materialUvAnimationMaskTransform),
                              0.0)
                       .b;
        uv = materialAnimated(uv, mask);
    }
    return materialTransformed(uv, transform);
}
#endif

#ifdef INKGRAPH_FRAGMENT_STAGE
in MaterialVarying {
    vec2 texcoord0;
    vec2 texcoord1;
    vec4 vertexColor;
} materialIn;

uniform vec4 materialBaseColorFactor; // linear RGBA
uniform int materialBaseColorTextured;
uniform int materialBaseColorSet;      // TEXCOORD_0 or _1
uniform mat3 materialBaseColorTransform; // KHR_texture_transform
uniform int materialAlphaMode;           // 0 opaque, 1 mask, 2 blend
uniform float materialAlphaCutoff;
uniform float materialBlendSolidAlpha;   // SceneMaterials.h kBlendSolidAlpha
uniform int materialUsesVertexColor;     // 0 for MToon materials, which ignore vertex colours
// sRGB8_ALPHA8 storage: texture() returns linear colour.
layout(binding = 1) uniform sampler2D materialBaseColorTexture;

// The fragment's texture coordinates of set `set` (TEXCOORD_0 or _1), animated, through `transform`.
vec2 materialTexcoord(int set, mat3 transform) {
    vec2 uv = set == 1 ? materialIn.texcoord1 : materialIn.texcoord0;
    if (materialAnimates()) {
        float mask = 1.0;
        if (materialUvAnimationMaskTextured != 0)
            mask = texture(materialUvAnimationMaskTexture,
                           materialTransformed(materialUvAnimationMaskSet == 1 ? materialIn.texcoord1
                                                                               : materialIn.texcoord0,
                                               materialUvAnimationMaskTransform))
                       .b;
        uv = materialAnimated(uv, mask);
    }
    return materialTransformed(uv, transform);
}

// Linear RGBA: factor x texture, without the vertex colour.
vec4 materialTexturedColor() {
    vec4 color = materialBaseColorFactor;
    if (materialBaseColorTextured != 0)
        color *= texture(materialBaseColorTexture, materialTexcoord(materialBaseColorSet, materialBaseColorTransform));
    return color;
}

// Linear RGBA: factor x texture x vertex colour (glTF 2.0's base colour); MToon materials take no vertex colour
// (docs/mtoon.md), here as in every pass.
vec4 materialBaseColor() {
    vec4 color = materialTexturedColor();
    return materialUsesVertexColor != 0 ? color * materialIn.vertexColor : color;
}

// Whether a fragment of this alpha is not part of the surface: below the cutoff of a MASK material; with
// MATERIAL_SOLID_ONLY (the G-buffer and the line masks), also a BLEND fragment less opaque than
// materialBlendSolidAlpha, so lines behind glass stay visible.
bool materialCutsOut(float alpha) {
    if (materialAlphaMode == 1) return alpha < materialAlphaCutoff;
#ifdef MATERIAL_SOLID_ONLY
    if (materialAlphaMode == 2) return alpha < materialBlendSolidAlpha;
#else
    if (materialAlphaMode == 2) return alpha <= 0.0;
#endif
    return false;
}

#ifdef MATERIAL_EMISSIVE
uniform vec3 materialEmissiveFactor; // linear
uniform int materialEmissiveTextured;
uniform int materialEmissiveSet;
uniform mat3 materialEmissiveTransform;
layout(binding = 2) uniform sampler2D materialEmissiveTexture;
uniform int materialUnlit; // KHR_materials_unlit: the base colour as is

vec3 materialEmissive() {
    vec3 emissive = materialEmissiveFactor;
    if (materialEmissiveTextured != 0)
        emissive *=
            texture(materialEmissiveTexture, materialTexcoord(materialEmissiveSet, materialEmissiveTransform)).rgb;
    return emissive;
}
#endif
#endif
