// Shading, one model per program (MODEL_* define from ShadePass): flat, gouraud, lambert, phong, cel, comic, mtoon,
// auto (mtoon's colour for the materials with MToon, cel's for the others)
// (docs/shading.md, docs/mtoon.md; mtoon's colour is common/mtoon.glsl's for MToon materials, common/pbr.glsl's for the
// others, which forward programs include). The base colour is the material's (common/material.glsl: factor x texture x
// vertex colour). Colour is computed in linear RGB and written sRGB-encoded, with the surface's alpha (1 unless the
// material blends).
// Forward, the surface comes from the mesh drawn (shade.vert). With SHADE_DEFERRED (lambert, phong, cel, comic; see
// ShadePass::chooseMode()) it comes from the G-buffer texel of this pixel, computed there by the same expressions:
// the normal turned toward the viewer (alpha: the coverage) and the view vector; the base colour is a uniform when
// the scene has one (ShadePass::sceneBaseColor()), else the G-buffer's sRGB8 copy (hence up to a code of difference
// from forward).
#ifdef SHADE_DEFERRED
#if defined(MODEL_FLAT) || defined(MODEL_GOURAUD) || defined(MODEL_MTOON) || defined(MODEL_AUTO) || defined(SHADE_COORDS)
#error "deferred shading needs a model that shades from the pixel's normal, view and base colour"
#endif
layout(binding = GBUFFER_NORMAL_UNIT) uniform sampler2D gbufferNormal;
#ifdef GBUFFER_BASECOLOR_UNIT
layout(binding = GBUFFER_BASECOLOR_UNIT) uniform sampler2D gbufferBaseColor;
#else
uniform vec3 sceneBaseColor; // linear
#endif
#ifdef GBUFFER_VIEW_UNIT
layout(binding = GBUFFER_VIEW_UNIT) uniform sampler2D gbufferView;
#endif

// The G-buffer texel of this pixel: the G-buffer is the frame's size.
vec4 gbufferTexel(sampler2D field) {
    return texelFetch(field, ivec2(gl_FragCoord.xy), 0);
}

vec3 deferredNormal; // the G-buffer's, read once in main()
#else
in vec3 viewPosition;
in vec3 viewNormal;
#endif
#ifdef MODEL_GOURAUD
in vec3 vertexLight;
#endif
#ifdef SHADE_COORDS
in vec2 shadeCoord;
#endif

uniform vec3 towardLightView; // unit, view space
uniform float shininess;        // phong, comic
uniform float specularStrength; // phong: weight of the white specular
#ifdef SPECULAR_ROW_BANDS
// Comic: the map's rows in bands (ShadeMap.h specularRowBands). Band k + 1 holds t when x = |r - v|^2 / 2 <=
// specularBorderLimit[k] (decreasing in k); its first row (from the bottom, t = 0) is specularBandRow[k + 1].
// SPECULAR_ROW_BANDS is the number of borders, a compile-time constant so the loop unrolls to plain comparisons; with
// per-mesh maps it is the largest count in use and ShadePass pads each map's borders with -1 (never reached, x >= 0).
uniform float specularBorderLimit[SPECULAR_ROW_BANDS];
uniform int specularBandRow[SPECULAR_ROW_BANDS + 1];
#endif
#ifdef VIEW_CONSTANT
uniform vec3 constantTowardEye; // comic: -V_c in view space, unit (Winnemöller & Bangay 2002 §3.5)
#endif
#if defined(MODEL_CEL) || defined(MODEL_COMIC) || defined(MODEL_AUTO)
// Linear texels (ShadePass decodes the map's sRGB once), nearest, clamped; GL row 0 is the map image's bottom row
// (t = 0). Cel maps have one row.
layout(binding = 0) uniform sampler2D shadeMap;
#endif


layout(location = 0) out vec4 outColor;

#ifdef SHADE_DEFERRED
// The G-buffer's normal, which is shadingNormal() below, computed there.
vec3 shadingNormal() {
    return deferredNormal;
}

#ifdef GBUFFER_VIEW_UNIT
// The G-buffer's view vector, which is towardEye() below, computed there.
vec3 towardEye() {
    return gbufferTexel(gbufferView).xyz;
}
#endif
#else
// The interpolated normal, renormalised and, seen from behind (open meshes, holes), turned to the viewer's side.
vec3 shadingNormal() {
    float normalLength = length(viewNormal);
    vec3 n = normalLength > 0.0 ? viewNormal / normalLength : vec3(0.0, 0.0, 1.0);
    return gl_FrontFacing ? n : -n;
}

// Unit vector from the surface to the eye (the view-space origin).
vec3 towardEye() {
    float distanceToEye = length(viewPosition);
    return distanceToEye > 0.0 ? -viewPosition / distanceToEye : vec3(0.0, 0.0, 1.0);
}
#endif

#if defined(MODEL_CEL) || defined(MODEL_COMIC) || defined(MODEL_AUTO)
// Texel i = min(floor(u N), N - 1) of an axis of N texels; u = 1 stays on the last texel.
int shadeMapIndex(float u, int count) {
    return clamp(int(floor(u * float(count))), 0, count - 1);
}

// Linear colour of the texel in column `column`, row `row` (row 0 at the bottom, t = 0).
vec3 shadeMapTexel(int column, int row) {
    return texelFetch(shadeMap, ivec2(column, row), 0).rgb;
}

// Linear colour of the texel at (u, v); v is ignored by one-row maps.
vec3 shadeMapColor(vec2 uv) {
    ivec2 size = textureSize(shadeMap, 0);
    return shadeMapTexel(shadeMapIndex(uv.x, size.x), shadeMapIndex(uv.y, size.y));
}
#endif

void main() {
#ifdef SHADE_DEFERRED
    vec4 normalTexel = gbufferTexel(gbufferNormal);
    if (normalTexel.a == 0.0) {
        // Off the model: what forward shading's clear leaves. Every pixel is written, so the pass clears nothing.
        outColor = vec4(0.0);
        return;
    }
    deferredNormal = normalTexel.xyz;
#ifdef GBUFFER_BASECOLOR_UNIT
    vec4 surface = vec4(decodeSrgb(gbufferTexel(gbufferBaseColor).rgb), 1.0);
#else
    vec4 surface = vec4(sceneBaseColor, 1.0);
#endif
#else
    vec4 surface = materialBaseColor();
    if (materialCutsOut(surface.a)) discard;
#endif
    vec3 base = surface.rgb;
    vec3 l = towardLightView;
    vec3 rgb;
#if defined(MODEL_FLAT)
    // Qu, Chen & Zwicker's eq. 2, normalised; turned toward the viewer by geometry, so a y-flipped target cannot invert it.
    vec3 faceNormal = cross(dFdx(viewPosition), dFdy(viewPosition));
    float faceNormalLength = length(faceNormal);
    vec3 n = faceNormalLength > 0.0 ? faceNormal / faceNormalLength : vec3(0.0, 0.0, 1.0);
    if (dot(n, -viewPosition) < 0.0) n = -n;
    rgb = base * diffuseLighting(n, l, ambientLight);
#elif defined(MODEL_GOURAUD)
    rgb = base * vertexLight;
#elif defined(MODEL_LAMBERT)
    rgb = base * diffuseLighting(shadingNormal(), l, ambientLight);
#elif defined(MODEL_PHONG)
    vec3 n = shadingNormal();
    float nDotL = dot(n, l);
    float specular = nDotL > 0.0 ? specularTerm(reflect(-l, n), towardEye(), shininess) : 0.0;
    rgb = base * diffuseLighting(n, l, ambientLight) + vec3(specularStrength * specular);
#elif defined(MODEL_CEL)
    rgb = shadeMapColor(vec2(halfLambert(shadingNormal(), l), 0.0)) * base;
#elif defined(MODEL_COMIC)
#ifdef SHADE_COORDS
    // Winnemöller & Bangay's per-vertex (s, t) from the CPU, interpolated.
    rgb = shadeMapColor(shadeCoord) * base;
#else
    vec3 n = shadingNormal();
    float nDotL = dot(n, l);
#ifdef VIEW_CONSTANT
    vec3 v = constantTowardEye;
#else
    vec3 v = towardEye();
#endif
#ifdef SPECULAR_ROW_BANDS
    // The row by comparisons in the distance domain: no log or exp, and exact at any shininess.
    int row = 0;
    if (nDotL > 0.0) {
        vec3 d = reflect(-l, n) - v;
        float x = 0.5 * dot(d, d);
        for (int border = 0; border < SPECULAR_ROW_BANDS; ++border)
            if (x <= specularBorderLimit[border]) row = specularBandRow[border + 1];
    }
    rgb = shadeMapTexel(shadeMapIndex(max(nDotL, 0.0), textureSize(shadeMap, 0).x), row) * base;
#else
    vec2 st = vec2(max(nDotL, 0.0), nDotL > 0.0 ? specularTerm(reflect(-l, n), v, shininess) : 0.0);
    rgb = shadeMapColor(st) * base;
#endif
#endif
#elif defined(MODEL_MTOON)
    // A material without MToon (a VRM's other materials, any glTF, OBJ, ...) is glTF's metallic-roughness, as three-vrm
    // draws it (common/pbr.glsl).
    if (mtoonPresent != 0)
        rgb = mtoonColor(base, mtoonShadingNormal(shadingNormal(), viewPosition), l, towardEye());
    else
        rgb = pbrColor(base, shadingNormal(), l, towardEye());
#elif defined(MODEL_AUTO)
    // Each material its own model: its MToon where it has one, else cel's band (as MODEL_CEL).
    if (mtoonPresent != 0)
        rgb = mtoonColor(base, mtoonShadingNormal(shadingNormal(), viewPosition), l, towardEye());
    else
        rgb = shadeMapColor(vec2(halfLambert(shadingNormal(), l), 0.0)) * base;
#else
#error "shade.frag needs one MODEL_* define"
#endif
    // KHR_materials_unlit: no lighting at all, in every model. A VRM material that also has MToon is not unlit (the
    // reader clears the flag: exporters write it as MToon's fallback for viewers without MToon, docs/mtoon.md).
    // Deferred shading has no unlit material (forwardReason() keeps such scenes forward).
#ifndef SHADE_DEFERRED
    if (materialUnlit != 0) rgb = base;
#endif
#ifndef SHADE_DEFERRED
    rgb += materialEmissive();
#endif
    // Straight alpha for the blend of BLEND surfaces over what is behind them; cut-out and opaque surfaces are 1.
#if defined(SHADE_DEFERRED)
    outColor = vec4(encodeSrgb(rgb), 1.0); // no blended material (chooseMode())
#else
    outColor = vec4(encodeSrgb(rgb), materialAlphaMode == 2 ? surface.a : 1.0);
#endif
}
