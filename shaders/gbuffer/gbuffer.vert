// G-buffer: transforms to view space; positions arrive relative to the scene's bounding-sphere centre.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

uniform mat4 viewFromModel;
uniform mat3 viewNormalFromModel; // inverse-transpose of viewFromModel's upper 3x3
uniform mat4 clipFromView;

// A block, so gbuffer.geom (the barycentric field's draw) can pass it on; unnamed, so the members are plain names here.
out SurfaceVarying {
    vec3 viewPosition;
    vec3 viewNormal;
};
// The pass draws twice when more fields are live than GL's 8 draw buffers, with two programs: invariance makes both
// rasterise exactly the same fragments.
invariant gl_Position;

void main() {
    vec4 position = viewFromModel * vec4(inPosition, 1.0);
    viewPosition = position.xyz;
    viewNormal = viewNormalFromModel * inNormal;
    gl_Position = clipFromView * position;
    passMaterialAttributes();
}
