// Inflated hull: the model pushed out along its hull normals. HULL_SCREEN_WIDTH moves each vertex a constant number
// of pixels on screen (the offset is scaled by clip w, so it survives the perspective divide unchanged);
// HULL_OBJECT_WIDTH moves it in model units. With neither, the model itself (the pass's depth draw).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inHullNormal; // unit, position-welded (or the raw normals when the test hook says so)

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel; // inverse-transpose of viewFromModel's upper 3x3
uniform mat4 clipFromView;
uniform vec2 viewportSize;        // pixels
uniform float widthPixels;
uniform float objectWidth;        // model units

void main() {
    vec3 position = inPosition;
#ifdef HULL_OBJECT_WIDTH
    position += objectWidth * inHullNormal;
#endif
    vec4 clip = clipFromView * (viewFromModel * vec4(position, 1.0));
#ifdef HULL_SCREEN_WIDTH
    // The normal's screen direction in pixels: clip xy of the direction, scaled by the viewport so a non-square
    // frame does not bend it (NDC to pixels also halves, which a direction does not care about).
    vec2 normalPixels = (clipFromView * vec4(viewNormalFromModel * inHullNormal, 0.0)).xy * viewportSize;
    float normalLength = length(normalPixels);
    // A normal along the line of sight has no screen direction: normalize() would give NaN, so it stays put.
    if (normalLength > 1e-6 * max(viewportSize.x, viewportSize.y)) {
        clip.xy += (normalPixels / normalLength) * (2.0 * widthPixels / viewportSize) * clip.w;
    }
#endif
    gl_Position = clip;
#ifdef MATERIAL_ALPHA
    passMaterialAttributes();
#endif
}
