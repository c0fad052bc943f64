// Object-space edges: a line fragment is kept when it is no deeper than the farthest of the model's (offset) depth
// at its pixel and its 4 edge neighbours, so visibility is decided to within a pixel. The polygon offset of the
// depth lets a line pass over the faces it lies on (valleys included); the neighbours let it pass where its pixel
// centre falls on a nearer face that does not hold the edge (a sub-pixel sliver beside a silhouette edge): a visible
// edge always has, one pixel across it (up or down for a line running more across than up, else left or right), a
// side whose surface is no nearer than itself. A line behind the surface stays hidden unless it runs within a pixel
// of the occluder's outline.
// With HIDDEN (the hidden-* outputs, --hidden-lines) the test is turned round: a fragment is kept exactly where the
// visible test drops it, so every fragment of an edge lands in one of the two outputs and none in both.
layout(location = 0) out float outLine;
// --strokes (MeshEdgesPass "<kind>-points", when writePoints): the fragment's view position, interpolated along its
// edge, and the edge's triangle (global index + 1) from the edge list's buffer: gl_PrimitiveID counts the draw's
// lines, or its points, two per edge.
layout(location = 1) out vec4 outPoint;
in vec3 viewPosition;
layout(std430, binding = 1) readonly buffer EdgeTriangles { float edgeTriangle[]; };
uniform bool writePoints;
uniform int primitivesPerEdge;

// Window depth of the model, polygon offset applied, reversed-Z (gl/GlObjects.h): 1 at the near plane, 0 = nothing,
// so the farthest is the smallest and a fragment is behind it when its depth is smaller.
layout(binding = 0) uniform sampler2D modelDepth;

void main() {
#ifdef MATERIAL_ALPHA
    if (materialCutsOut(materialBaseColor().a)) discard; // common/material.glsl
#endif
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 lastPixel = textureSize(modelDepth, 0) - 1;
    const ivec2 kAround[5] = ivec2[5](ivec2(0, 0), ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    float farthest = 1.0;
    for (int i = 0; i < 5; ++i) {
        farthest = min(farthest, texelFetch(modelDepth, clamp(pixel + kAround[i], ivec2(0), lastPixel), 0).r);
    }
#ifdef HIDDEN
    if (gl_FragCoord.z >= farthest) discard;
#else
    if (gl_FragCoord.z < farthest) discard;
#endif
    outLine = 1.0;
    outPoint = vec4(0.0);
    if (writePoints) outPoint = vec4(viewPosition, edgeTriangle[gl_PrimitiveID / primitivesPerEdge]);
}
