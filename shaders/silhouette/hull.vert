// Inflated hull: the model pushed out along its hull normals. The width comes from HULL_SCREEN_WIDTH (a constant
// number of pixels on screen: the offset is scaled by clip w, so it survives the perspective divide unchanged),
// HULL_OBJECT_WIDTH (model units), or HULL_MATERIAL_WIDTH (each material's MToon outline, docs/mtoon.md: its mode
// picks model units or a share of the screen height, times its width texture's green channel; the shade pass draws
// these shells as MToon's outlines, shaders/shade/shade.frag with MTOON_OUTLINE). With none, the model itself (the
// silhouette pass's depth draw).
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

#ifdef HULL_MATERIAL_WIDTH
uniform int mtoonOutlineMode; // 1 worldCoordinates, 2 screenCoordinates (0: the mesh is not drawn)
uniform float mtoonOutlineWidthFactor;
uniform int mtoonOutlineWidthMultiplyTextured;
uniform int mtoonOutlineWidthMultiplySet;
uniform mat3 mtoonOutlineWidthMultiplyTransform;
layout(binding = 4) uniform sampler2D mtoonOutlineWidthMultiplyTexture; // linear data: its green channel

out vec3 viewPosition; // for shade.frag, which lights the outline
out vec3 viewNormal;
#endif

// Moves `clip` by `pixels` along the normal's direction on screen. A normal along the line of sight has no screen
// direction (normalize() would give NaN): the vertex stays put.
vec4 pushedOnScreen(vec4 clip, vec3 viewDirection, float pixels) {
    // The normal's screen direction in pixels: clip xy of the direction, scaled by the viewport so a non-square
    // frame does not bend it (NDC to pixels also halves, which a direction does not care about).
    vec2 normalPixels = (clipFromView * vec4(viewDirection, 0.0)).xy * viewportSize;
    float normalLength = length(normalPixels);
    if (normalLength > 1e-6 * max(viewportSize.x, viewportSize.y))
        clip.xy += (normalPixels / normalLength) * (2.0 * pixels / viewportSize) * clip.w;
    return clip;
}

void main() {
    vec3 position = inPosition;
    float screenPixels = 0.0;
#ifdef HULL_OBJECT_WIDTH
    position += objectWidth * inHullNormal;
#endif
#ifdef HULL_SCREEN_WIDTH
    screenPixels = widthPixels;
#endif
#ifdef HULL_MATERIAL_WIDTH
    passMaterialAttributes();
    float width = mtoonOutlineWidthFactor;
    if (mtoonOutlineWidthMultiplyTextured != 0)
        width *= textureLod(mtoonOutlineWidthMultiplyTexture,
                            materialVertexTexcoord(mtoonOutlineWidthMultiplySet, mtoonOutlineWidthMultiplyTransform),
                            0.0)
                     .g;
    if (mtoonOutlineMode == 1) position += width * inHullNormal;
    if (mtoonOutlineMode == 2) screenPixels = width * viewportSize.y; // a share of the picture's height
#elif defined(MATERIAL_ALPHA)
    passMaterialAttributes();
#endif
    vec4 view = viewFromModel * vec4(position, 1.0);
    vec4 clip = clipFromView * view;
    if (screenPixels > 0.0) clip = pushedOnScreen(clip, viewNormalFromModel * inHullNormal, screenPixels);
#ifdef HULL_MATERIAL_WIDTH
    viewPosition = view.xyz;
    viewNormal = viewNormalFromModel * inHullNormal;
#endif
    gl_Position = clip;
}
