// Lander's outline: the model in view and clip space. Alone it draws the model's depth; with the geometry stage, the
// contour and border edges as quads.
layout(location = 0) in vec3 inPosition;

uniform mat4 viewFromModel;
uniform mat4 clipFromView;

out vec3 viewPosition;
out float widthFactor; // --outline-width-map at this vertex (common/width_map.glsl), for the geometry stage

void main() {
    vec4 position = viewFromModel * vec4(inPosition, 1.0);
    viewPosition = position.xyz;
    widthFactor = outlineWidthMapFactor();
    gl_Position = clipFromView * position;
#ifdef MATERIAL_ALPHA
    passMaterialAttributes();
#endif
}
