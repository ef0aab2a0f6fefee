#version 430
// Beyond the paper: the sprite pass of tracing against solids with height on
// the GPU, one invocation per ray of the light's area grown by the tallest
// point's rows. The CPU reference is core's light_sprite_points_by_rays
// (occluders.cpp), after start_sprite_points: the same Bresenham steps, the
// same double-precision descents and the same bounded state per ray
// (RayShadow, core/src/solids/solids_pass_tree.hpp), so the same pixels.
// A segment from the light (height H) down to a point h high, d steps out,
// descends u = (H - h) / d per step. The spans standing on the ground block
// every descent above the least of their (H - high) / s (the ray's horizon);
// each crown over the ground blocks ((H - high) / s, (H - low) / s], kept as
// up to `most` disjoint sorted intervals (beyond, the two nearest join). A
// ray passes a step's spans own_steps steps after it reaches them: a
// point's last steps hold its own solid at about its height.
// Points are written where lit into `lit` (started by start_layers.comp; the
// ground pass leaves the area's sprite pixels to this one): rays that reach
// the same point write the same value (it depends on the pixel only).
// One dispatch serves every light of a frame: light gl_WorkGroupID.y, its
// ray gl_GlobalInvocationID.x, its layer of `lit`.
layout(local_size_x = 64) in;

layout(r8ui, binding = 0) uniform writeonly uimage2DArray lit;               // per light its clip: texel (0, 0) is world clip.xy
layout(std430, binding = 0) readonly buffer Targets { ivec2 targets[]; };    // offsets from the centre, each light's run in turn
layout(std430, binding = 1) readonly buffer Falloff { uint falloff[]; };     // by distance max(|dx|, |dy|)
layout(std430, binding = 2) readonly buffer Spans { vec4 spans[]; };        // (low, high) of the lower span, then the upper's
struct Shown {
    float height;  // of the point the pixel shows
    uint rows;     // the pixel lies this many rows above its ground pixel
};                 // (an edit's padding: rows 2^30, outside every area, so skipped)
layout(std430, binding = 4) readonly buffer ShownStart { uint shown_start[]; };  // per ground pixel, and one past the last
layout(std430, binding = 5) readonly buffer ShownPoints { Shown shown[]; };
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

uniform ivec2 span_origin;  // the occluder map's rect: spans and shown_start
uniform ivec2 span_size;

const int own_steps = 2;
const int most = 16;

// The ray's state (RayShadow).
bool hidden = false;            // the light stands inside a solid
bool has_standing = false;
double standing = 0.0;          // every descent above it is blocked
int crowns = 0;
double from_[most + 1], to_[most + 1];  // disjoint (from, to], sorted (one spare while joining)

void move(int a, int b) {
    from_[b] = from_[a];
    to_[b] = to_[a];
}

void add(double f, double t) {
    int i = 0;
    while (i < crowns && to_[i] < f) ++i;  // the first that ends at or after f
    int j = i;
    while (j < crowns && from_[j] <= t) {  // those it meets join it
        f = min(f, from_[j]);
        t = max(t, to_[j]);
        ++j;
    }
    int shift = 1 - (j - i);
    if (shift > 0)
        for (int k = crowns - 1; k >= j; --k) move(k, k + shift);
    else if (shift < 0)
        for (int k = j; k < crowns; ++k) move(k, k + shift);
    crowns += shift;
    from_[i] = f;
    to_[i] = t;
    if (crowns <= most) return;
    int best = 0;  // one too many: the two with the least gap between them join
    for (int k = 1; k + 1 < crowns; ++k)
        if (from_[k + 1] - to_[k] < from_[best + 1] - to_[best]) best = k;
    to_[best] = to_[best + 1];
    for (int k = best + 2; k < crowns; ++k) move(k, k - 1);
    --crowns;
}

void pass(vec4 both, int s, double H) {
    for (int j = 0; j < 2; ++j) {
        vec2 sp = j == 0 ? both.xy : both.zw;
        if (!(sp.y > sp.x)) continue;
        double lo = double(sp.x), hi = double(sp.y);
        if (s == 0) {
            if (lo <= H && H < hi) hidden = true;
        } else if (lo <= 0.0) {
            double d = (H - hi) / double(s);
            standing = has_standing ? min(standing, d) : d;
            has_standing = true;
        } else {
            add((H - hi) / double(s), (H - lo) / double(s));
        }
    }
}

bool blocks(double u) {
    if (hidden || (has_standing && u > standing)) return true;
    for (int j = 0; j < crowns; ++j)
        if (from_[j] < u && u <= to_[j]) return true;
    return false;
}

bool on_map(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, span_size)); }

void main() {
    Light light = lights[gl_WorkGroupID.y];
    int id = int(gl_GlobalInvocationID.x);
    if (id >= light.sprite_rays.y) return;
    ivec2 t = targets[light.sprite_rays.x + id];
    ivec2 centre = light.centre;
    ivec4 clip = light.clip, area = light.area;
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
    vec4 passed[own_steps + 1];  // the spans of the last steps
    for (int i = 0; i <= longest; ++i) {
        int s = i - own_steps;
        if (s >= 0) pass(passed[s % (own_steps + 1)], s, H);
        ivec2 q = p - span_origin;
        bool on = on_map(q);
        int g = q.y * span_size.x + q.x;
        passed[i % (own_steps + 1)] = on ? spans[g] : vec4(0.0);
        if (on)
            for (uint k = shown_start[g]; k < shown_start[g + 1]; ++k) {
                ivec2 at = ivec2(p.x, p.y - int(shown[k].rows));
                if (any(lessThan(at, area.xy)) || any(greaterThanEqual(at, area.xy + area.zw))) continue;
                double u = i > 0 ? (H - double(shown[k].height)) / double(i) : 0.0;
                if (i <= own_steps || !blocks(u)) {
                    ivec2 d = abs(at - centre);
                    imageStore(lit, ivec3(at - clip.xy, light.layer), uvec4(falloff[max(d.x, d.y)]));
                }
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
