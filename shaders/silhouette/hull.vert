// Inflated hull: the model pushed out along its hull normals. The width comes from HULL_SCREEN_WIDTH (a constant
// number of pixels on screen: the offset is scaled by clip w, so it survives the perspective divide unchanged,
// common/hull.glsl) or HULL_OBJECT_WIDTH (model units). With neither, the model itself (the silhouette pass's depth
// draw). MToon's outline shells are the mtoon-outline pass's own (mtoon/outline.vert).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inHullNormal; // unit, position-welded (or the raw normals when the test hook says so)

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel; // inverse-transpose of viewFromModel's upper 3x3
uniform mat4 clipFromView;
uniform vec2 viewportSize;        // pixels
uniform float widthPixels;
uniform float objectWidth;        // model units

// Unmoved vertices must land on the model's depth to the bit, whichever program drew that depth (this one without a
// width define, or the G-buffer's, gbuffer.vert): the strictly-nearer test then leaves them out.
invariant gl_Position;

void main() {
    vec3 position = inPosition;
    float screenPixels = 0.0;
    // Scaled per vertex by --outline-width-map (common/width_map.glsl); 0 leaves the vertex on the surface, where
    // the strictly-nearer test leaves it out.
#ifdef HULL_OBJECT_WIDTH
    position += objectWidth * outlineWidthMapFactor() * inHullNormal;
#endif
#ifdef HULL_SCREEN_WIDTH
    screenPixels = widthPixels * outlineWidthMapFactor();
#endif
#ifdef MATERIAL_ALPHA
    passMaterialAttributes();
#endif
    vec4 view = viewFromModel * vec4(position, 1.0);
    vec4 clip = clipFromView * view;
    if (screenPixels > 0.0)
        clip = pushedOnScreen(clip, viewNormalFromModel * inHullNormal, screenPixels, clipFromView, viewportSize);
    gl_Position = clip;
}
