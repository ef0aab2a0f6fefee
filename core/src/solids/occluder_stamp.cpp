// Beyond the paper: a sprite's solids estimated from its alpha, as the
// occluder map stamps them (spans per ground pixel) and the heights of
// the points its pixels show (occluder_map.hpp; the objects themselves:
// solid_estimate.hpp).
#include "isolux/occluder_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>
#include <vector>

#include "isolux/opacity_map.hpp"

namespace isolux {

namespace {

constexpr double sqrt2 = 1.4142135623730951;

// The first of some runs [first, last] of 0..n-1 to cover each index, in
// the order given (-1: none): each run takes the indices no earlier one
// took, skipping those taken (next: the first not taken from i).
class FirstRun {
public:
    explicit FirstRun(int n) : next_(std::size_t(n) + 1), of_(std::size_t(n)) { clear(); }
    void clear() {
        for (std::size_t i = 0; i < next_.size(); ++i) next_[i] = int(i);
        std::fill(of_.begin(), of_.end(), -1);
    }
    void take(int first, int last, int run) {
        for (int i = find(first); i <= last; i = find(i + 1)) of_[std::size_t(i)] = run, next_[std::size_t(i)] = i + 1;
    }
    int operator[](int i) const { return of_[std::size_t(i)]; }

private:
    int find(int i) {
        while (next_[std::size_t(i)] != i) i = next_[std::size_t(i)] = next_[std::size_t(next_[std::size_t(i)])];
        return i;
    }
    std::vector<int> next_, of_;
};

// The run of indices 0..n-1 about `centre` where `in` holds, given its
// estimate [centre - half, centre + half] (a slice of a convex
// cross-section), its ends settled by `in` itself so that floating point
// rounding never moves a pixel in or out. Empty: first > last.
template <class In>
std::pair<int, int> settle_run(double centre, double half, int n, In&& in) {
    int i0 = std::max(int(std::ceil(centre - half)), 0), i1 = std::min(int(std::floor(centre + half)), n - 1);
    if (i0 > i1) {  // rounding may hide a run of one: the index nearest the centre
        const int c = std::clamp(int(std::lround(centre)), 0, n - 1);
        if (!in(c)) return {1, 0};
        i0 = i1 = c;
    }
    while (i0 > 0 && in(i0 - 1)) --i0;
    while (i0 <= i1 && !in(i0)) ++i0;
    while (i1 < n - 1 && in(i1 + 1)) ++i1;
    while (i1 >= i0 && !in(i1)) --i1;
    return {i0, i1};
}

// The topmost point of object `o` on the view line of each pixel of a w x h
// sprite whose `best` is still -1 (no object in front shows one): the
// highest half-pixel height z on it inside a cross-section. On the view line
// through sprite pixel (sx, sy) the point z high lies at u = sx / sqrt(2)
// across the view and v = sqrt(2) (sy + z) in depth, so down a column each
// height z is inside for one run of rows: the columns take those runs from
// the top down, each row keeping the first (rows x heights, not their product).
void topmost_points(const EstimatedObject& o, std::int32_t index, int w, int h, std::vector<float>& best,
                    std::vector<std::int32_t>& shown_by) {
    const int heights = 2 * int(o.radius.size());  // z = top - n / 2, n < heights
    const double top = o.height() - 0.5;
    FirstRun rows(h);
    for (int x = 0; x < w; ++x) {
        const double sx = x + 0.5 - o.center_x, u = sx / sqrt2;
        // A prism's flat top or its step over this column: a face its points lie on.
        const double face = o.flat_top ? o.height() : o.steps.empty() || o.ridge_axis >= 0 ? -1 : o.step_at(sx);
        rows.clear();
        for (int n = 0; n < heights; ++n) {
            const double z = top - 0.5 * n;
            const std::size_t level = std::size_t(z);
            const double d = o.radius[level], a = o.across_at(level);
            if (d <= 0 || u * u > a * a * (1 + 1e-9)) continue;
            const double half = d / sqrt2 * std::sqrt(std::max(0.0, 1 - u * u / (a * a)));
            const auto [y0, y1] = settle_run(o.center_y - 0.5 - z, half, h, [&](int y) {
                const Vec3 q = ground_frame(sx, y + 0.5 - o.center_y, z);
                return o.holds(level, q.x, q.y);
            });
            rows.take(y0, y1, n);
        }
        for (int y = 0; y < h; ++y) {
            const std::size_t i = std::size_t(y) * w + x;
            float& b = best[i];
            // A flat-topped prism's point in its top cross-section lies on
            // its top face (a hedge's), as a stepped prism's in its column's
            // top one does on its step: at the face's height, not half a
            // pixel inside, where the prism's own spans would shade it from
            // every light above it.
            if (b < 0 && rows[y] >= 0)
                b = float(o.height() - 0.5 * rows[y] == face ? face : top - 0.5 * rows[y]), shown_by[i] = index;
        }
    }
}

// The spans of object `o` over its stamp's pixels: at each pixel the
// heights from the lowest cross-section that holds its centre to above the
// highest (EstimatedObject::span_at's). A ground pixel's centre lies at
// screen (sx, sy) from the axis's foot, in the ground frame u = sx / sqrt(2)
// across the view and v = sqrt(2) sy in depth, so along a stamp row v is
// fixed and each cross-section holds one run of pixels about the axis.
// Each row takes those runs (from the ellipse, its ends settled by holds
// itself, so the bytes are span_at's), then hands each pixel the first run
// that covers it from below and from above: rows x (cross-sections +
// pixels), not pixels x cross-sections, so a huge sprite stays cheap.
void stamp_spans(const EstimatedObject& o, SpanStamp& stamp) {
    const Rect r = stamp.rect;
    stamp.spans.assign(std::size_t(r.w) * std::size_t(r.h), {0.f, 0.f});
    if (o.model == ObjectModel::prism) {
        // A prism fills its rectangle from the ground to its column's step
        // (a stepped prism's level is several runs along a row), less the
        // levels its hull carves: per pixel. A level its hull carves between
        // two it holds stays in the span (one span a pixel).
        for (int j = 0; j < r.h; ++j)
            for (int i = 0; i < r.w; ++i) {
                const double sx = r.x + i + 0.5 - o.center_x;
                const Vec3 q = ground_frame(sx, r.y + j + 0.5 - o.center_y, 0);
                if (std::abs(q.x) > o.half_x || std::abs(q.y) > o.half_y || !o.behind_front(q.x, q.y)) continue;
                const int top = int(std::min(o.height(), std::ceil(o.top_at(q.x, q.y))));
                // Its hull may carve levels off the bottom and the top (a fence's gap under its rails).
                int lo = 0, hi = top;
                while (lo < hi && !o.in_hull(std::size_t(lo), q.x, q.y)) ++lo;
                while (hi > lo && !o.in_hull(std::size_t(hi - 1), q.x, q.y)) --hi;
                if (hi > lo) stamp.spans[std::size_t(j) * r.w + std::size_t(i)] = {float(lo), float(hi)};
            }
        return;
    }
    const int levels = int(o.radius.size());
    std::vector<std::pair<int, int>> runs(static_cast<std::size_t>(levels));
    FirstRun lowest(r.w), highest(r.w);
    for (int j = 0; j < r.h; ++j) {
        const double sy = r.y + j + 0.5 - o.center_y, v = sqrt2 * sy;
        for (int z = 0; z < levels; ++z) {
            const double d = o.radius[std::size_t(z)];
            runs[std::size_t(z)] = {1, 0};
            if (d <= 0 || v * v > d * d * (1 + 1e-9)) continue;
            const double half = sqrt2 * o.across_at(std::size_t(z)) * std::sqrt(std::max(0.0, 1 - v * v / (d * d)));
            runs[std::size_t(z)] = settle_run(o.center_x - r.x - 0.5, half, r.w, [&](int i) {
                const Vec3 q = ground_frame(r.x + i + 0.5 - o.center_x, sy, 0);
                return o.holds(std::size_t(z), q.x, q.y);
            });
        }
        lowest.clear();
        highest.clear();
        for (int z = 0; z < levels; ++z) lowest.take(runs[std::size_t(z)].first, runs[std::size_t(z)].second, z);
        for (int z = levels - 1; z >= 0; --z) highest.take(runs[std::size_t(z)].first, runs[std::size_t(z)].second, z);
        for (int i = 0; i < r.w; ++i)
            if (lowest[i] >= 0) stamp.spans[std::size_t(j) * r.w + std::size_t(i)] = {float(lowest[i]), float(highest[i] + 1)};
    }
}

}  // namespace

SpriteSolids sprite_solids(const Tileset& ts, const Sprite& s, const Params& p) {
    SpriteSolids out;
    out.objects = sprite_objects(ts, s, p);
    for (const EstimatedObject& o : out.objects) {
        // The ground under the widest cross-section: its ellipse on screen
        // is across * sqrt(2) wide and radius / sqrt(2) high on each side.
        double across = 0, depth = 0;
        for (std::size_t z = 0; z < o.radius.size(); ++z)
            across = std::max(across, o.across_at(z)), depth = std::max(depth, o.radius[z]);
        SpanStamp stamp;
        stamp.rect = Rect{int(std::floor(o.center_x - across * sqrt2)) - 1, int(std::floor(o.center_y - depth / sqrt2)) - 1,
                          int(std::ceil(2 * across * sqrt2)) + 3, int(std::ceil(2 * depth / sqrt2)) + 3};
        stamp_spans(o, stamp);
        out.stamps.push_back(std::move(stamp));
    }
    // The point a pixel shows: the topmost point of a solid on its view line
    // (the first the viewer meets), else its row's height above the
    // footprint. On the view line through sprite pixel (sx, sy) relative to
    // an axis's foot, the point z high is ground_frame(sx, sy, z).
    // With several objects (a grove), the viewer meets the front one first
    // (the lowest foot on screen), and a pixel no solid shows takes its row's
    // height above the foot of the object whose axis is nearest.
    std::vector<std::size_t> front_first(out.objects.size());
    for (std::size_t k = 0; k < front_first.size(); ++k) front_first[k] = k;
    std::stable_sort(front_first.begin(), front_first.end(),
                     [&](std::size_t a, std::size_t b) { return out.objects[a].center_y > out.objects[b].center_y; });
    // Only the pixels the surface shows (opaque at the preset's threshold)
    // read their height; the others keep 0.
    const Mask shown = opacity_map(s.image, sprite_threshold(s, p.opacity_threshold));
    out.heights.assign(std::size_t(s.image.width) * s.image.height, 0.f);
    std::vector<float> best(out.heights.size(), -1.f);
    out.shown_by.assign(out.heights.size(), -1);
    for (std::size_t k : front_first)
        topmost_points(out.objects[k], std::int32_t(k), s.image.width, s.image.height, best, out.shown_by);
    for (int y = 0; y < s.image.height; ++y)
        for (int x = 0; x < s.image.width; ++x) {
            if (!shown.get(x, y)) {
                out.shown_by[std::size_t(y) * s.image.width + x] = -1;
                continue;
            }
            float b = best[std::size_t(y) * s.image.width + x];
            if (b < 0 && !out.objects.empty()) {
                const EstimatedObject* nearest = &out.objects[0];
                for (const EstimatedObject& o : out.objects)
                    if (std::abs(x + 0.5 - o.center_x) < std::abs(x + 0.5 - nearest->center_x)) nearest = &o;
                b = float(std::max(0.0, nearest->center_y - (y + 0.5)));
            }
            out.heights[std::size_t(y) * s.image.width + x] = std::max(b, 0.f);
        }
    return out;
}

}  // namespace isolux
