// One triangle that covers the viewport, from gl_VertexID alone (no vertex buffer). At window
// depth 0.5, or with SG_FULLSCREEN_FAR at the far plane (1): tested GREATER against a depth
// buffer the scene drew, it shades only the pixels that hold geometry, and a CPU rasteriser's
// early depth test skips the blocks that hold none before they run any shader.
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
#ifdef SG_FULLSCREEN_FAR
    gl_Position = vec4(p * 2.0 - 1.0, 1.0, 1.0);
#else
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
#endif
}
