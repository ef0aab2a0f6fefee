// sprites.vert: the map's sprites as instanced quads from one atlas, drawn
// back to front into the view's colour target. Mirrors
// core/src/map/placement.cpp (render_sprites).
// Attributes (per instance):
//   vec4 a_world   x, y, w, h of the sprite in world pixels
//   vec4 a_atlas   x, y, w, h of the sprite in the atlas, texels
// Uniforms:
//   vec4 u_view    x, y, w, h of the view in world pixels
//   vec2 u_atlas_size
#version 330 core
layout(location = 0) in vec4 a_world;
layout(location = 1) in vec4 a_atlas;
uniform vec4 u_view;
uniform vec2 u_atlas_size;
out vec2 v_uv;
void main() {
    // Two triangles: (0,0) (1,0) (0,1) and (1,0) (1,1) (0,1).
    vec2 corner = vec2((gl_VertexID == 1 || gl_VertexID == 3 || gl_VertexID == 4) ? 1.0 : 0.0,
                       (gl_VertexID == 2 || gl_VertexID == 4 || gl_VertexID == 5) ? 1.0 : 0.0);
    vec2 world = a_world.xy + corner * a_world.zw;
    // Texel row 0 of the target is the view's top world row.
    vec2 ndc = (world - u_view.xy) / u_view.zw * 2.0 - 1.0;
    gl_Position = vec4(ndc, 0.0, 1.0);
    v_uv = (a_atlas.xy + corner * a_atlas.zw) / u_atlas_size;
}
