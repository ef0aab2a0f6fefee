// sprites.frag: samples the premultiplied-alpha atlas texel by texel
// (nearest), blended with ONE, ONE_MINUS_SRC_ALPHA: "over", as
// core/src/map.cpp (render_sprites) composes sprites.
// Uniforms:
//   sampler2D u_atlas   unit 0: every sprite of the tileset, premultiplied
#version 330 core
uniform sampler2D u_atlas;
in vec2 v_uv;
out vec4 o_color;
void main() { o_color = texture(u_atlas, v_uv); }
