// present.frag: the final view plus the editor's overlays (obstacle map,
// opacity maps, Δy bands), over the window's background. Display only: no
// core/ counterpart (the CLI writes the final image itself).
// Uniforms:
//   sampler2D u_final     unit 0: composite.frag's output (straight alpha)
//   sampler2D u_overlay   unit 1: overlay colours, premultiplied, world-anchored
//   vec2 u_view_origin, u_view_size      the view in world pixels
//   vec2 u_overlay_origin, u_overlay_size the overlay texture in world pixels
//   float u_overlay_opacity
//   vec3 u_background
#version 330 core
uniform sampler2D u_final;
uniform sampler2D u_overlay;
uniform vec2 u_view_origin;
uniform vec2 u_view_size;
uniform vec2 u_overlay_origin;
uniform vec2 u_overlay_size;
uniform float u_overlay_opacity;
uniform vec3 u_background;
in vec2 v_uv;
out vec4 o_color;
void main() {
    // v_uv.y = 0 at the bottom of the window's quad, the view's last row.
    vec2 uv = vec2(v_uv.x, 1.0 - v_uv.y);
    vec4 c = texture(u_final, uv);
    vec3 rgb = mix(u_background, c.rgb, c.a);
    vec2 world = u_view_origin + uv * u_view_size;
    vec2 ouv = (world - u_overlay_origin) / u_overlay_size;
    if (all(greaterThanEqual(ouv, vec2(0.0))) && all(lessThan(ouv, vec2(1.0)))) {
        vec4 o = texture(u_overlay, ouv) * u_overlay_opacity;
        rgb = o.rgb + rgb * (1.0 - o.a);
    }
    o_color = vec4(rgb, 1.0);
}
