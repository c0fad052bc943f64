// Colour helpers: shading is computed in linear RGB; every 8-bit colour target holds sRGB-encoded values (so files
// read correctly in any viewer and dark tones keep their precision).
vec3 encodeSrgb(vec3 linearRgb) {
    vec3 clamped = clamp(linearRgb, 0.0, 1.0);
    vec3 low = clamped * 12.92;
    vec3 high = 1.055 * pow(clamped, vec3(1.0 / 2.4)) - 0.055;
    return mix(high, low, lessThanEqual(clamped, vec3(0.0031308)));
}

vec3 decodeSrgb(vec3 encoded) {
    vec3 low = encoded / 12.92;
    vec3 high = pow((encoded + 0.055) / 1.055, vec3(2.4));
    return mix(high, low, lessThanEqual(encoded, vec3(0.04045)));
}
