// The template pass (passes/_template/): one triangle over the viewport.
void main() { emitFullscreenVertex(); }
