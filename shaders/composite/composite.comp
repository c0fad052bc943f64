// postfx/Composite.cpp compositeFinal() as a compute shader (--post-stage gpu, passes/composite/GpuCompositePass.h),
// in the same 8-bit integer arithmetic, so the picture is the CPU's to the byte. BASE: the paper, and the shading
// (premultiplied) over it; otherwise one line layer over what `finalImage` holds. Every texture of the graph has GL's
// bottom-up rows, so a pixel is the same texel in all of them.
layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = 0, rgba8) uniform image2D finalImage;
layout(binding = 0) uniform sampler2D layer; // BASE: the shading colour (rgba8); else the line layer (r8)

uniform ivec2 size;
#if defined(BASE)
uniform uvec4 paper;     // the paper colour in bytes
uniform bool hasShading; // false for --shading none
#else
uniform uvec4 lineColor; // the layer's colour in bytes
#endif

uvec4 bytesOf(vec4 unorm) { return uvec4(round(unorm * 255.0)); }

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= size.x || texel.y >= size.y) return;
#if defined(BASE)
    uvec4 result = paper;
    if (hasShading) {
        uvec4 shading = bytesOf(texelFetch(layer, texel, 0));
        uint alpha = shading.a;
        if (alpha == 255u) {
            result = shading;
        } else if (alpha != 0u) { // premultiplied: shading + paper x (1 - alpha)
            result.rgb = min(uvec3(255u), shading.rgb + (paper.rgb * (255u - alpha) + 127u) / 255u);
            result.a = alpha + (paper.a * (255u - alpha) + 127u) / 255u;
        }
    }
    imageStore(finalImage, texel, vec4(result) / 255.0);
#else
    uint mask = bytesOf(texelFetch(layer, texel, 0)).r;
    if (mask == 0u) return;
    uvec4 below = bytesOf(imageLoad(finalImage, texel));
    uint alpha = (mask * lineColor.a + 127u) / 255u;
    uvec4 result;
    result.rgb = (lineColor.rgb * alpha + below.rgb * (255u - alpha) + 127u) / 255u;
    result.a = alpha + (below.a * (255u - alpha) + 127u) / 255u;
    imageStore(finalImage, texel, vec4(result) / 255.0);
#endif
}
