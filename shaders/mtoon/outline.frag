// MToon's outline colour (docs/mtoon.md): the full MToon surface result (common/mtoon.glsl) evaluated at the shell
// fragment with the shell vertex's normal, taken into the outline colour as far as the lighting mix says; opaque.
in vec3 viewPosition;
in vec3 viewNormal;

uniform vec3 towardLightView; // unit, view space
uniform vec3 mtoonOutlineColorFactor; // linear
uniform float mtoonOutlineLightingMixFactor;

layout(location = 0) out vec4 outColor;

void main() {
    vec4 surface = materialBaseColor();
    if (materialCutsOut(surface.a)) discard;
    vec3 base = surface.rgb;
    vec3 l = towardLightView;
    // The shell is seen from inside (front faces culled): its normal already points out, and is not flipped.
    float normalLength = length(viewNormal);
    vec3 n = normalLength > 0.0 ? viewNormal / normalLength : vec3(0.0, 0.0, 1.0);
    float distanceToEye = length(viewPosition);
    vec3 v = distanceToEye > 0.0 ? -viewPosition / distanceToEye : vec3(0.0, 0.0, 1.0);
    vec3 rgb = mtoonColor(base, n, l, v);
    rgb += materialEmissive();
    rgb = mix(mtoonOutlineColorFactor, mtoonOutlineColorFactor * rgb, mtoonOutlineLightingMixFactor);
    outColor = vec4(encodeSrgb(rgb), 1.0);
}
