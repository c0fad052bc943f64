// The bare draw of BM_GBufferVsBareDraw: a constant into each of TARGET_COUNT colour targets, so only rasterisation,
// the depth test and the stores are left to compare the G-buffer with.
layout(location = 0) out vec4 outTarget[TARGET_COUNT];

void main() {
    for (int target = 0; target < TARGET_COUNT; ++target) outTarget[target] = vec4(0.5, 0.25, 0.75, 1.0);
}
