// MToon's surface colour (VRMC_materials_mtoon-1.0, docs/mtoon.md) from the mesh's material parameters, which
// passes/material/SceneMaterials binds: the shade pass shades the surface with it (shade/shade.frag, MODEL_MTOON) and
// the mtoon-outline pass lights its shells with it (mtoon/outline.frag). Needs common/material.glsl before it.
#ifdef INKGRAPH_FRAGMENT_STAGE
// A material without MToon gets mtoonPresent 0, and shading draws it with common/pbr.glsl instead.
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
// Units 7 to 11: SceneMaterials.h's kMatcapTextureUnit and the rest.
uniform int mtoonShadingShiftTextured;
uniform int mtoonShadingShiftSet;
uniform mat3 mtoonShadingShiftTransform;
uniform float mtoonShadingShiftTextureScale;
layout(binding = 9) uniform sampler2D mtoonShadingShiftTexture; // linear data: its red channel
uniform vec3 mtoonMatcapFactor;                                 // linear
uniform int mtoonMatcapTextured;
uniform mat3 mtoonMatcapTransform;
layout(binding = 7) uniform sampler2D mtoonMatcapTexture; // sRGB storage: linear colour
uniform int mtoonRimMultiplyTextured;
uniform int mtoonRimMultiplySet;
uniform mat3 mtoonRimMultiplyTransform;
layout(binding = 8) uniform sampler2D mtoonRimMultiplyTexture; // sRGB storage: linear colour
uniform int materialNormalTextured;
uniform int materialNormalSet;
uniform mat3 materialNormalTransform;
uniform float materialNormalScale;
layout(binding = 10) uniform sampler2D materialNormalTexture; // linear data: xyz = 2 rgb - 1, tangent space
uniform mat3 worldFromView; // the view's rotation undone (passes/ViewUniforms.h)

// MToon's linearstep: 0 below a, 1 above b, linear between (the specification's definition).
float linearstep(float a, float b, float t) {
    return clamp((t - a) / max(b - a, 1e-6), 0.0, 1.0);
}

// Where the matcap texture is read for the unit normal `n` seen along the unit `v` toward the eye, both in view space:
// the specification's matcap uv, in world space as UniVRM computes it (its x axis horizontal in the world, its y axis
// the view's up tilted to be perpendicular to v; 0.495 keeps the disc off the texture's border), with v flipped so that
// a normal facing up reads the image's top, as in UniVRM (whose textures' v runs up) and in any matcap image.
vec2 mtoonMatcapUv(vec3 n, vec3 v) {
    vec3 worldN = worldFromView * n;
    vec3 worldV = worldFromView * v;
    vec3 across = vec3(worldV.z, 0.0, -worldV.x);
    // Looking straight up or down the world's y axis leaves no horizontal direction; any is as good.
    across = dot(across, across) > 1e-12 ? normalize(across) : vec3(1.0, 0.0, 0.0);
    vec3 up = cross(worldV, across);
    vec2 disc = vec2(dot(across, worldN), dot(up, worldN)) * 0.495 + 0.5;
    return materialTransformed(vec2(disc.x, 1.0 - disc.y), mtoonMatcapTransform);
}

// The shading normal `n` (unit, turned toward the viewer) bent by an MToon material's normal map at the view-space
// `position`. The tangent frame is the surface's own, per pixel, from the screen-space derivatives of the position and
// the normal map's uv (the reader keeps no TANGENT attribute): solving dp = dp/du du + dp/dv dv for the pixel's two
// steps gives dp/du and dp/dv, made perpendicular to n; glTF's map is +x along u and +y against v (up the image). On a
// back face the whole frame turns with n, so the map's bump is a dent from behind, as glTF's double-sided rule says.
vec3 mtoonShadingNormal(vec3 n, vec3 position) {
    if (mtoonPresent == 0 || materialNormalTextured == 0) return n;
    vec2 uv = materialTexcoord(materialNormalSet, materialNormalTransform);
    vec3 tangentSample = texture(materialNormalTexture, uv).rgb * 2.0 - 1.0;
    vec3 dpdx = dFdx(position);
    vec3 dpdy = dFdy(position);
    vec2 duvdx = dFdx(uv);
    vec2 duvdy = dFdy(uv);
    float determinant = duvdx.x * duvdy.y - duvdx.y * duvdy.x;
    if (abs(determinant) < 1e-20) return n; // the map is not spread over this pixel: no frame to bend in
    vec3 alongU = (dpdx * duvdy.y - dpdy * duvdx.y) / determinant;
    vec3 alongV = (dpdy * duvdx.x - dpdx * duvdy.x) / determinant;
    vec3 tangent = alongU - n * dot(n, alongU);
    vec3 bitangent = -alongV - n * dot(n, -alongV);
    if (dot(tangent, tangent) < 1e-24 || dot(bitangent, bitangent) < 1e-24) return n;
    tangent = normalize(tangent);
    bitangent = normalize(bitangent);
    if (!gl_FrontFacing) {
        tangent = -tangent;
        bitangent = -bitangent;
    }
    vec3 bent = tangent * (tangentSample.x * materialNormalScale) + bitangent * (tangentSample.y * materialNormalScale) +
                n * tangentSample.z;
    float bentLength = length(bent);
    return bentLength > 0.0 ? bent / bentLength : n;
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
        if (mtoonShadingShiftTextured != 0)
            shift += texture(mtoonShadingShiftTexture,
                             materialTexcoord(mtoonShadingShiftSet, mtoonShadingShiftTransform)).r *
                     mtoonShadingShiftTextureScale;
        toony = mtoonShadingToonyFactor;
    }
    float shading = linearstep(-1.0 + toony, 1.0 - toony, dot(n, l) + shift);
    // The direct light is white of intensity 1: its colour multiplies nothing.
    vec3 color = mix(shade, lit, shading);
    // Global illumination: the ambient light is uniform, so rawGi(n) is the same in every direction and the
    // specification's equalization between it and (rawGi(up) + rawGi(down)) / 2 changes nothing: gi = ambientLight.
    vec3 gi = ambientLight;
    color += gi * lit;
    if (mtoonPresent != 0) {
        float parametricRim =
            pow(clamp(1.0 - dot(n, v) + mtoonRimLiftFactor, 0.0, 1.0), max(mtoonRimFresnelPowerFactor, 1e-5));
        vec3 rim = mtoonRimColorFactor * parametricRim;
        if (mtoonMatcapTextured != 0)
            rim += mtoonMatcapFactor * texture(mtoonMatcapTexture, mtoonMatcapUv(n, v)).rgb;
        if (mtoonRimMultiplyTextured != 0)
            rim *= texture(mtoonRimMultiplyTexture, materialTexcoord(mtoonRimMultiplySet, mtoonRimMultiplyTransform)).rgb;
        // The rim takes the lighting (direct 1 + gi) as far as rimLightingMixFactor says; 0 is like emission.
        color += rim * mix(vec3(1.0), vec3(1.0) + gi, mtoonRimLightingMixFactor);
    }
    return color;
}
#endif
