// The material outlines drawn by another pass (mtoon-outline: MToon's shells, colour and depth) laid into forward
// shading after its opaque surfaces, on deferred.vert's full-screen triangle. Each shell pixel goes in at its own
// depth (gl_FragDepth) under the pass's strictly-nearer test, as the shell's fragment would have, and writes depth,
// so the blended surfaces drawn next go over it. Texel-exact: the layer is the frame's size.
// OUTLINE_MULTISAMPLED (--msaa): the layer and the shading's target have the same samples at the same (fixed)
// locations; reading gl_SampleID makes this shader run once per sample, each sample taking the layer's own sample
// with its depth, so a shell's anti-aliased edge meets the surfaces sample by sample, as the shell drawn among them
// would.
#ifdef OUTLINE_MULTISAMPLED
layout(binding = OUTLINE_COLOR_UNIT) uniform sampler2DMS outlineColor; // sRGB8 values, a = 1 where a shell is
layout(binding = OUTLINE_DEPTH_UNIT) uniform sampler2DMS outlineDepth; // window depth (reversed-Z)
#define OUTLINE_SAMPLE gl_SampleID
#else
layout(binding = OUTLINE_COLOR_UNIT) uniform sampler2D outlineColor; // sRGB8 values, a = 1 where a shell is
layout(binding = OUTLINE_DEPTH_UNIT) uniform sampler2D outlineDepth; // window depth (reversed-Z)
#define OUTLINE_SAMPLE 0 // the level
#endif

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 color = texelFetch(outlineColor, texel, OUTLINE_SAMPLE);
    if (color.a == 0.0) discard; // no shell here
    gl_FragDepth = texelFetch(outlineDepth, texel, OUTLINE_SAMPLE).r;
    outColor = color;
}
