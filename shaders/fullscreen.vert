// fullscreen.vert: a triangle covering the target; passes nothing.
// Used by blur.frag and composite.frag, which address texels with
// gl_FragCoord and texelFetch so that every fragment maps to exactly one
// texel, as the CPU references in core/ do.
#version 330 core
void main() {
    vec2 p = vec2((gl_VertexID == 1) ? 3.0 : -1.0, (gl_VertexID == 2) ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
