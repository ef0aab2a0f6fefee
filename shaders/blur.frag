// blur.frag: one pass of the separable box blur of the light texture.
// Mirrors core/src/blur.cpp (box_blur): the mean of the (2r+1)^2 texels
// around each texel, coordinates clamped to the texture's edge.
// Uniforms:
//   sampler2D u_source   texture unit 0: the light texture (pass 1) or the
//                        horizontal sums (pass 2)
//   int u_radius         r, the blur radius in texels
//   ivec2 u_direction    (1, 0) for the horizontal pass, (0, 1) for the vertical
//   int u_final_pass     0: write the horizontal sums in 0..255 units to a
//                        float target (exact: integers below 2^24); 1: divide
//                        the vertical sums by (2r+1)^2 with box_blur's integer
//                        rounding, (sum + n/2) / n, and write RGBA8 exactly
//   float u_input_scale  255 for the 8-bit light texture, 1 for the float sums
#version 330 core
uniform sampler2D u_source;
uniform int u_radius;
uniform ivec2 u_direction;
uniform int u_final_pass;
uniform float u_input_scale;
out vec4 o_color;
void main() {
    ivec2 size = textureSize(u_source, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 sum = vec3(0.0);
    for (int i = -u_radius; i <= u_radius; ++i) {
        ivec2 q = clamp(p + u_direction * i, ivec2(0), size - 1);
        sum += texelFetch(u_source, q, 0).rgb * u_input_scale;
    }
    if (u_final_pass == 0) {
        o_color = vec4(floor(sum + 0.5), 1.0);
        return;
    }
    int n = (2 * u_radius + 1) * (2 * u_radius + 1);
    ivec3 s = ivec3(sum + 0.5);
    ivec3 mean = (s + n / 2) / n;
    o_color = vec4(vec3(mean) / 255.0, 1.0);
}
