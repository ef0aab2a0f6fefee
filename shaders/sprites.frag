// sprites.frag: samples the atlas texel by texel (nearest) and premultiplies
// in float, blended with ONE, ONE_MINUS_SRC_ALPHA into a float target:
// "over", as core/src/map/placement.cpp (render_sprites) composes sprites.
// Uniforms:
//   sampler2D u_atlas   unit 0: every sprite of the tileset, straight alpha
#version 330 core
uniform sampler2D u_atlas;
in vec2 v_uv;
out vec4 o_color;
void main() {
    vec4 c = texture(u_atlas, v_uv);
    o_color = vec4(c.rgb * c.a, c.a);
}
