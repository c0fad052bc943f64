// MToon's surface colour (VRMC_materials_mtoon-1.0, docs/mtoon.md) from the mesh's material parameters, which
// passes/material/SceneMaterials binds: the shade pass shades the surface with it (shade/shade.frag, MODEL_MTOON) and
// the mtoon-outline pass lights its shells with it (mtoon/outline.frag). Needs common/material.glsl before it.
#ifdef INKGRAPH_FRAGMENT_STAGE
// A material without MToon gets mtoonPresent 0 and the fallback below.
uniform int mtoonPresent;
uniform vec3 mtoonShadeColorFactor;
uniform int mtoonShadeMultiplyTextured;
uniform int mtoonShadeMultiplySet;
uniform mat3 mtoonShadeMultiplyTransform;
layout(binding = 3) uniform sampler2D mtoonShadeMultiplyTexture;
uniform float mtoonShadingShiftFactor;
uniform float mtoonShadingToonyFactor;
uniform vec3 mtoonRimColorFactor;
uniform float mtoonRimFresnelPowerFactor;
uniform float mtoonRimLiftFactor;
uniform float mtoonRimLightingMixFactor;

// The shade tone of a material without MToon parameters, times its lit colour (docs/mtoon.md).
const float kMToonFallbackShade = 0.5;

// MToon's linearstep: 0 below a, 1 above b, linear between (the specification's definition).
float linearstep(float a, float b, float t) {
    return clamp((t - a) / max(b - a, 1e-6), 0.0, 1.0);
}

vec3 mtoonColor(vec3 lit, vec3 n, vec3 l, vec3 v) {
    vec3 shade;
    float shift, toony;
    if (mtoonPresent != 0) {
        shade = mtoonShadeColorFactor;
        if (mtoonShadeMultiplyTextured != 0)
            shade *= texture(mtoonShadeMultiplyTexture,
                             materialTexcoord(mtoonShadeMultiplySet, mtoonShadeMultiplyTransform)).rgb;
        shift = mtoonShadingShiftFactor;
        toony = mtoonShadingToonyFactor;
    } else {
        // No MToon in the file: the lit colour's own shadow tone, a hard band at n.l = 0 (docs/mtoon.md).
        shade = lit * kMToonFallbackShade;
        shift = 0.0;
        toony = 0.9;
    }
    float shading = linearstep(-1.0 + toony, 1.0 - toony, dot(n, l) + shift);
    // The direct light is white of intensity 1: its colour multiplies nothing.
    vec3 color = mix(shade, lit, shading);
    // Global illumination: the ambient light is uniform, so rawGi(n) is the same in every direction and the
    // specification's equalization between it and (rawGi(up) + rawGi(down)) / 2 changes nothing: gi = ambientLight.
    vec3 gi = ambientLight;
    color += gi * lit;
    if (mtoonPresent != 0) {
        float rim = pow(clamp(1.0 - dot(n, v) + mtoonRimLiftFactor, 0.0, 1.0), max(mtoonRimFresnelPowerFactor, 1e-5));
        // The rim takes the lighting (direct 1 + gi) as far as rimLightingMixFactor says; 0 is like emission.
        color += mtoonRimColorFactor * rim * mix(vec3(1.0), vec3(1.0) + gi, mtoonRimLightingMixFactor);
    }
    return color;
}
#endif
