#version 430
// Beyond the paper: the start of tracing a frame's lights against solids
// with height on the GPU, one invocation per pixel of every light's layer
// (its clip), run before both passes, which then only write what they
// light. Every pixel starts unlit (0), but, with the sprite pass
// (`sprite_points`), a sprite pixel of the light's area whose ground point
// no ray of that pass walks (off the map): it takes its own line's answer.
// The CPU reference is core's start of light_sprite_points_by_rays
// (start_sprite_points): a point's own line from the light's centre to its
// ground pixel (all but the last own_steps steps) is lit unless a span there
// holds the segment's height. The ground pass leaves the area's sprite
// pixels to the sprite pass (trace_solids.comp's skip_sprites), as the CPU's
// start unlights them.
layout(local_size_x = 8, local_size_y = 8) in;

layout(r8ui, binding = 0) uniform writeonly uimage2DArray lit;  // per light its clip: texel (0, 0) is world clip.xy
layout(std430, binding = 1) readonly buffer Falloff { uint falloff[]; };  // by distance max(|dx|, |dy|)
layout(std430, binding = 2) readonly buffer Spans { vec4 spans[]; };     // (low, high) of the lower span, then the upper's
layout(std430, binding = 7) readonly buffer SurfaceHeight { float surface_height[]; };  // per pixel of surface_origin, surface_size
layout(std430, binding = 8) readonly buffer SurfaceSprite { uint surface_sprite[]; };   // a bit per pixel: it shows an overlay
struct Light {  // as trace_solids.comp's
    ivec2 centre;
    ivec2 extent;
    ivec2 ground_rays;
    ivec2 sprite_rays;  // the first of its targets (the area grown by the tallest point's rows), and their count
    ivec4 clip;
    ivec4 area;         // the light's area within the clip: only its points are lit
    double height;
    int layer;
    int unused;
};
layout(std430, binding = 6) readonly buffer Lights { Light lights[]; };

uniform ivec2 span_origin;  // the occluder map's rect
uniform ivec2 span_size;
uniform ivec2 surface_origin;
uniform ivec2 surface_size;
uniform int tallest;  // the sprite pass's rays reach this many rows past the area
uniform bool sprite_points;  // the sprite pass follows

const int own_steps = 2;

bool inside(ivec2 q, ivec2 origin, ivec2 size) {
    return all(greaterThanEqual(q, origin)) && all(lessThan(q, origin + size));
}

// rows_above: h rounded half away from zero.
int rows_above(float h) {
    double a = abs(double(h));
    int r = int(a);
    r += a - double(r) >= 0.5 ? 1 : 0;
    return h < 0.0 ? -r : r;
}

bool holds(vec4 both, double z) {
    return (z >= double(both.x) && z < double(both.y)) || (z >= double(both.z) && z < double(both.w));
}

// own_line_lit: the Bresenham line from the centre to (gx, gy).
bool own_line_lit(ivec2 c, ivec2 g, double h, double H) {
    ivec2 t = g - c;
    ivec2 diagonal = ivec2(sign(t.x), sign(t.y));
    int longest = abs(t.x), shortest = abs(t.y);
    ivec2 straight = ivec2(diagonal.x, 0);
    if (!(longest > shortest)) {
        longest = abs(t.y);
        shortest = abs(t.x);
        straight = ivec2(0, diagonal.y);
    }
    int steps = longest;
    int numerator = longest >> 1;
    ivec2 p = c;
    for (int i = 0; i <= steps - own_steps; ++i) {
        ivec2 q = p - span_origin;
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, span_size))) {
            precise double z = H + (h - H) * double(i) / double(steps);
            if (holds(spans[q.y * span_size.x + q.x], z)) return false;
        }
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            p += diagonal;
        } else {
            p += straight;
        }
    }
    return true;
}

void main() {
    Light light = lights[gl_WorkGroupID.z];
    ivec2 l = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(l, light.clip.zw))) return;
    ivec2 at = light.clip.xy + l;
    uint v = 0u;
    if (sprite_points && inside(at, light.area.xy, light.area.zw) && inside(at, surface_origin, surface_size)) {
        ivec2 s = at - surface_origin;
        int i = s.y * surface_size.x + s.x;
        if ((surface_sprite[i >> 5] >> (i & 31) & 1u) != 0u) {
            float h = surface_height[i];
            ivec2 g = ivec2(at.x, at.y + rows_above(h));
            ivec2 c = light.centre;
            // The sprite pass's rays run to the border of the area grown by `tallest` rows.
            ivec2 grown = light.extent + ivec2(0, tallest);
            bool walked = inside(g, c - grown, 2 * grown + 1) && inside(g, surface_origin, surface_size);
            if (!walked && own_line_lit(c, g, double(h), light.height)) {
                ivec2 d = abs(at - c);
                v = falloff[max(d.x, d.y)];
            }
        }
    }
    imageStore(lit, ivec3(l, light.layer), uvec4(v));
}
