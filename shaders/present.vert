// present.vert: the composited view drawn onto the window with pan and zoom.
// Uniforms:
//   vec4 u_rect   x0, y0, x1, y1 of the view on the window, in NDC
#version 330 core
uniform vec4 u_rect;
out vec2 v_uv;
void main() {
    // Two triangles: (0,0) (1,0) (0,1) and (1,0) (1,1) (0,1).
    vec2 corner = vec2((gl_VertexID == 1 || gl_VertexID == 3 || gl_VertexID == 4) ? 1.0 : 0.0,
                       (gl_VertexID == 2 || gl_VertexID == 4 || gl_VertexID == 5) ? 1.0 : 0.0);
    gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), 0.0, 1.0);
    v_uv = corner;
}
