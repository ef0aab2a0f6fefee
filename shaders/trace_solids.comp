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
layout(local_size_x = 64) in;

layout(r8ui, binding = 0) uniform writeonly uimage2D lit;                  // the clip: texel (0, 0) is world clip.xy
layout(std430, binding = 0) readonly buffer Targets { ivec2 targets[]; };  // offsets from the centre
layout(std430, binding = 1) readonly buffer Falloff { uint falloff[]; };   // by distance max(|dx|, |dy|)
layout(std430, binding = 2) readonly buffer Spans { vec4 spans[]; };      // (low, high) of the lower span, then the upper's, per pixel of span_origin, span_size
layout(std430, binding = 3) buffer Overflow { uint overflowed; };

uniform ivec2 centre;
uniform ivec4 clip;  // x, y, w, h
uniform ivec2 span_origin;
uniform ivec2 span_size;
uniform int ray_count;
uniform double light_height;  // H >= 0

const int max_shades = 64;

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
    double H = light_height;
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
        if (!shaded && all(greaterThanEqual(l, ivec2(0))) && all(lessThan(l, clip.zw))) imageStore(lit, l, uvec4(falloff[i]));
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            p += diagonal;
        } else {
            p += straight;
        }
    }
}
