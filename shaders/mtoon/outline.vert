// MToon's outline shell (the mtoon-outline pass, docs/mtoon.md): the mesh pushed out along its hull normals by its
// material's outline width, in model units (worldCoordinates) or as a share of the picture's height
// (screenCoordinates: the offset is scaled by clip w, so it survives the perspective divide unchanged), times the
// width texture's green channel and --outline-width-map (common/width_map.glsl).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inHullNormal; // unit, position-welded

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel; // inverse-transpose of viewFromModel's upper 3x3
uniform mat4 clipFromView;
uniform vec2 viewportSize;        // pixels

uniform int mtoonOutlineMode; // 1 worldCoordinates, 2 screenCoordinates (0: the mesh is not drawn)
uniform float mtoonOutlineWidthFactor;
uniform int mtoonOutlineWidthMultiplyTextured;
uniform int mtoonOutlineWidthMultiplySet;
uniform mat3 mtoonOutlineWidthMultiplyTransform;
layout(binding = 4) uniform sampler2D mtoonOutlineWidthMultiplyTexture; // linear data: its green channel

// Invariant, as the silhouette's hull (silhouette/hull.vert): a vertex's position does not depend on how the compiler
// schedules the rest of the program.
invariant gl_Position;

out vec3 viewPosition; // for outline.frag, which lights the outline
out vec3 viewNormal;

void main() {
    vec3 position = inPosition;
    float screenPixels = 0.0;
    passMaterialAttributes();
    // The material's width texture (its green channel) and --outline-width-map, through the one function
    // (common/width_map.glsl), multiplied.
    float width = mtoonOutlineWidthFactor * outlineWidthMapFactor();
    if (mtoonOutlineWidthMultiplyTextured != 0)
        width *= widthMapFactor(2, 1, mtoonOutlineWidthMultiplyTexture,
                                materialVertexTexcoord(mtoonOutlineWidthMultiplySet, mtoonOutlineWidthMultiplyTransform));
    if (mtoonOutlineMode == 1) position += width * inHullNormal;
    if (mtoonOutlineMode == 2) screenPixels = width * viewportSize.y; // a share of the picture's height
    vec4 view = viewFromModel * vec4(position, 1.0);
    vec4 clip = clipFromView * view;
    if (screenPixels > 0.0)
        clip = pushedOnScreen(clip, viewNormalFromModel * inHullNormal, screenPixels, clipFromView, viewportSize);
    viewPosition = view.xyz;
    viewNormal = viewNormalFromModel * inHullNormal;
    gl_Position = clip;
}
