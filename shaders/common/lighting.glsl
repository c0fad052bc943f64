// Lighting terms shared by the shading passes (docs/shading.md). Every vector is unit and in
// view space: n the normal, l surface -> light, v surface -> eye, r = reflect(-l, n) (the incident direction is -l).

// The uniform ambient light, linear RGB (FrameParams::ambientLight, --ambient): the ambient term of flat, gouraud,
// lambert and phong, and MToon's global illumination (common/mtoon.glsl).
uniform vec3 ambientLight;

// Ambient plus Lambert diffuse, the factor the base colour is multiplied with.
vec3 diffuseLighting(vec3 n, vec3 l, vec3 ambient) {
    return ambient + (1.0 - ambient) * max(dot(n, l), 0.0);
}

// Qu, Chen & Zwicker's half-Lambert q = (n.l + 1) / 2, in [0, 1].
float halfLambert(vec3 n, vec3 l) {
    return clamp(0.5 * dot(n, l) + 0.5, 0.0, 1.0);
}

// max(r.v, 0)^shininess, finite for every shininess in [0, 1e6] (and beyond). pow() is undefined for a zero or
// negative base, and 1 - r.v is lost to float cancellation long before shininess reaches 1e6, so:
// - shininess 0 gives 1 (C's pow(0, 0), not GLSL's undefined value);
// - near the highlight, where it matters, log(r.v) = log(1 - x) comes from x = |r - v|^2 / 2 (small values of
//   |r - v|^2 keep their relative precision) as the series -x - x^2/2 - x^3/3, whose error is below x^4/4 (1e-8 at
//   the switch, x = 1/64);
// - farther out, log(r.v) of the dot product itself, which is exact to a few 1e-8 even where r.v is near 0 (where
//   1 - x would keep only the rounding error of x: 2e-4 instead of 0 for r perpendicular to v at shininess 0.5);
// - 0 where r.v <= 0; the result exp(shininess log(r.v)) is in [0, 1] and underflows to 0, never to Inf or NaN.
float specularTerm(vec3 r, vec3 v, float shininess) {
    if (shininess <= 0.0) return 1.0;
    float cosine = dot(r, v);
    if (cosine <= 0.0) return 0.0;
    vec3 d = r - v;
    float x = 0.5 * dot(d, d);
    float logCosine = x < 1.0 / 64.0 ? -x * (1.0 + x * (0.5 + x * (1.0 / 3.0))) : log(cosine);
    return exp(shininess * logCosine);
}
