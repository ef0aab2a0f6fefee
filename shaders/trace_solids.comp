#version 430
// Beyond the paper: the ground pass of tracing against solids with height on
// the GPU, one invocation per ray. The CPU reference is core's
// trace_light_solids (occluders.cpp): the same Bresenham steps and the same
// double-precision shades, so the same pixels. A ground pixel holds up to two
// spans (the lower first, as on the CPU). A span [low, high) s steps
// out, below the light's height H, shades the steps from s H / (H - low)
// (from s where it stands on the ground) to s H / (H - high), or to the
// border where high >= H; those to the border are one, and one that overlaps
// the last kept joins it, as on the CPU. A ray with more live shades than
// this shader holds sets `overflowed` and stops: the host then traces on the
// CPU.
// Rays that cross write the same value (it depends on the pixel only).

// One dispatch traces every light of a frame: light gl_WorkGroupID.y, its
// ray gl_GlobalInvocationID.x, its mask layer `layer` of `lit` (started by
// start_layers.comp).
layout(local_size_x = 64) in;

layout(r8ui, binding = 0) uniform writeonly uimage2DArray lit;             // per light its clip: texel (0, 0) is world clip.xy
layout(std430, binding = 0) readonly buffer Targets { ivec2 targets[]; };  // offsets from the centre, each light's run in turn
layout(std430, binding = 1) readonly buffer Falloff { uint falloff[]; };   // by distance max(|dx|, |dy|)
layout(std430, binding = 2) readonly buffer Spans { vec4 spans[]; };      // (low, high) of the lower span, then the upper's, per pixel of span_origin, span_size
layout(std430, binding = 3) buffer Overflow { uint overflowed; };
struct Light {
    ivec2 centre;
    ivec2 extent;       // a, b
    ivec2 ground_rays;  // the first of its targets, and their count
    ivec2 sprite_rays;  // the same for the sprite pass (sprite_points.comp)
    ivec4 clip;         // x, y, w, h
    ivec4 area;         // the light's area within the clip
    double height;      // H >= 0
    int layer;
    int unused;
};
layout(std430, binding = 6) readonly buffer Lights { Light lights[]; };
layout(std430, binding = 8) readonly buffer SurfaceSprite { uint surface_sprite[]; };  // a bit per pixel: it shows an overlay

uniform ivec2 span_origin;
uniform ivec2 span_size;
uniform bool skip_sprites;  // the area's sprite pixels left to the sprite pass (start_layers.comp)
uniform ivec2 surface_origin;
uniform ivec2 surface_size;

bool a_sprite_pixel(ivec2 at, ivec4 area) {
    if (!skip_sprites || any(lessThan(at, area.xy)) || any(greaterThanEqual(at, area.xy + area.zw)) ||
        any(lessThan(at, surface_origin)) || any(greaterThanEqual(at, surface_origin + surface_size)))
        return false;
    ivec2 s = at - surface_origin;
    int i = s.y * surface_size.x + s.x;
    return (surface_sprite[i >> 5] >> (i & 31) & 1u) != 0u;
}

const int max_shades = 64;

void main() {
    Light light = lights[gl_WorkGroupID.y];
    int id = int(gl_GlobalInvocationID.x);
    if (id >= light.ground_rays.y) return;
    ivec2 t = targets[light.ground_rays.x + id];
    ivec2 centre = light.centre;
    ivec4 clip = light.clip;
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
    double H = light.height;
    double from_[max_shades], to_[max_shades];
    int n = 0;
    bool endless = false;
    double endless_from = 0.0;
    for (int i = 0; i <= longest; ++i) {
        double k = double(i);
        ivec2 q = p - span_origin;
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, span_size))) {
            vec4 both = spans[q.y * span_size.x + q.x];
            for (int j = 0; j < 2; ++j) {
                vec2 s = j == 0 ? both.xy : both.zw;
                if (s.y > s.x && double(s.x) < H) {
                    double from = s.x <= 0.0 ? k : k * H / (H - double(s.x));
                    double to = k * H / (H - double(s.y));
                    if (double(s.y) >= H) {
                        endless_from = endless ? min(endless_from, from) : from;
                        endless = true;
                    } else if (n > 0 && from <= to_[n - 1] && from_[n - 1] <= to) {  // joins the last kept
                        from_[n - 1] = min(from_[n - 1], from);
                        to_[n - 1] = max(to_[n - 1], to);
                    } else {
                        if (n == max_shades) {
                            overflowed = 1u;
                            return;
                        }
                        from_[n] = from;
                        to_[n] = to;
                        ++n;
                    }
                }
            }
        }
        bool shaded = endless && endless_from <= k;
        for (int j = 0; j < n;) {
            if (to_[j] <= k) {  // behind the ray's front: done with
                --n;
                from_[j] = from_[n];
                to_[j] = to_[n];
                continue;
            }
            shaded = shaded || from_[j] <= k;
            ++j;
        }
        ivec2 l = p - clip.xy;
        if (!shaded && all(greaterThanEqual(l, ivec2(0))) && all(lessThan(l, clip.zw)) && !a_sprite_pixel(p, light.area))
            imageStore(lit, ivec3(l, light.layer), uvec4(falloff[i]));
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            p += diagonal;
        } else {
            p += straight;
        }
    }
}
