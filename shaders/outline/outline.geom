// Lander's outline, one mesh edge at a time (passes/outline/OutlinePass.h): its two ends and an opposite vertex of a
// face on each side in, and, where the surface folds away from the eye there (or the edge is a border), a
// screen-space quad widthPixels wide on the side away from its faces out, with square caps (core profile has no
// dependable wide lines, and quads keep the width at every angle).
layout(lines_adjacency) in; // 0: opposite vertex of one face, 1 and 2: the edge, 3: opposite vertex of another face
layout(triangle_strip, max_vertices = 4) out;

uniform mat4 clipFromView;
uniform vec2 viewportSize; // pixels
uniform float widthPixels;

in vec3 viewPosition[];
in float widthFactor[]; // --outline-width-map at each vertex (outline.vert)
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

void main() {
    // The plane through the eye (the view-space origin) and the edge: a point's side of it is the side of the edge's
    // screen line it projects to. The surface folds back at the edge (the exact perspective contour test; for a
    // consistently oriented manifold edge, one face front and one back) when both opposite vertices lie on the same
    // side. Needing no face orientation, this is also right for flipped faces and for both sides of a sheet. A border
    // repeats its opposite vertex and is always kept. cross(a, b - a), not cross(a, b): the same plane, without the
    // cancellation of two long nearly parallel vectors far from the eye.
    vec3 a = viewPosition[1];
    vec3 planeNormal = cross(a, viewPosition[2] - a);
    float sideFirst = sign(dot(planeNormal, viewPosition[0] - a));
    float sideSecond = sign(dot(planeNormal, viewPosition[3] - a));
    bool border = viewPosition[0] == viewPosition[3];
    // Faces on both sides; or both seen edge-on (an edge inside a flat region seen edge-on: the region's own outline
    // is drawn by the edges around it, where one side is off the plane).
    if (!border && (sideFirst * sideSecond < 0.0 || (sideFirst == 0.0 && sideSecond == 0.0))) return;
    float surfaceSide = sideFirst != 0.0 ? sideFirst : sideSecond;

    // The band is widthPixels times the width map at each end, a trapezoid between; nothing where both ends are 0.
    float widthA = widthPixels * widthFactor[1];
    float widthB = widthPixels * widthFactor[2];
    if (widthA <= 0.0 && widthB <= 0.0) return;

    vec4 clipA = gl_in[1].gl_Position;
    vec4 clipB = gl_in[2].gl_Position;
    if (!clipToNearPlane(clipA, clipB)) return;
    vec2 pixelsA = clipA.xy / clipA.w * 0.5 * viewportSize;
    vec2 pixelsB = clipB.xy / clipB.w * 0.5 * viewportSize;
    vec2 along = pixelsB - pixelsA;
    float edgeLength = length(along);
    if (edgeLength <= 1e-4 || surfaceSide == 0.0) {
        // Seen end-on (along the line of sight), or with its faces in the plane through the eye: no outer side to
        // choose, so a square around the point, or a band on both sides.
        vec2 direction = edgeLength > 1e-4 ? along / edgeLength : vec2(1.0, 0.0);
        vec2 across = vec2(-direction.y, direction.x);
        emitCorner(clipA, -direction * widthA - across * widthA, 1);
        emitCorner(clipA, -direction * widthA + across * widthA, 1);
        emitCorner(clipB, direction * widthB - across * widthB, 2);
        emitCorner(clipB, direction * widthB + across * widthB, 2);
        EndPrimitive();
        return;
    }
    vec2 direction = along / edgeLength;
    vec2 across = vec2(-direction.y, direction.x);
    // Toward the faces in pixels: the gradient of the plane's side over the screen. Image-plane coordinates are
    // view x / -z = ndc x / clipFromView[0][0], and y likewise; the scale factors are positive, so only the signs
    // matter. Only the outer side is drawn: the front faces would hide an inner half, and on a thin shell a band
    // lying over the surface z-fights with it.
    vec2 towardFaces = surfaceSide * vec2(planeNormal.x / (clipFromView[0][0] * viewportSize.x),
                                          planeNormal.y / (clipFromView[1][1] * viewportSize.y));
    if (dot(across, towardFaces) > 0.0) across = -across;
    // Square caps as long as the band is wide close the joins at the chain's convex corners.
    emitCorner(clipA, -direction * widthA, 1);
    emitCorner(clipA, -direction * widthA + across * widthA, 1);
    emitCorner(clipB, direction * widthB, 2);
    emitCorner(clipB, direction * widthB + across * widthB, 2);
    EndPrimitive();
}
