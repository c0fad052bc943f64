// Forward shading: transforms to view space (positions arrive relative to the scene's bounding-sphere centre, as in
// the G-buffer). Gouraud lights each vertex here; the CPU face-orientation variant (SHADE_COORDS) passes the
// per-vertex (s, t) the CPU computed through to the shade-map lookup.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
#ifdef SHADE_COORDS
layout(location = SHADE_COORD_LOCATION) in vec2 inShadeCoord;
out vec2 shadeCoord;
#endif

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel; // inverse-transpose of viewFromModel's upper 3x3
uniform mat4 clipFromView;

out vec3 viewPosition;
out vec3 viewNormal;

#ifdef MODEL_GOURAUD
uniform vec3 towardLightView; // unit
out vec3 vertexLight;         // the lighting factor, interpolated; the fragment multiplies the base colour
#endif

void main() {
    vec4 position = viewFromModel * vec4(inPosition, 1.0);
    viewPosition = position.xyz;
    viewNormal = viewNormalFromModel * inNormal;
    gl_Position = clipFromView * position;
#ifdef SHADE_COORDS
    shadeCoord = inShadeCoord;
#endif
    passMaterialAttributes();
#ifdef MODEL_GOURAUD
    // Lit with the vertex normal as stored: a vertex cannot know which side its triangles will be seen from, so
    // faces seen from behind (through holes of open meshes) show the lighting of their front side.
    float normalLength = length(viewNormal);
    vec3 n = normalLength > 0.0 ? viewNormal / normalLength : vec3(0.0, 0.0, 1.0);
    vertexLight = diffuseLighting(n, towardLightView, ambientLight);
#endif
}
