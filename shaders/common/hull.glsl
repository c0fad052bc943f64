// The inflated hull's push in screen space, shared by the silhouette's hull (silhouette/hull.vert) and MToon's
// outline shells (mtoon/outline.vert), so a shell of N pixels is the silhouette's N pixels.
#ifdef INKGRAPH_VERTEX_STAGE
// Moves `clip` by `pixels` along the normal's direction on screen. A normal along the line of sight has no screen
// direction (normalize() would give NaN): the vertex stays put.
vec4 pushedOnScreen(vec4 clip, vec3 viewDirection, float pixels, mat4 clipFromView, vec2 viewportSize) {
    // The normal's screen direction in pixels: clip xy of the direction, scaled by the viewport so a non-square
    // frame does not bend it (NDC to pixels also halves, which a direction does not care about).
    vec2 normalPixels = (clipFromView * vec4(viewDirection, 0.0)).xy * viewportSize;
    float normalLength = length(normalPixels);
    if (normalLength > 1e-6 * max(viewportSize.x, viewportSize.y))
        clip.xy += (normalPixels / normalLength) * (2.0 * pixels / viewportSize) * clip.w;
    return clip;
}
#endif
