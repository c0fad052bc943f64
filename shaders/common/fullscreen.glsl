// One triangle covering the viewport, generated from gl_VertexID (no vertex buffer). Fragment passes then read
// their inputs with texelFetch(ivec2(gl_FragCoord.xy)), texel-exact, never filtered.
#ifdef INKGRAPH_VERTEX_STAGE
void emitFullscreenVertex() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
#endif
