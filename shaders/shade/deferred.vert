// Deferred shading (ShadePass in deferred mode): one triangle over the viewport; shade.frag with SHADE_DEFERRED reads
// the pixel's surface from the G-buffer.
void main() { emitFullscreenVertex(); }
