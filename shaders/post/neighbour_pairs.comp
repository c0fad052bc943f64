// The image-space line kernels of postfx/ over 4-neighbour pairs as one compute shader (--post-stage gpu), one
// kernel per define: CONTOUR (postfx/Contour.cpp extractContours: depth breaks and n.v sign changes), DEPTH_EDGE
// (postfx/ImageEdges.cpp extractDepthEdges: depth breaks) or NORMAL_EDGE (extractNormalEdges: creases between
// normals, pairs across a depth break skipped). Every pair (p, q), q being p's right or lower neighbour in image rows
// (row 0 at the top, which is GL's top texel row), is visited once, by p's invocation. A pair that marks a pixel
// appends one event: the pair, which of its two pixels is marked, and where along the pair the point lies. The CPU
// reads back only the events, sorts them into the CPU kernel's order and builds the skeleton
// (passes/lines/types/GpuImageEdges.h).
layout(local_size_x = 16, local_size_y = 16) in;

#if defined(CONTOUR)
layout(binding = 0) uniform sampler2D nDotVField; // n.v of the visible surface
#elif defined(NORMAL_EDGE)
layout(binding = 0) uniform sampler2D normalField; // the view-space normal (xyz)
#endif
layout(binding = 1) uniform sampler2D depthField; // linear view depth, 0 = background

layout(std430, binding = 0) buffer PairEvents {
    // Every event found, those past `capacity` too: the CPU then grows the buffer and runs the kernel again.
    uint eventCount;
    uint unused0;
    uint unused1;
    uint unused2;
    // x: the pair, 2 (row x width + col) of p, + 1 for the pair below; y: 1 when q is the marked pixel, 0 for p;
    // z: the bits of `along`, the point being p + along (q - p).
    uvec4 events[];
};

uniform ivec2 size;      // the fields' size
uniform float depthJump; // the relative depth jump of a depth break (postfx/LineSkeleton.h isDepthBreak)
uniform uint capacity;   // the length of events[]
#if defined(NORMAL_EDGE)
uniform float cosCreaseSigned;  // cos(crease) |cos(crease)|
uniform float sinCreaseSquared; // sin(crease)^2
uniform bool zeroCrease;        // a zero crease angle: every pair of different directions is a crease
#endif

ivec2 texelOf(int col, int row) { return ivec2(col, size.y - 1 - row); }

void append(uint pair, bool marksQ, float along) {
    uint index = atomicAdd(eventCount, 1u);
    if (index < capacity) events[index] = uvec4(pair, marksQ ? 1u : 0u, floatBitsToUint(along), 0u);
}

#if defined(NORMAL_EDGE)
// postfx/ImageEdges.cpp Creases::isCrease, term by term (`precise`: no fused multiply-add the CPU does not do).
bool isCrease(vec3 a, vec3 b) {
    precise float crossX = a.y * b.z - a.z * b.y;
    precise float crossY = a.z * b.x - a.x * b.z;
    precise float crossZ = a.x * b.y - a.y * b.x;
    precise float sineSquared = crossX * crossX + crossY * crossY + crossZ * crossZ;
    precise float cosine = a.x * b.x + a.y * b.y + a.z * b.z;
    precise float cosineSigned = cosine * abs(cosine);
    precise float left = sineSquared * cosCreaseSigned;
    precise float right = cosineSigned * sinCreaseSquared;
    return left > right || (zeroCrease && cosine < 0.0);
}
#endif

// postfx/NeighbourPairs.h classifyPair() and the kernel's mark(), pair by pair.
void visitPair(int col, int row, int otherCol, int otherRow, uint pair) {
    ivec2 texelA = texelOf(col, row);
    ivec2 texelB = texelOf(otherCol, otherRow);
    float depthA = texelFetch(depthField, texelA, 0).r;
    float depthB = texelFetch(depthField, texelB, 0).r;
    bool coveredA = depthA > 0.0;
    bool coveredB = depthB > 0.0;
    bool both = coveredA && coveredB;
    if (coveredA != coveredB || (both && abs(depthA - depthB) > depthJump * min(depthA, depthB))) {
#if defined(NORMAL_EDGE)
        return; // a depth break is the depth edge's, not a crease
#else
        // The nearer pixel is marked, the point at the midpoint; a NaN depth is never the nearer one.
        bool aNearer = !(depthB > 0.0) || (depthA > 0.0 && depthA < depthB);
        append(pair, !aNearer, 0.5);
        return;
#endif
    }
    if (!both) return;
#if defined(CONTOUR)
    float a = texelFetch(nDotVField, texelA, 0).r;
    float b = texelFetch(nDotVField, texelB, 0).r;
    if ((a >= 0.0) == (b >= 0.0)) return; // no sign change (0 counts as front-facing)
    float along = a / (a - b);           // the linear zero crossing
    if (!(along >= 0.0 && along <= 1.0)) return;
    append(pair, !(abs(a) <= abs(b)), along);
#elif defined(NORMAL_EDGE)
    if (isCrease(texelFetch(normalField, texelA, 0).xyz, texelFetch(normalField, texelB, 0).xyz))
        append(pair, false, 0.5); // the left or upper pixel, the point at the midpoint
#endif
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy); // x: column, y: image row
    if (pixel.x >= size.x || pixel.y >= size.y) return;
    uint index = uint(pixel.y) * uint(size.x) + uint(pixel.x);
    if (pixel.x + 1 < size.x) visitPair(pixel.x, pixel.y, pixel.x + 1, pixel.y, 2u * index);
    if (pixel.y + 1 < size.y) visitPair(pixel.x, pixel.y, pixel.x, pixel.y + 1, 2u * index + 1u);
}
