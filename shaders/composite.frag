// composite.frag: the paper's Algorithm 3, mixing sprite colour with the
// light texture under the ambient clarity.
// Mirrors core/src/frame/composite.cpp (composite, composite_pixel).
// Uniforms:
//   sampler2D u_color        unit 0: the view's sprites, premultiplied alpha (float)
//   sampler2D u_light        unit 1: the blurred light texture (RGBA8, world-anchored)
//   sampler2D u_light_flat   unit 2: the flat-mode light texture (split view only)
//   ivec2 u_view_origin      world pixel of the view's texel (0, 0)
//   ivec2 u_light_origin     world pixel of u_light's texel (0, 0); the paper's
//                            inverse translation between retraces is this offset
//   ivec2 u_flat_origin      the same for u_light_flat
//   float u_ambient          ambient clarity in [0, 1]
//   int u_dark_unlit         1: texture factor times the light
//   int u_shadow             1: the texture holds shadow (subtract)
//   int u_light_mix          0: Algorithm 3's luminance x light; 1: colour x light (Params::light_mix)
//   float u_exposure         multiplies the light term (Params::exposure)
//   int u_tone_map           0: clamp (the paper); 1: reinhard_knee (composite.hpp's tone_knee)
//   int u_show               0 final, 1 the light texture alone
//   int u_split              >= 0: texels with x >= u_split use u_light_flat (Figure 10)
#version 330 core
uniform sampler2D u_color;
uniform sampler2D u_light;
uniform sampler2D u_light_flat;
uniform ivec2 u_view_origin;
uniform ivec2 u_light_origin;
uniform ivec2 u_flat_origin;
uniform float u_ambient;
uniform int u_dark_unlit;
uniform int u_shadow;
uniform int u_light_mix;
uniform float u_exposure;
uniform int u_tone_map;
uniform int u_show;
uniform int u_split;
out vec4 o_color;

vec3 light_at(sampler2D tex, ivec2 origin, ivec2 world) {
    ivec2 q = world - origin;
    ivec2 size = textureSize(tex, 0);
    if (q.x < 0 || q.y < 0 || q.x >= size.x || q.y >= size.y) return vec3(0.0);
    return texelFetch(tex, q, 0).rgb;
}

const float knee_at = 0.5;  // composite.hpp's tone_knee_at

// composite.cpp's tone_knee: the light scaled down until the sum's highest
// channel lies on the roll-off into the headroom the texture leaves.
vec3 tone_knee(vec3 base, vec3 add) {
    float top = max(base.r, max(base.g, base.b));
    vec3 sum = base + add;
    float peak = max(sum.r, max(sum.g, sum.b));
    float head = max(0.0, 1.0 - top), knee = knee_at * head, span = head - knee, over = peak - top;
    float scale = 1.0;
    if (over > knee) {
        float x = span > 0.0 ? (over - knee) / span : 0.0;
        float target = top + knee + span * x / (1.0 + x);
        for (int k = 0; k < 3; ++k)
            if (add[k] > 0.0) scale = min(scale, (target - base[k]) / add[k]);
    }
    return clamp(base + add * scale, 0.0, 1.0);
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 world = u_view_origin + p;
    bool flat_side = u_split >= 0 && p.x >= u_split;
    vec3 L = flat_side ? light_at(u_light_flat, u_flat_origin, world) : light_at(u_light, u_light_origin, world);
    vec4 c = texelFetch(u_color, p, 0);
    if (u_show == 1) {
        o_color = vec4(L, 1.0);
        return;
    }
    if (c.a <= 0.0) {
        o_color = vec4(0.0);
        return;
    }
    vec3 color = c.rgb / c.a;  // straight colour, as the CPU reference works
    float luminance = color.r * 0.349 + color.g * 0.114 + color.b * 0.537;
    // u_light_mix 1 (not in the paper): the sprite's own colour takes the light.
    vec3 mixed = u_light_mix == 1 ? color : vec3(luminance);
    vec3 lightFactor = mixed * L / (u_ambient * u_ambient + 0.1) * u_exposure;
    vec3 texFactor = color * sqrt(u_ambient);
    bool shadow = u_shadow == 1 && !flat_side;
    if (u_light_mix == 1 && shadow) {
        // A shadow darkens by up to three quarters instead of subtracting.
        o_color = vec4(clamp(texFactor * (vec3(1.0) - 0.75 * L * u_exposure), 0.0, 1.0), c.a);
        return;
    }
    if (u_dark_unlit == 1) texFactor *= shadow ? (vec3(1.0) - L) : L;
    vec3 result = shadow ? clamp(texFactor - lightFactor, 0.0, 1.0)
                  : u_tone_map == 1 ? tone_knee(texFactor, lightFactor)
                  : clamp(texFactor + lightFactor, 0.0, 1.0);
    o_color = vec4(result, c.a);
}
