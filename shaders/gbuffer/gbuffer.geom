// G-buffer, in the draw that writes the barycentric field only: passes each triangle on unchanged (its clip positions
// are the vertex stage's invariant ones, so it rasterises the same fragments as the draw without this stage) and
// gives its corners the unit weights (1,0,0), (0,1,0), (0,0,1) in index order. Interpolated perspective-correctly,
// they are the barycentric weights of the point seen at each fragment.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in SurfaceVarying {
    vec3 viewPosition;
    vec3 viewNormal;
} surfaceIn[];
out SurfaceVarying {
    vec3 viewPosition;
    vec3 viewNormal;
} surfaceOut;
// common/material.glsl's attributes, passed on so the fragment stage cuts out what the material cuts out.
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
out vec3 barycentricWeights;

invariant gl_Position;

void main() {
    for (int corner = 0; corner < 3; ++corner) {
        gl_Position = gl_in[corner].gl_Position;
        surfaceOut.viewPosition = surfaceIn[corner].viewPosition;
        surfaceOut.viewNormal = surfaceIn[corner].viewNormal;
        materialOut.texcoord0 = materialIn[corner].texcoord0;
        materialOut.texcoord1 = materialIn[corner].texcoord1;
        materialOut.vertexColor = materialIn[corner].vertexColor;
        barycentricWeights = vec3(corner == 0, corner == 1, corner == 2);
        // The triangle's number in the draw, which the triangleId field reads, as it is without this stage.
        gl_PrimitiveID = gl_PrimitiveIDIn;
        EmitVertex();
    }
    EndPrimitive();
}
