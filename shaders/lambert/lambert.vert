void main() { emitFullscreenVertex(); }
