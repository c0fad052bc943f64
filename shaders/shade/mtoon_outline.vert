// MToon's outline (docs/mtoon.md "Outline"): the mesh again, pushed out along its position-welded normals by the
// material's outline width, drawn with front faces culled so only the rim of the pushed shell shows around the surface.
// worldCoordinates: the width in model units; screenCoordinates: a share of the screen height, moved along the
// normal's direction on screen and scaled by clip w so the perspective divide keeps it. shade.frag colours it
// (MTOON_OUTLINE).
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inHullNormal; // unit, position-welded (GpuScene::hullNormals), so the shell stays closed

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel;
uniform mat4 clipFromView;
uniform vec2 viewportSize; // pixels

uniform int mtoonOutlineMode; // 1 worldCoordinates, 2 screenCoordinates (0: the mesh is not drawn)
uniform float mtoonOutlineWidthFactor;
uniform int mtoonOutlineWidthMultiplyTextured;
uniform int mtoonOutlineWidthMultiplySet;
uniform mat3 mtoonOutlineWidthMultiplyTransform;
layout(binding = 4) uniform sampler2D mtoonOutlineWidthMultiplyTexture; // linear data: its green channel

out vec3 viewPosition;
out vec3 viewNormal;

void main() {
    passMaterialAttributes();
    float width = mtoonOutlineWidthFactor;
    if (mtoonOutlineWidthMultiplyTextured != 0) {
        vec2 uv = mtoonOutlineWidthMultiplySet == 1 ? inTexcoord1 : inTexcoord0; // common/material.glsl
        width *= textureLod(mtoonOutlineWidthMultiplyTexture, (mtoonOutlineWidthMultiplyTransform * vec3(uv, 1.0)).xy,
                            0.0).g;
    }
    vec3 position = inPosition;
    if (mtoonOutlineMode == 1) position += width * inHullNormal;
    vec4 view = viewFromModel * vec4(position, 1.0);
    viewPosition = view.xyz;
    viewNormal = viewNormalFromModel * inHullNormal;
    vec4 clip = clipFromView * view;
    if (mtoonOutlineMode == 2) {
        // The normal's direction in pixels, then width x height pixels along it, back in NDC (2 / viewport per pixel).
        vec2 normalPixels = (clipFromView * vec4(viewNormal, 0.0)).xy * viewportSize;
        float normalLength = length(normalPixels);
        if (normalLength > 1e-6 * max(viewportSize.x, viewportSize.y)) {
            vec2 offsetPixels = normalPixels / normalLength * width * viewportSize.y;
            clip.xy += offsetPixels * (2.0 / viewportSize) * clip.w;
        }
    }
    gl_Position = clip;
}
