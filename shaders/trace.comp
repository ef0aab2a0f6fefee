#version 430
// Paper Algorithm 2 on the GPU: one invocation per ray, from the light's
// centre to its target, drawing falloff(d) until the first obstacle pixel
// (Mode light), or on past it recording what is reached (Mode shadow), or
// ignoring obstacles (Mode flat). The CPU reference is core's trace_light
// (light_trace.cpp): the same Bresenham decisions, so the same pixels. Rays
// that cross write the same value (it depends on the pixel only), so the
// order of writes does not matter.
layout(local_size_x = 64) in;

layout(binding = 0) uniform usampler2D obstacles;  // r8ui: texel (x, y) is world (x, y) + obstacle_origin
layout(r8ui, binding = 0) uniform writeonly uimage2D lit;      // the clip: texel (0, 0) is world clip.xy
layout(r8ui, binding = 1) uniform writeonly uimage2D reached;
layout(std430, binding = 0) readonly buffer Targets { ivec2 targets[]; };  // offsets from the centre
layout(std430, binding = 1) readonly buffer Falloff { uint falloff[]; };   // by distance max(|dx|, |dy|)

uniform ivec2 centre;
uniform ivec4 clip;  // x, y, w, h
uniform ivec2 obstacle_origin;
uniform ivec2 obstacle_size;
uniform int ray_count;
uniform int mode;  // 0 light, 1 shadow, 2 flat

bool blocked(ivec2 p) {
    ivec2 q = p - obstacle_origin;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, obstacle_size))) return false;  // none outside the map
    return texelFetch(obstacles, q, 0).r != 0u;
}

void main() {
    int id = int(gl_GlobalInvocationID.x);
    if (id >= ray_count) return;
    ivec2 t = targets[id];
    ivec2 diagonal = ivec2(sign(t.x), sign(t.y));
    int longest = abs(t.x), shortest = abs(t.y);
    ivec2 straight = ivec2(diagonal.x, 0);
    if (!(longest > shortest)) {
        longest = abs(t.y);
        shortest = abs(t.x);
        straight = ivec2(0, diagonal.y);
    }
    int numerator = longest >> 1;
    ivec2 p = centre;
    bool stopped = false;
    for (int i = 0; i <= longest; ++i) {
        if (mode != 2 && !stopped && blocked(p)) {
            if (mode == 0) return;
            stopped = true;  // shadow: this pixel and the rest are reached, not lit
        }
        ivec2 l = p - clip.xy;
        if (all(greaterThanEqual(l, ivec2(0))) && all(lessThan(l, clip.zw))) {
            if (!stopped) imageStore(lit, l, uvec4(falloff[i]));
            if (mode == 1) imageStore(reached, l, uvec4(1u));
        }
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            p += diagonal;
        } else {
            p += straight;
        }
    }
}
