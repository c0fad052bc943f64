// Line mask: 1.0 in the R8 target stores 255 (the depth draw writes no colour at all). With MATERIAL_ALPHA (and the
// common/material.glsl snippet) what the material cuts out is not drawn, as in the G-buffer.
layout(location = 0) out float outLine;

void main() {
#ifdef MATERIAL_ALPHA
    if (materialCutsOut(materialBaseColor().a)) discard;
#endif
    outLine = 1.0;
}
