// The two passes of occluder_map.hpp over the border rays' prefix tree
// (ray_tree.hpp): every node once, not every ray's every step, and the parts
// of the tree no solid stands before walked with no bookkeeping at all. The
// same bytes as the ray-by-ray passes (tests/core/solids/solids_pass_test.cpp holds them
// to it); those stay the reference and serve every case these do not.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "isolux/light_trace.hpp"
#include "isolux/occluder_map.hpp"

namespace isolux {

// Whether the trees reach a light of half-extents a, b (border rays, an
// extent the trees are kept for); and whether the tree passes serve a
// light's area: within that extent, lying inside the occluder map.
bool occluder_tree_extent(int a, int b, const Params& p);
bool occluder_tree_serves(const OccluderMap& occ, Rect area, const Params& p);

// The ground pass (trace_light_solids) over the tree, into `m` as started
// with its clip the whole area; only the pixels in `wanted` (within the
// area) are sure to be lit: the walk skips the rays once they leave it.
// On `threads` threads the tree's subtrees are walked apart, to the same
// bytes.
void trace_ground_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                       const Params& p, Rect wanted, int threads = 1);

// What the spans a ray of the sprite pass has passed (all but its last
// own_steps steps, which hold a point's own solid at about its height)
// block: a segment from the light down to a point h high d steps out
// descends u = (H - h) / d per step, and a span [lo, hi) s steps out blocks
// it when lo <= H - u s < hi. The spans standing on the ground block every
// descent above the least of their (H - hi) / s (the ray's horizon); each
// crown over the ground the descents ((H - hi) / s, (H - lo) / s], kept as
// up to `most` disjoint intervals (beyond, the two nearest join, blocking
// their gap too: a bounded state, cheap to carry down the tree).
struct RayShadow {
    static constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr int most = 16;  // crowns' blocked descents kept apart (more join the nearest two)
    double standing = inf;          // every descent above it is blocked
    int crowns = 0;
    std::array<double, most + 1> from{}, to{};  // disjoint (from, to], sorted (one spare while joining)

    // The spans s steps out (s >= 0; s = 0 the light's own pixel: a light
    // inside a solid is hidden from every point).
    void pass(const Spans& sps, int s, double H) {
        for (const Span& sp : {sps.lower, sps.upper}) {
            if (!sp.any()) continue;
            if (s == 0) {
                if (sp.low <= H && H < sp.high) standing = -inf;
            } else if (sp.low <= 0) {
                standing = std::min(standing, (H - sp.high) / double(s));
            } else {
                add((H - sp.high) / double(s), (H - sp.low) / double(s));
            }
        }
    }
    bool hidden() const { return standing == -inf; }
    // Copies `o`'s crowns in use alone (a ray rarely keeps more than a few).
    void set(const RayShadow& o) {
        standing = o.standing;
        crowns = o.crowns;
        for (int j = 0; j < crowns; ++j) from[std::size_t(j)] = o.from[std::size_t(j)], to[std::size_t(j)] = o.to[std::size_t(j)];
    }
    // Whether the segment descending u per step to a point is blocked.
    bool blocks(double u) const {
        if (u > standing) return true;
        for (int j = 0; j < crowns; ++j)
            if (from[std::size_t(j)] < u && u <= to[std::size_t(j)]) return true;
        return false;
    }

private:
    void move(int from_k, int to_k) { from[std::size_t(to_k)] = from[std::size_t(from_k)], to[std::size_t(to_k)] = to[std::size_t(from_k)]; }
    void add(double f, double t) {
        int i = 0;
        while (i < crowns && to[std::size_t(i)] < f) ++i;  // the first that ends at or after f
        int j = i;
        while (j < crowns && from[std::size_t(j)] <= t) {  // those it meets join it
            f = std::min(f, from[std::size_t(j)]);
            t = std::max(t, to[std::size_t(j)]);
            ++j;
        }
        // [i, j) become one interval at i: the rest move by 1 - (j - i).
        const int shift = 1 - (j - i);
        if (shift > 0)
            for (int k = crowns - 1; k >= j; --k) move(k, k + shift);
        else if (shift < 0)
            for (int k = j; k < crowns; ++k) move(k, k + shift);
        crowns += shift;
        from[std::size_t(i)] = f;
        to[std::size_t(i)] = t;
        if (crowns <= most) return;
        // One too many: the two with the least gap between them join.
        int best = 0;
        for (int k = 1; k + 1 < crowns; ++k)
            if (from[std::size_t(k + 1)] - to[std::size_t(k)] < from[std::size_t(best + 1)] - to[std::size_t(best)]) best = k;
        to[std::size_t(best)] = to[std::size_t(best + 1)];
        for (int k = best + 2; k < crowns; ++k) move(k, k - 1);
        --crowns;
    }
};

// The sprite pass's rays (light_sprite_points, after its sprite pixels are
// unlit) over the tree of its rays' area (the light's grown by occ.tallest
// rows up and down, which the caller checks the tree serves), the mask's
// clip the light's whole area; only the sprite pixels in `wanted` (within
// the area) are sure to be lit: the walk leaves the rays once they move
// away from it, and a ray from where no point below can be lit (hidden, or
// its horizon past every point's top behind a span as tall as the light).
// On `threads` threads, as trace_ground_tree.
void light_sprite_points_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                              const Params& p, int own_steps, Rect wanted, int threads = 1);

}  // namespace isolux
