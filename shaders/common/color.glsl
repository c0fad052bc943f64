// Colour helpers: shading is computed in linear RGB and encoded to sRGB once, when written to an 8-bit target.
vec3 encodeSrgb(vec3 linearRgb) {
    vec3 clamped = clamp(linearRgb, 0.0, 1.0);
    vec3 low = clamped * 12.92;
    vec3 high = 1.055 * pow(clamped, vec3(1.0 / 2.4)) - 0.055;
    return mix(high, low, lessThanEqual(clamped, vec3(0.0031308)));
}
