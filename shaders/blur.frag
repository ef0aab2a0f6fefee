// blur.frag: one pass of the separable box blur of the light texture.
// Mirrors core/src/frame/blur.cpp: box_blur (the mean of the (2r+1)^2 texels
// around each texel, coordinates clamped to the texture's edge), or, with
// u_within_surfaces, core/src/frame/blur_within.cpp: box_blur_within (the texels
// reached by up to r steps along the column, then along the rows, without
// leaving the surface each texel shows nor the texture).
// Uniforms:
//   sampler2D u_source   texture unit 0: the light texture (pass 1) or the
//                        horizontal sums (pass 2)
//   isampler2D u_surface texture unit 1: which surface each pixel shows
//                        (read only with u_within_surfaces); -1 outside it
//   ivec2 u_surface_origin where u_surface's texel (0, 0) lies, in light texels
//   int u_radius         r, the blur radius in texels
//   ivec2 u_direction    (1, 0) for the horizontal pass, (0, 1) for the vertical
//   int u_final_pass     0: write the horizontal sums in 0..255 units (and,
//                        within surfaces, their texel count in alpha) to a
//                        float target (exact: integers below 2^24); 1: divide
//                        the vertical sums by their count, (2r+1)^2 or the
//                        summed counts, with box_blur's integer rounding,
//                        (sum + n/2) / n, and write RGBA8 exactly
//   float u_input_scale  255 for the 8-bit light texture, 1 for the float sums
//   int u_within_surfaces 1: box_blur_within; 0: box_blur
#version 330 core
uniform sampler2D u_source;
uniform isampler2D u_surface;
uniform int u_radius;
uniform ivec2 u_direction;
uniform int u_final_pass;
uniform float u_input_scale;
uniform int u_within_surfaces;
uniform ivec2 u_surface_origin;
out vec4 o_color;

int surface_at(ivec2 q) {
    ivec2 s = q - u_surface_origin;
    if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, textureSize(u_surface, 0)))) return -1;
    return texelFetch(u_surface, s, 0).r;
}

// A texel's sums and count: a light texel counts once, a pass-1 sum its count.
vec4 summand(ivec2 q) {
    vec4 t = texelFetch(u_source, q, 0);
    return u_final_pass == 0 ? vec4(t.rgb * u_input_scale, 1.0) : t;
}

void main() {
    ivec2 size = textureSize(u_source, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 sum = vec4(0.0);
    if (u_within_surfaces == 1) {
        int own = surface_at(p);
        sum = summand(p);
        for (int i = 1; i <= u_radius; ++i) {
            ivec2 q = p - u_direction * i;
            if (any(lessThan(q, ivec2(0))) || surface_at(q) != own) break;
            sum += summand(q);
        }
        for (int i = 1; i <= u_radius; ++i) {
            ivec2 q = p + u_direction * i;
            if (any(greaterThanEqual(q, size)) || surface_at(q) != own) break;
            sum += summand(q);
        }
    } else {
        for (int i = -u_radius; i <= u_radius; ++i) {
            ivec2 q = clamp(p + u_direction * i, ivec2(0), size - 1);
            sum.rgb += texelFetch(u_source, q, 0).rgb * u_input_scale;
        }
        sum.a = float((2 * u_radius + 1) * (2 * u_radius + 1));
    }
    if (u_final_pass == 0) {
        o_color = floor(sum + 0.5);
        return;
    }
    ivec4 s = ivec4(sum + 0.5);
    int n = s.a;
    ivec3 mean = (s.rgb + n / 2) / n;
    o_color = vec4(vec3(mean) / 255.0, 1.0);
}
