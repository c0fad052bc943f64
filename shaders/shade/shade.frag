// Forward shading, one model per program (MODEL_* define from ShadePass): flat, gouraud, lambert, phong, cel, comic
// (docs/shading.md). Colour is computed in linear RGB and written sRGB-encoded, alpha 1 on the model.
in vec3 viewPosition;
in vec3 viewNormal;
#ifdef MODEL_GOURAUD
in vec3 vertexColor;
#endif
#ifdef SHADE_COORDS
in vec2 shadeCoord;
#endif

uniform vec4 baseColor;       // linear
uniform vec3 towardLightView; // unit, view space
uniform float ambient;          // flat, gouraud, lambert, phong
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
#if defined(MODEL_CEL) || defined(MODEL_COMIC)
// sRGB texels, nearest, clamped; GL row 0 is the map image's bottom row (t = 0). Cel maps have one row.
layout(binding = 0) uniform sampler2D shadeMap;
#endif

layout(location = 0) out vec4 outColor;

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

#if defined(MODEL_CEL) || defined(MODEL_COMIC)
// Texel i = min(floor(u N), N - 1) of an axis of N texels; u = 1 stays on the last texel.
int shadeMapIndex(float u, int count) {
    return clamp(int(floor(u * float(count))), 0, count - 1);
}

// Linear colour of the texel in column `column`, row `row` (row 0 at the bottom, t = 0).
vec3 shadeMapTexel(int column, int row) {
    return decodeSrgb(texelFetch(shadeMap, ivec2(column, row), 0).rgb);
}

// Linear colour of the texel at (u, v); v is ignored by one-row maps.
vec3 shadeMapColor(vec2 uv) {
    ivec2 size = textureSize(shadeMap, 0);
    return shadeMapTexel(shadeMapIndex(uv.x, size.x), shadeMapIndex(uv.y, size.y));
}
#endif

void main() {
    vec3 l = towardLightView;
    vec3 rgb;
#if defined(MODEL_FLAT)
    // Qu, Chen & Zwicker's eq. 2, normalised; turned toward the viewer by geometry, so a y-flipped target cannot invert it.
    vec3 faceNormal = cross(dFdx(viewPosition), dFdy(viewPosition));
    float faceNormalLength = length(faceNormal);
    vec3 n = faceNormalLength > 0.0 ? faceNormal / faceNormalLength : vec3(0.0, 0.0, 1.0);
    if (dot(n, -viewPosition) < 0.0) n = -n;
    rgb = baseColor.rgb * diffuseLighting(n, l, ambient);
#elif defined(MODEL_GOURAUD)
    rgb = vertexColor;
#elif defined(MODEL_LAMBERT)
    rgb = baseColor.rgb * diffuseLighting(shadingNormal(), l, ambient);
#elif defined(MODEL_PHONG)
    vec3 n = shadingNormal();
    float nDotL = dot(n, l);
    float specular = nDotL > 0.0 ? specularTerm(reflect(-l, n), towardEye(), shininess) : 0.0;
    rgb = baseColor.rgb * diffuseLighting(n, l, ambient) + vec3(specularStrength * specular);
#elif defined(MODEL_CEL)
    rgb = shadeMapColor(vec2(halfLambert(shadingNormal(), l), 0.0)) * baseColor.rgb;
#elif defined(MODEL_COMIC)
#ifdef SHADE_COORDS
    // Winnemöller & Bangay's per-vertex (s, t) from the CPU, interpolated.
    rgb = shadeMapColor(shadeCoord) * baseColor.rgb;
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
    rgb = shadeMapTexel(shadeMapIndex(max(nDotL, 0.0), textureSize(shadeMap, 0).x), row) * baseColor.rgb;
#else
    vec2 st = vec2(max(nDotL, 0.0), nDotL > 0.0 ? specularTerm(reflect(-l, n), v, shininess) : 0.0);
    rgb = shadeMapColor(st) * baseColor.rgb;
#endif
#endif
#else
#error "shade.frag needs one MODEL_* define"
#endif
    outColor = vec4(encodeSrgb(rgb), 1.0);
}
