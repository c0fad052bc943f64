// Object-space edges: the model in clip space. Drawn as triangles it gives the pass's depth; drawn as GL_LINES
// through an index list of vertex pairs on the same positions, the chosen edges (common/line_mask.frag writes 255).
layout(location = 0) in vec3 inPosition;

uniform mat4 viewFromModel;
uniform mat4 clipFromView;
out vec3 viewPosition; // edges.frag's --strokes points

void main() {
    vec4 view = viewFromModel * vec4(inPosition, 1.0);
    viewPosition = view.xyz;
    gl_Position = clipFromView * view;
#ifdef MATERIAL_ALPHA
    passMaterialAttributes();
#endif
}
