// Back-face outline: one triangle in, its three edges out as screen-space quads 2 x halfWidthPixels wide with
// square caps (core profile has no dependable wide lines, and quads keep the width at every angle).
layout(triangles) in;
layout(triangle_strip, max_vertices = 12) out;

uniform vec2 viewportSize;    // pixels
uniform float halfWidthPixels;

in vec3 viewPosition[];
// common/material.glsl's attributes, passed on per corner so line_mask.frag cuts the edges a material cuts out
// (always passed: the fragment stage declares the block whether or not it reads it).
in MaterialVarying {
    vec2 texcoord0;
    vec2 texcoord1;
    vec4 vertexColor;
} materialIn[];
out MaterialVarying {
    vec2 texcoord0;
    vec2 texcoord1;
    vec4 vertexColor;
} materialOut;

// An edge is clipped to the near plane (reversed-Z, gl/GlObjects.h: clip z <= w in front of it), where w equals the
// near distance, so w stays positive. The
// guard is w > 0 and not an absolute floor: w is a view depth in model units, so a floor such as 1e-7 dropped every
// edge of a model scaled to 1e-9 (tests/pipeline/ExtremesGLTest, exact scales).

// Clips the segment a-b to the near plane's visible side; false when none of it is visible.
bool clipToNearPlane(inout vec4 a, inout vec4 b) {
    float distanceA = a.w - a.z;
    float distanceB = b.w - b.z;
    if (distanceA < 0.0 && distanceB < 0.0) return false;
    if (distanceA < 0.0) {
        a = mix(a, b, distanceA / (distanceA - distanceB));
    } else if (distanceB < 0.0) {
        b = mix(b, a, distanceB / (distanceB - distanceA));
    }
    return a.w > 0.0 && b.w > 0.0;
}

void emitCorner(vec4 clip, vec2 offsetPixels, int corner) {
    materialOut.texcoord0 = materialIn[corner].texcoord0;
    materialOut.texcoord1 = materialIn[corner].texcoord1;
    materialOut.vertexColor = materialIn[corner].vertexColor;
    // Offset in NDC, times w so the divide leaves it intact; z and w stay the endpoint's, so depth follows the edge.
    gl_Position = vec4(clip.xy + offsetPixels * (2.0 / viewportSize) * clip.w, clip.z, clip.w);
    EmitVertex();
}

void emitEdgeQuad(int first, int second) {
    vec4 a = gl_in[first].gl_Position;
    vec4 b = gl_in[second].gl_Position;
    if (!clipToNearPlane(a, b)) return;
    vec2 pixelsA = a.xy / a.w * 0.5 * viewportSize;
    vec2 pixelsB = b.xy / b.w * 0.5 * viewportSize;
    vec2 along = pixelsB - pixelsA;
    float edgeLength = length(along);
    // An edge seen end-on (along the line of sight) becomes a square around its point.
    vec2 direction = edgeLength > 1e-4 ? along / edgeLength : vec2(1.0, 0.0);
    vec2 lengthwise = direction * halfWidthPixels;
    vec2 across = vec2(-direction.y, direction.x) * halfWidthPixels;
    emitCorner(a, -lengthwise - across, first);
    emitCorner(a, -lengthwise + across, first);
    emitCorner(b, lengthwise - across, second);
    emitCorner(b, lengthwise + across, second);
    EndPrimitive();
}

void main() {
    // Front-facing: the outward (counter-clockwise) normal points toward the eye at the view-space origin. Exact
    // under perspective and independent of clipping, unlike a screen-space winding test. Made for the CPU's back
    // sets too: they also hold Listing 1's "intermediate" front-facing triangles, whose edges would hatch the surface.
    vec3 normal = cross(viewPosition[1] - viewPosition[0], viewPosition[2] - viewPosition[0]);
    vec3 middle = (viewPosition[0] + viewPosition[1] + viewPosition[2]) / 3.0;
    if (dot(normal, middle) < 0.0) return;
    emitEdgeQuad(0, 1);
    emitEdgeQuad(1, 2);
    emitEdgeQuad(2, 0);
}
