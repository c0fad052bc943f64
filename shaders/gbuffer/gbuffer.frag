// G-buffer: float32 view-space quantities. Only the live outputs are declared (OUT_* and LOC_* defines come from
// GBufferPass), so nothing is computed or stored for a buffer no pass reads.
in SurfaceVarying {
    vec3 viewPosition;
    vec3 viewNormal;
};

// common/material.glsl: the base colour (OUT_BASECOLOR) and, with MATERIAL_ALPHA, the cut-out that decides coverage.
#ifdef OUT_MATERIAL_ID
uniform uint materialId; // GpuScene::DrawMesh::materialId, one per draw
#endif
#ifdef OUT_OBJECT_ID
uniform uint objectIndex; // GpuScene::DrawMesh::objectIndex, one per draw
#endif
#ifdef OUT_MESH_ID
uniform uint meshNumber; // GpuScene::DrawMesh::meshNumber, one per draw
#endif
#if defined(OUT_TRIANGLE_ID) || defined(OUT_BARYCENTRIC)
uniform uint firstTriangle; // the global index of the mesh's first triangle (GpuScene::TriangleIdMap)
// Where the loader dropped some of the mesh's triangles or swapped some triangles' corners, from
// fileTriangle[fileTrianglesAt] on each drawn triangle's index among the file's, its top bit set where its 2nd and
// 3rd corners are the file's 3rd and 2nd; 0xffffffff where it did neither.
uniform uint fileTrianglesAt;
layout(std430, binding = FILE_TRIANGLES_BINDING) readonly buffer FileTriangles { uint fileTriangle[]; };

// The drawn triangle's entry: its index among the mesh's file triangles, and the swapped-corners bit.
uint fileTriangleEntry() {
    uint drawn = uint(gl_PrimitiveID); // the draw's triangles in index order
    return fileTrianglesAt == 0xffffffffu ? drawn : fileTriangle[fileTrianglesAt + drawn];
}

// The drawn triangle's id: its global index (scene/MeshLabels.h TriangleNumbering) + 1. Exact in float32 below 2^24
// triangles (the renderer warns above).
float triangleId() {
    return float(firstTriangle + (fileTriangleEntry() & 0x7fffffffu) + 1u);
}
#endif
#ifdef OUT_BARYCENTRIC
in vec3 barycentricWeights; // gbuffer.geom: each corner's unit weight, interpolated perspective-correctly
#endif
#ifdef OUT_RADIAL
// (0.5 width clipFromView[0][0], 0.5 height clipFromView[1][1]): the focal lengths in pixels of the perspective
// projection (GBufferPass checks its form).
uniform vec2 focalPixels;
uniform float radialLengthScale; // 1 / the length unit of the radial field (the bounding radius)
#endif

#ifdef OUT_NORMAL
layout(location = LOC_NORMAL) out vec4 outNormal;
#endif
#ifdef OUT_VIEW
layout(location = LOC_VIEW) out vec4 outView;
#endif
#ifdef OUT_WVEC
layout(location = LOC_WVEC) out vec4 outWVec;
#endif
#ifdef OUT_NDOTV
layout(location = LOC_NDOTV) out float outNDotV;
#endif
#ifdef OUT_DEPTH
layout(location = LOC_DEPTH) out float outDepth;
#endif
#ifdef OUT_COVERAGE
layout(location = LOC_COVERAGE) out float outCoverage;
#endif
#ifdef OUT_BASECOLOR
layout(location = LOC_BASECOLOR) out vec4 outBaseColor;
#endif
#ifdef OUT_MATERIAL_ID
layout(location = LOC_MATERIAL_ID) out float outMaterialId;
#endif
#ifdef OUT_OBJECT_ID
layout(location = LOC_OBJECT_ID) out float outObjectId;
#endif
#ifdef OUT_MESH_ID
layout(location = LOC_MESH_ID) out float outMeshId;
#endif
#ifdef OUT_TRIANGLE_ID
layout(location = LOC_TRIANGLE_ID) out float outTriangleId;
#endif
#ifdef OUT_BARYCENTRIC
layout(location = LOC_BARYCENTRIC) out vec4 outBarycentric;
#endif
#ifdef OUT_RADIAL
layout(location = LOC_RADIAL) out vec4 outRadial;

// J d: how far (in pixels, x right, y down) the image of p = viewPosition moves when it moves by d in view space.
// Differentiates pixel = viewport/2 * (clip.xy / clip.w + 1) for a perspective projection, whose w row is
// (0, 0, -1, 0) and x and y rows (f_x, 0, c_x, 0) and (0, f_y, c_y, 0): clip.w = -p.z, and the off-axis terms c cancel
// in (clipStep.x clip.w - clip.x clipStep.w) / clip.w^2 = f_x (p.x d.z - d.x p.z) / p.z^2. The general quotient with
// two matrix products cost the G-buffer a tenth of its time on llvmpipe, where the bunny's triangles cover a few
// pixels each and every operation runs for whole 4x4 blocks.
vec2 imageDisplacement(vec3 d) {
    vec3 p = viewPosition;
    return vec2(focalPixels.x, -focalPixels.y) * (p.xy * d.z - d.xy * p.z) / (p.z * p.z);
}
#endif

void main() {
#if defined(OUT_BASECOLOR) || defined(MATERIAL_ALPHA)
    vec4 surfaceColor = materialBaseColor();
#endif
#ifdef MATERIAL_ALPHA
    // Cut out before anything is written: coverage, depth and every field follow the mask's edge.
    if (materialCutsOut(surfaceColor.a)) discard;
#endif
    // Interpolated normals are renormalised per fragment; seen from behind (open meshes, holes) the surface is
    // two-sided, so the normal turns toward the viewer's side.
    float normalLength = length(viewNormal);
    vec3 n = normalLength > 0.0 ? viewNormal / normalLength : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) n = -n;
    // Unit vector from the surface to the eye (the eye is the view-space origin).
    float distanceToEye = length(viewPosition);
    vec3 v = distanceToEye > 0.0 ? -viewPosition / distanceToEye : vec3(0.0, 0.0, 1.0);
    float nDotV = dot(n, v);
#ifdef OUT_NORMAL
    outNormal = vec4(n, 1.0);
#endif
#ifdef OUT_VIEW
    outView = vec4(v, 1.0);
#endif
#ifdef OUT_WVEC
    // Unnormalised: |w| = sin(theta). Never normalised here, so w -> 0 (frontal surfaces) stays finite.
    outWVec = vec4(v - nDotV * n, 1.0);
#endif
#ifdef OUT_NDOTV
    outNDotV = nDotV;
#endif
#ifdef OUT_DEPTH
    outDepth = -viewPosition.z;
#endif
#ifdef OUT_COVERAGE
    outCoverage = 1.0;
#endif
#ifdef OUT_BASECOLOR
    outBaseColor = vec4(encodeSrgb(surfaceColor.rgb), 1.0);
#endif
#ifdef OUT_MATERIAL_ID
    // + 1 so the cleared background (0) is no material; exact in float32 below 2^24 materials.
    outMaterialId = float(materialId + 1u);
#endif
#ifdef OUT_OBJECT_ID
    // Likewise: 0 is the background, objects count from 1.
    outObjectId = float(objectIndex + 1u);
#endif
#ifdef OUT_MESH_ID
    outMeshId = float(meshNumber + 1u);
#endif
#ifdef OUT_TRIANGLE_ID
    outTriangleId = triangleId();
#endif
#ifdef OUT_BARYCENTRIC
    // The sample lies inside its triangle, so its weights are in [0, 1] and sum to 1: clamping and renormalising
    // removes only the rasteriser's rounding (llvmpipe's interpolation leaves about 3e-4).
    vec3 weights = clamp(barycentricWeights, 0.0, 1.0);
    // In the file's corner order: the loader swapped some triangles' last two corners to turn their front outward.
    if ((fileTriangleEntry() & 0x80000000u) != 0u) weights = weights.xzy;
    // Alpha: the id (global index + 1) of the triangle these weights are of, from this same draw, so a pixel's weights
    // and their triangle always go together (the triangleId field comes from another draw, which where two surfaces
    // lie within depth rounding of each other can keep the other one).
    outBarycentric = vec4(weights / max(weights.x + weights.y + weights.z, 1e-30), triangleId());
#endif
#ifdef OUT_RADIAL
    // DeCarlo's unnormalised view vector v = c - p (c is the view-space origin). J v = 0 (moving along the eye ray
    // does not move the pixel), so J w = -(n.v) J n, which avoids the cancellation of J v - (n.v) J n.
    // Lengths are in units of the bounding radius L, as if the model were scaled by 1/L: n.v and |w|^2 shrink by L
    // and L^2, while J w (pixels) does not change, since J of the scaled world is L J. The values are then O(1) at
    // any model scale, so float16 holds them and a model at scale 1e-4 gives the numbers it gives at scale 1.
    vec3 towardEye = -viewPosition;
    float worldNDotV = dot(n, towardEye);
    float radialNDotV = worldNDotV * radialLengthScale;
    vec3 w = (towardEye - worldNDotV * n) * radialLengthScale;
    outRadial = vec4(radialNDotV, -worldNDotV * imageDisplacement(n), dot(w, w));
#endif
}
