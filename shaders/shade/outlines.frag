// The material outlines drawn by another pass (mtoon-outline: MToon's shells, colour and depth) laid into forward
// shading after its opaque surfaces, on deferred.vert's full-screen triangle. Each shell pixel goes in at its own
// depth (gl_FragDepth) under the pass's strictly-nearer test, as the shell's fragment would have, and writes depth,
// so the blended surfaces drawn next go over it. Texel-exact: the layer is the frame's size.
layout(binding = OUTLINE_COLOR_UNIT) uniform sampler2D outlineColor; // sRGB8 values, a = 1 where a shell is
layout(binding = OUTLINE_DEPTH_UNIT) uniform sampler2D outlineDepth; // window depth (reversed-Z)

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 color = texelFetch(outlineColor, texel, 0);
    if (color.a == 0.0) discard; // no shell here
    gl_FragDepth = texelFetch(outlineDepth, texel, 0).r;
    outColor = color;
}
