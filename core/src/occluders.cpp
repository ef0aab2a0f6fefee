// Beyond the paper: tracing against solids with height (occluders.hpp).
#include "isolux/occluders.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "isolux/error.hpp"
#include "isolux/footprint.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/solid_estimate.hpp"
#include "occluders_tree.hpp"

namespace isolux {

void Spans::add(float lo, float hi) {
    // The spans held and the new one, lowest first, those that meet joined;
    // three left: the narrowest gap closed.
    std::array<Span, 3> v{};
    int n = 0;
    for (const Span& s : {lower, upper, Span{lo, hi}})
        if (s.any()) v[std::size_t(n++)] = s;
    auto before = [](const Span& a, const Span& b) { return a.low < b.low || (a.low == b.low && a.high < b.high); };
    for (int i = 1; i < n; ++i)  // three at most: by insertion
        for (int k = i; k > 0 && before(v[std::size_t(k)], v[std::size_t(k - 1)]); --k) std::swap(v[std::size_t(k)], v[std::size_t(k - 1)]);
    int kept = 0;
    for (int k = 0; k < n; ++k) {
        if (kept > 0 && v[std::size_t(k)].low <= v[std::size_t(kept - 1)].high)
            v[std::size_t(kept - 1)].high = std::max(v[std::size_t(kept - 1)].high, v[std::size_t(k)].high);
        else
            v[std::size_t(kept++)] = v[std::size_t(k)];
    }
    if (kept == 3) {
        const int j = v[1].low - v[0].high <= v[2].low - v[1].high ? 0 : 1;  // the narrower gap, the lower on a tie
        v[std::size_t(j)].high = v[std::size_t(j + 1)].high;
        if (j == 0) v[1] = v[2];
        kept = 2;
    }
    lower = kept > 0 ? v[0] : Span{};
    upper = kept > 1 ? v[1] : Span{};
}

namespace {

constexpr double sqrt2 = 1.4142135623730951;
// A sprite pixel's own line is not tested over its last steps: its point
// stands at its own solid's surface, and the ground pixels just before it
// hold that solid's span at about its height.
constexpr int own_steps = 2;

// Widens the span at ground pixel i to hold [lo, hi), and flags it.
void fill(OccluderMap& m, std::size_t i, double lo, double hi) {
    lo = std::max(0.0, lo);
    if (hi <= lo) return;
    m.spans[i].add(float(lo), float(hi));
    m.flags[i] = OccluderMap::has_span;
}

// The heights the solid fills on the vertical line through ground point (X, Y).
bool vertical_span(const Solid& s, double X, double Y, double& lo, double& hi) {
    switch (s.kind) {
        case SolidKind::box:
            if (X < s.a.x || X > s.b.x || Y < s.a.y || Y > s.b.y) return false;
            lo = s.a.z, hi = s.b.z;
            return true;
        case SolidKind::cylinder:
        case SolidKind::cone: {
            const double d = std::hypot(X - s.a.x, Y - s.a.y), r = s.b.x;
            if (r <= 0 || d > r) return false;
            lo = s.a.z;
            hi = s.a.z + s.b.z * (s.kind == SolidKind::cone ? 1 - d / r : 1);
            return true;
        }
        case SolidKind::ellipsoid: {
            if (s.b.x <= 0 || s.b.y <= 0) return false;
            const double u = (X - s.a.x) / s.b.x, v = (Y - s.a.y) / s.b.y, q = u * u + v * v;
            if (q > 1) return false;
            const double half = s.b.z * std::sqrt(1 - q);
            lo = s.a.z - half, hi = s.a.z + half;
            return true;
        }
    }
    return false;
}

void fill_estimated(OccluderMap& m, const World& world, const Params& p, const std::vector<std::uint32_t>& near,
                    SolidsCache& cache, std::vector<std::vector<float>>& heights) {
    if (cache.made.size() != world.tileset.sprites.size()) {
        cache.sprites.assign(world.tileset.sprites.size(), SpriteSolids{});
        cache.made.assign(world.tileset.sprites.size(), 0);
    }
    for (std::uint32_t k : near) {
        const SpriteInstance& in = world.placed.instances[k];
        const std::size_t si = std::size_t(in.sprite);
        if (!cache.made[si]) {
            cache.sprites[si] = sprite_solids(world.tileset, world.tileset.sprites[si], p);
            cache.made[si] = 1;
        }
        const SpriteSolids& ss = cache.sprites[si];
        if (heights[si].empty()) heights[si] = ss.heights;
        for (const SpanStamp& stamp : ss.stamps) {
            const Rect box = intersect(Rect{in.x + stamp.rect.x, in.y + stamp.rect.y, stamp.rect.w, stamp.rect.h}, m.rect);
            for (int y = box.y; y < box.y + box.h; ++y)
                for (int x = box.x; x < box.x + box.w; ++x) {
                    const auto [lo, hi] = stamp.spans[std::size_t(y - in.y - stamp.rect.y) * stamp.rect.w + std::size_t(x - in.x - stamp.rect.x)];
                    if (hi > lo) fill(m, std::size_t(y - m.rect.y) * m.rect.w + (x - m.rect.x), lo, hi);
                }
        }
    }
}

void fill_shapes(OccluderMap& m, const World& world, Rect region) {
    const WorldSolids solids = world_solids(world, region);  // Error naming a sprite without a shape
    for (std::size_t k = 0; k < solids.solids.size(); ++k) {
        const auto& b = solids.bounds[k];
        // The ground rectangle under the solid, on screen: x = X - Y, y = (X + Y) / 2.
        const Rect box = intersect(Rect{int(std::floor(b[0].x - b[1].y)) - 1, int(std::floor((b[0].x + b[0].y) / 2)) - 1,
                                        int(std::ceil((b[1].x - b[0].y) - (b[0].x - b[1].y))) + 3,
                                        int(std::ceil((b[1].x + b[1].y - b[0].x - b[0].y) / 2)) + 3},
                                   m.rect);
        for (int y = box.y; y < box.y + box.h; ++y)
            for (int x = box.x; x < box.x + box.w; ++x) {
                const Vec3 q = ground_frame(x + 0.5, y + 0.5, 0);
                double lo = 0, hi = 0;
                if (vertical_span(solids.solids[k], q.x, q.y, lo, hi))
                    fill(m, std::size_t(y - m.rect.y) * m.rect.w + (x - m.rect.x), lo, hi);
            }
    }
}

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
void topmost_points(const EstimatedObject& o, int w, int h, std::vector<float>& best) {
    const int heights = 2 * int(o.radius.size());  // z = top - n / 2, n < heights
    const double top = o.height() - 0.5;
    FirstRun rows(h);
    for (int x = 0; x < w; ++x) {
        const double sx = x + 0.5 - o.center_x, u = sx / sqrt2;
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
            float& b = best[std::size_t(y) * w + x];
            if (b < 0 && rows[y] >= 0) b = float(top - 0.5 * rows[y]);
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
    for (std::size_t k : front_first) topmost_points(out.objects[k], s.image.width, s.image.height, best);
    for (int y = 0; y < s.image.height; ++y)
        for (int x = 0; x < s.image.width; ++x) {
            if (!shown.get(x, y)) continue;
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

namespace {

// The has_span flags of the pixels of `part` (inside the map), from their spans.
void flag_spans(OccluderMap& m, Rect part) {
    for (int y = part.y; y < part.y + part.h; ++y) {
        const std::size_t at = std::size_t(y - m.rect.y) * std::size_t(m.rect.w) + std::size_t(part.x - m.rect.x);
        for (std::size_t i = at; i < at + std::size_t(part.w); ++i)
            m.flags[i] = std::uint8_t(m.spans[i].any() ? OccluderMap::has_span : 0);
    }
}

// The lists of a map before a pan, and the ground pixels (in both the old
// region and the new) whose lists the pan cannot change.
struct KeptIndex {
    Rect rect, unchanged;
    std::vector<std::uint32_t> start;
    std::vector<OccluderMap::Shown> shown;
};

// The sprite points by ground pixel, and the has_shown flags (the has_span
// flags set). A ground pixel's points are the sprite pixels of its own
// column, at most reach_rows above it: with `kept`, the pixels it holds
// unchanged keep their lists, and only the others are listed from the
// surface (a pan: the strips that came in, and the rows below a top that
// moved, which gain or lose the points of sprites above).
void index_shown(OccluderMap& m, const KeptIndex* kept = nullptr) {
    const Surface& s = m.surface;
    const std::size_t n = s.instance.size();
    if (n >= std::numeric_limits<std::uint32_t>::max() - 1)
        throw Error("occluders: the region of " + std::to_string(n) + " pixels is too large to trace against solids");
    const Rect region = s.rect;
    const std::size_t w = std::size_t(std::max(0, region.w));
    const Rect unchanged = kept ? intersect(kept->unchanged, region) : Rect{};
    for (std::uint8_t& f : m.flags) f &= OccluderMap::has_span;
    // 1. The points of the ground pixels listed anew: each sprite pixel of
    // row y shows a point `rows` high over ground pixel i + rows * w, listed
    // in scan order where that ground pixel lies in the part.
    struct Point {
        std::uint32_t ground;
        OccluderMap::Shown shown;
    };
    thread_local std::vector<Point> points;
    points.clear();
    std::vector<std::uint32_t>& start = m.shown_start;
    start.assign(n + 2, 0);
    std::uint32_t tallest = 0, reach = 0;
    const std::vector<Rect> anew = unchanged.empty() ? std::vector<Rect>{region} : outside(region, unchanged);
    for (const Rect part : anew) {
        const std::size_t x0 = std::size_t(part.x - region.x), x1 = x0 + std::size_t(part.w);
        const std::size_t g0 = std::size_t(part.y - region.y), g1 = g0 + std::size_t(part.h);  // its ground rows
        const std::size_t from = part == region ? 0 : g0 - std::min<std::size_t>(g0, std::size_t(m.reach_rows));
        for (std::size_t y = from; y < g1; ++y)
            for (std::size_t i = y * w + x0; i < y * w + x1; ++i) {
                if (s.instance[i] < 0) continue;
                const float height = std::max(s.height[i], 0.f);  // one below the ground counts as on it
                const std::uint32_t rows = std::uint32_t(rows_above(height));
                reach = std::max(reach, rows);
                if (y + rows < g0 || y + rows >= g1) continue;
                const std::size_t g = i + rows * w;
                points.push_back({std::uint32_t(g), {height, rows}});
                ++start[g + 2];
                tallest = std::max(tallest, rows);
            }
    }
    // 2. The unchanged pixels' counts from their old lists.
    const auto old_index = [&](std::size_t y, std::size_t x) {  // region row and column -> the old map's pixel
        return std::size_t(int(y) + region.y - kept->rect.y) * std::size_t(kept->rect.w) + std::size_t(int(x) + region.x - kept->rect.x);
    };
    const std::size_t ux0 = std::size_t(unchanged.x - region.x), uy0 = std::size_t(unchanged.y - region.y);
    for (std::size_t y = uy0; y < uy0 + std::size_t(unchanged.h); ++y) {
        const std::size_t o = old_index(y, ux0);
        for (std::size_t x = 0; x < std::size_t(unchanged.w); ++x)
            start[y * w + ux0 + x + 2] = kept->start[o + x + 1] - kept->start[o + x];
    }
    // 3. The starts (a running sum of the counts: shown_start[g + 1] is then
    // where g's points start) and the has_shown flags.
    for (std::size_t g = 0; g < n; ++g) {
        if (start[g + 2]) m.flags[g] |= OccluderMap::has_shown;
        start[g + 2] += start[g + 1];
    }
    m.shown.resize(start[n + 1]);
    // 4. The unchanged pixels' lists, a row's at once, then the points
    // placed at their ground pixels' cursors shown_start[g + 1], which end
    // where g + 1's start: the starts, with one last entry to drop.
    for (std::size_t y = uy0; y < uy0 + std::size_t(unchanged.h); ++y) {
        const std::size_t g = y * w + ux0, o = old_index(y, ux0);
        const std::uint32_t first = kept->start[o], last = kept->start[o + std::size_t(unchanged.w)];
        std::copy(kept->shown.begin() + first, kept->shown.begin() + last, m.shown.begin() + start[g + 1]);
        for (std::uint32_t k = first; k < last; ++k) tallest = std::max(tallest, kept->shown[k].rows);
        for (std::size_t x = 0; x < std::size_t(unchanged.w); ++x) start[g + x + 1] = start[g + x + 2];
    }
    for (const Point& p : points) m.shown[start[p.ground + 1]++] = p.shown;
    start.pop_back();
    m.tallest = int(tallest);
    m.reach_rows = unchanged.empty() ? int(reach) : std::max(m.reach_rows, int(reach));
}

}  // namespace

void index_occluders(OccluderMap& m) {
    m.flags.resize(m.surface.instance.size());
    flag_spans(m, m.rect);
    index_shown(m);
}

namespace {

// Walks the Bresenham ray from (cx, cy) to (tx, ty), calling
// body(i, x, y, g, v) at each step: g the step's index in `grid` (-1 off
// it), v its index in `clip` (-1 outside). A ray whose ends both lie in
// both (its box does, so every step does) steps the two indices by offsets,
// with no test per step: the common case, a light inside the map and the view.
template <class Body>
void walk_ray(std::int64_t cx, std::int64_t cy, std::int64_t tx, std::int64_t ty, Rect grid, Rect clip, Body&& body) {
    BresenhamRay r(cx, cy, tx, ty);
    auto in = [](Rect q, std::int64_t x, std::int64_t y) { return q.contains(int(x), int(y)); };
    if (!(in(grid, cx, cy) && in(grid, tx, ty) && in(clip, cx, cy) && in(clip, tx, ty))) {
        for (; !r.done(); r.step())
            body(r.i, r.x, r.y,
                 in(grid, r.x, r.y) ? std::ptrdiff_t(r.y - grid.y) * grid.w + std::ptrdiff_t(r.x - grid.x) : -1,
                 in(clip, r.x, r.y) ? std::ptrdiff_t(r.y - clip.y) * clip.w + std::ptrdiff_t(r.x - clip.x) : -1);
        return;
    }
    std::ptrdiff_t g = std::ptrdiff_t(cy - grid.y) * grid.w + std::ptrdiff_t(cx - grid.x);
    std::ptrdiff_t v = std::ptrdiff_t(cy - clip.y) * clip.w + std::ptrdiff_t(cx - clip.x);
    const std::ptrdiff_t g_diagonal = std::ptrdiff_t(r.dy1) * grid.w + r.dx1, g_straight = std::ptrdiff_t(r.dy2) * grid.w + r.dx2;
    const std::ptrdiff_t v_diagonal = std::ptrdiff_t(r.dy1) * clip.w + r.dx1, v_straight = std::ptrdiff_t(r.dy2) * clip.w + r.dx2;
    std::int64_t x = cx, y = cy, numerator = r.numerator;
    for (std::int64_t i = 0; i <= r.longest; ++i) {
        body(i, x, y, g, v);
        numerator += r.shortest;
        if (!(numerator < r.longest)) {
            numerator -= r.longest;
            g += g_diagonal, v += v_diagonal, x += r.dx1, y += r.dy1;
        } else {
            g += g_straight, v += v_straight, x += r.dx2, y += r.dy2;
        }
    }
}

// The falloff by distance max(|dx|, |dy|), the step count along a ray.
std::vector<std::uint8_t> falloff_table(int a, int b, double scale) {
    std::vector<std::uint8_t> t(std::size_t(std::max(a, b)) + 1);
    for (std::size_t d = 0; d < t.size(); ++d) t[d] = falloff(std::int64_t(d), scale);
    return t;
}

// A sprite pixel's point h high over ground point (gx, gy) that no ray walks:
// lit unless a span on its own line from the light's centre (but the last
// own_steps) holds the segment's height there. Inside the map the line steps
// by index and reads a span only where the flags say one stands.
bool own_line_lit(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, std::int64_t gx, std::int64_t gy, double h,
                  double H) {
    const std::int64_t steps = std::max(std::llabs(gx - cx), std::llabs(gy - cy));
    bool lit = true;
    walk_ray(cx, cy, gx, gy, occ.rect, occ.rect, [&](std::int64_t i, std::int64_t, std::int64_t, std::ptrdiff_t g, std::ptrdiff_t) {
        if (!lit || i > steps - own_steps || g < 0 || !(occ.flags[std::size_t(g)] & OccluderMap::has_span)) return;
        const double z = H + (h - H) * double(i) / double(steps);
        lit = !occ.spans[std::size_t(g)].holds(z);
    });
    return lit;
}

}  // namespace

int occluder_reach(const Tileset& ts) {
    // A disc's ellipse fits its sprite's width (2 r sqrt(2) <= w), so the
    // ground it stands over lies at most r / sqrt(2) <= w / 4 rows below the
    // foot, and the foot lies inside the sprite; 4 more for the box's rounding.
    int reach = 0;
    for (const Sprite& s : ts.sprites) reach = std::max(reach, s.image.width / 4 + 4);
    return reach;
}

namespace {

// `m` made the spans, their has_span flags and the surface of `region`,
// without the index, in the storage it has: each pixel's values depend only
// on the sprites near it, so the map of a part of a region equals that part
// of the region's map.
void fill_occluders(OccluderMap& m, const World& world, const Params& p, Rect region, SolidsCache* cache) {
    m.rect = region;
    const std::size_t n = std::size_t(std::max(0, region.w)) * std::max(0, region.h);
    m.spans.assign(n, Spans{});
    m.flags.assign(n, 0);  // has_span set where a span is filled in
    if (region.empty() || p.occluders == Occluders::footprints) {
        build_surface_into(m.surface, world, region, p.opacity_threshold);
        return;
    }
    if (p.occluders == Occluders::shapes) {
        fill_shapes(m, world, region);
        build_surface_into(m.surface, world, region, p.opacity_threshold);
        return;
    }
    // The sprites whose solids stand over the region: a solid's ground lies
    // up to occluder_reach below its sprite.
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near, occluder_reach(world.tileset));
    std::vector<std::vector<float>> heights(world.tileset.sprites.size());
    SolidsCache own;
    fill_estimated(m, world, p, near, cache ? *cache : own, heights);
    build_surface_into(m.surface, world, region, p.opacity_threshold, &heights);
}

// Copies `from`'s spans, their flags and surface inside `r` (in both maps) into `to`.
void copy_part(OccluderMap& to, const OccluderMap& from, Rect r) {
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::size_t i = std::size_t(y - to.rect.y) * to.rect.w + std::size_t(r.x - to.rect.x);
        const std::size_t j = std::size_t(y - from.rect.y) * from.rect.w + std::size_t(r.x - from.rect.x);
        std::copy_n(&from.spans[j], r.w, &to.spans[i]);
        std::copy_n(&from.flags[j], r.w, &to.flags[i]);
        std::copy_n(&from.surface.instance[j], r.w, &to.surface.instance[i]);
        std::copy_n(&from.surface.height[j], r.w, &to.surface.height[i]);
    }
}

}  // namespace

namespace {

void check_occluder_region(Rect region, const Params& p) {
    if ((long long)std::max(region.w, 0) * std::max(region.h, 0) <= max_occluder_pixels) return;
    throw Error("occluders " + std::string(p.occluders == Occluders::shapes ? "shapes" : "solids") +
                ": the view and its lights need a region of " + std::to_string(region.w) + "x" +
                std::to_string(region.h) + " pixels, over the " + std::to_string(max_occluder_pixels >> 20) +
                "-megapixel limit for tracing against solids (about 35 bytes a pixel): show a smaller part of the "
                "map (isolux-cli: --view X,Y,W,H), use smaller light areas, or occluders footprints");
}

}  // namespace

OccluderMap build_occluders(const World& world, const Params& p, Rect region, SolidsCache* cache) {
    OccluderMap m;
    rebuild_occluders(m, world, p, region, cache);
    return m;
}

void rebuild_occluders(OccluderMap& m, const World& world, const Params& p, Rect region, SolidsCache* cache) {
    check_occluder_region(region, p);
    fill_occluders(m, world, p, region, cache);
    index_shown(m);
}

void update_occluders(OccluderMap& m, const World& world, const Params& p, Rect region, Rect changed, SolidsCache* cache) {
    check_occluder_region(region, p);
    const Rect keep = intersect(m.rect, region);
    // The manifest's shapes may stand anywhere around their sprites: no
    // bound says which sprites reach a part, so shapes are built whole.
    if (p.occluders == Occluders::shapes || keep.empty() || region.empty() || m.flags.size() != m.spans.size()) {
        rebuild_occluders(m, world, p, region, cache);
        return;
    }
    // The kept pixels' spans, surface and has_span flags hold where they are
    // (in place when the size is the same: a pan).
    KeptIndex kept{m.rect, keep, std::move(m.shown_start), std::move(m.shown)};
    move_grid(m.spans, m.rect, region);
    move_grid(m.surface.instance, m.rect, region, -1);
    move_grid(m.surface.height, m.rect, region);
    move_grid(m.flags, m.rect, region);
    m.rect = m.surface.rect = region;
    // What came into the region, and what the world changed: built.
    std::vector<Rect> parts = outside(region, keep);
    const Rect edited = intersect(changed, region);
    if (!edited.empty()) parts.push_back(edited);
    for (Rect r : parts) {
        OccluderMap part;
        fill_occluders(part, world, p, r, cache);
        copy_part(m, part, r);
        for (std::size_t i = 0; i < part.surface.instance.size(); ++i)
            if (part.surface.instance[i] >= 0)
                m.reach_rows = std::max(m.reach_rows, int(rows_above(std::max(part.surface.height[i], 0.f))));
    }
    // The lists that cannot change: not where the world changed (those are
    // listed whole), nor in the rows below a top that moved, within reach of
    // the sprites above it, which came or went.
    if (!edited.empty()) return index_shown(m);
    if (region.y != kept.rect.y) {
        const int top = std::max(region.y, kept.rect.y) + m.reach_rows;
        kept.unchanged = intersect(keep, Rect{keep.x, top, keep.w, std::max(0, keep.y + keep.h - top)});
    }
    index_shown(m, &kept);
}

namespace {

// The ground pass ray by ray: the reference the tree pass is held to, and
// what serves every light the tree does not.
void ground_by_rays(LightMask& m, const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double H,
                    const std::vector<std::uint8_t>& table, const Params& p) {
    // Ground pixels: one pass per ray, each span before a pixel shading a
    // stretch of the ray beyond it (its own pixel too when it stands on the
    // ground). Stretches that run to the border are one: from the nearest
    // start; one that overlaps the last kept joins it (the same union, so
    // the same pixels, from a handful of stretches a ray).
    // (shaders/trace_solids.comp is this loop on the GPU.)
    struct Shade { double from, to; };
    std::vector<Shade> shades;
    const double inf = std::numeric_limits<double>::infinity();
    const Spans* spans = occ.spans.data();
    const std::uint8_t* flags = occ.flags.data();
    for_each_ray_target(cx, cy, a, b, p, [&](std::int64_t tx, std::int64_t ty) {
        shades.clear();
        double endless_from = inf;
        walk_ray(cx, cy, tx, ty, occ.rect, m.clip, [&](std::int64_t i, std::int64_t, std::int64_t, std::ptrdiff_t g, std::ptrdiff_t v) {
            const double k = double(i);
            if (g >= 0 && (flags[g] & OccluderMap::has_span))
                for (const Span& sp : {spans[g].lower, spans[g].upper}) {  // the lower first, as the GPU
                    if (!sp.any() || sp.low >= H) continue;
                    const float lo = sp.low, hi = sp.high;
                    const double from = lo <= 0 ? k : k * H / (H - lo);
                    const double to = k * H / (H - hi);
                    if (hi >= H)
                        endless_from = std::min(endless_from, from);
                    else if (!shades.empty() && from <= shades.back().to && shades.back().from <= to)
                        shades.back() = {std::min(shades.back().from, from), std::max(shades.back().to, to)};
                    else
                        shades.push_back({from, to});
                }
            bool shaded = endless_from <= k;
            for (std::size_t s = 0; s < shades.size();) {
                if (shades[s].to <= k) {  // behind the ray's front: done with
                    shades[s] = shades.back();
                    shades.pop_back();
                    continue;
                }
                shaded = shaded || shades[s].from <= k;
                ++s;
            }
            if (!shaded && v >= 0) m.value[std::size_t(v)] = table[std::size_t(i)];
        });
    });
}

LightMask solids_mask(std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Rect clip) {
    LightMask m;
    start_mask(m, cx, cy, a, b, p, clip, p.mode == Mode::shadow);
    if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), std::uint8_t(1));
    return m;
}

}  // namespace

LightMask trace_light_solids(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double height,
                             const Params& p, Rect clip, int threads) {
    LightMask m = solids_mask(cx, cy, a, b, p, clip);
    if (m.clip.empty()) return m;
    assert(occ.flags.size() == occ.spans.size());  // index_occluders
    const double H = std::max(height, 0.0);
    const std::vector<std::uint8_t> table = falloff_table(a, b, p.falloff_scale);
    const Rect area{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
    if (!occluder_tree_serves(occ, area, p)) {
        ground_by_rays(m, occ, cx, cy, a, b, H, table, p);
        return m;
    }
    if (m.clip == area) {
        trace_ground_tree(m, occ, H, table, p, area, threads);
        return m;
    }
    // Clipped: the whole area over the tree, then the part of it the clip
    // holds copied (rays run to the border whatever the clip; past the area
    // the clip stays unlit). Leaving each ray once it moves away from the
    // clip, the tree walks fewer steps than the rays one by one would.
    const Rect inside = intersect(m.clip, area);
    thread_local LightMask whole;
    start_mask(whole, cx, cy, a, b, p, area);
    trace_ground_tree(whole, occ, H, table, p, inside, threads);
    for (int y = inside.y; y < inside.y + inside.h; ++y)
        std::memcpy(&m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(inside.x - m.clip.x)],
                    &whole.value[std::size_t(y - area.y) * area.w + std::size_t(inside.x - area.x)], std::size_t(inside.w));
    return m;
}

LightMask trace_light_solids_by_rays(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b,
                                     double height, const Params& p, Rect clip) {
    LightMask m = solids_mask(cx, cy, a, b, p, clip);
    if (m.clip.empty()) return m;
    ground_by_rays(m, occ, cx, cy, a, b, std::max(height, 0.0), falloff_table(a, b, p.falloff_scale), p);
    return m;
}

namespace {

// The sprite pass ray by ray: the reference the tree pass is held to, and
// what serves every light the tree does not.
void sprite_points_by_rays(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    const double H = std::max(height, 0.0);
    const std::int64_t cx = m.cx, cy = m.cy;
    const Rect area = intersect(Rect{int(cx) - m.a, int(cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    auto index = [&](std::int64_t x, std::int64_t y) { return std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x); };
    start_sprite_points(m, occ, height, p);
    // Along each ray: the descents blocked by the spans passed at least
    // own_steps before (the last steps hold the point's own solid at about
    // its height), then the points over this step's ground pixel.
    const std::vector<std::uint8_t> table = falloff_table(m.a, m.b, p.falloff_scale);
    std::array<Spans, own_steps + 1> passed{};  // the spans of the last steps
    auto sprite_ray = [&](std::int64_t tx, std::int64_t ty) {
        RayShadow blocked;
        walk_ray(cx, cy, tx, ty, occ.rect, m.clip, [&](std::int64_t i, std::int64_t x, std::int64_t y, std::ptrdiff_t g, std::ptrdiff_t) {
            const std::int64_t s = i - own_steps;
            if (s >= 0) blocked.pass(passed[std::size_t(s) % passed.size()], int(s), H);
            const std::uint8_t f = g >= 0 ? occ.flags[std::size_t(g)] : 0;
            passed[std::size_t(i) % passed.size()] = f & OccluderMap::has_span ? occ.spans[std::size_t(g)] : Spans{};
            if (!(f & OccluderMap::has_shown)) return;
            for (std::uint32_t k = occ.shown_start[std::size_t(g)]; k < occ.shown_start[std::size_t(g) + 1]; ++k) {
                const double h = occ.shown[k].height;
                const std::int64_t rows = occ.shown[k].rows;
                if (!area.contains(int(x), int(y - rows))) continue;
                std::uint8_t& v = m.value[index(x, y - rows)];
                if (v) continue;
                const double u = i > 0 ? (H - h) / double(i) : 0;
                if (i <= own_steps || !blocked.blocks(u)) v = table[std::size_t(std::max(std::llabs(x - cx), std::llabs(y - rows - cy)))];
            }
        });
    };
    for_each_ray_target(cx, cy, m.a, m.b + occ.tallest, p, sprite_ray);
}

}  // namespace

void start_sprite_points(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    if (m.clip.empty()) return;
    const double H = std::max(height, 0.0);
    const Surface& surface = occ.surface;
    const std::int64_t cx = m.cx, cy = m.cy;
    const Rect area = intersect(Rect{int(cx) - m.a, int(cy) - m.b, 2 * m.a + 1, 2 * m.b + 1}, m.clip);
    auto at = [&](std::int64_t x, std::int64_t y) {
        return std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x);
    };
    // The rays run to the border of the light's area grown by the tallest
    // point's rows, so a sprite standing below the area whose top shows in
    // it is reached too (the tree's rays are the same bytes). One whose
    // ground point no ray walks (off the map) is tested along its own line
    // (own_line_lit).
    const Rect ray_area{int(cx) - m.a, int(cy) - m.b - occ.tallest, 2 * m.a + 1, 2 * (m.b + occ.tallest) + 1};
    const Rect rows = intersect(area, surface.rect);  // outside the surface: no sprite
    for (int y = rows.y; y < rows.y + rows.h; ++y) {
        const std::int32_t* instance = &surface.instance[at(rows.x, y)];
        const float* heights = &surface.height[at(rows.x, y)];
        std::uint8_t* value = &m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(rows.x - m.clip.x)];
        for (int i = 0; i < rows.w; ++i) {
            if (instance[i] < 0) continue;
            value[i] = 0;
            const double h = heights[i];
            const std::int64_t gx = rows.x + i, gy = y + rows_above(h);
            if (ray_area.contains(int(gx), int(gy)) && surface.rect.contains(int(gx), int(gy))) continue;
            if (own_line_lit(occ, cx, cy, gx, gy, h, H))
                value[i] = falloff(std::max(std::llabs(gx - cx), std::llabs(std::int64_t(y) - cy)), p.falloff_scale);
        }
    }
}

void light_sprite_points(LightMask& m, const OccluderMap& occ, double height, const Params& p, int threads) {
    if (m.clip.empty()) return;
    assert(occ.flags.size() == occ.surface.instance.size());  // index_occluders
    const Rect whole_area{int(m.cx) - m.a, int(m.cy) - m.b, 2 * m.a + 1, 2 * m.b + 1};
    const Rect ray_area{whole_area.x, whole_area.y - occ.tallest, whole_area.w, whole_area.h + 2 * occ.tallest};
    if (!occluder_tree_serves(occ, ray_area, p)) return sprite_points_by_rays(m, occ, height, p);
    // Over the tree: every ground point lies in the rays' area, inside the
    // map. A clipped light's sprite pixels come from its whole area's (rays
    // run to the border whatever the clip, so each pixel's answer is the
    // same), the walk asked for the clip's alone.
    const Rect wanted = intersect(whole_area, m.clip);
    const Surface& surface = occ.surface;
    const bool whole = m.clip == whole_area;
    thread_local LightMask whole_mask;
    if (!whole) start_mask(whole_mask, m.cx, m.cy, m.a, m.b, p, whole_area);
    LightMask& into = whole ? m : whole_mask;
    for (int y = wanted.y; y < wanted.y + wanted.h; ++y) {  // every sprite pixel starts unlit
        const std::int32_t* instance = &surface.instance[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(wanted.x - surface.rect.x)];
        std::uint8_t* value = &into.value[std::size_t(y - into.clip.y) * into.clip.w + std::size_t(wanted.x - into.clip.x)];
        for (int i = 0; i < wanted.w; ++i)
            if (instance[i] >= 0) value[i] = 0;
    }
    const std::vector<std::uint8_t> table = falloff_table(m.a, m.b, p.falloff_scale);
    light_sprite_points_tree(into, occ, std::max(height, 0.0), table, p, own_steps, wanted, threads);
    if (whole) return;
    for (int y = wanted.y; y < wanted.y + wanted.h; ++y)
        for (int x = wanted.x; x < wanted.x + wanted.w; ++x)
            if (surface.instance[std::size_t(y - surface.rect.y) * surface.rect.w + std::size_t(x - surface.rect.x)] >= 0)
                m.value[std::size_t(y - m.clip.y) * m.clip.w + std::size_t(x - m.clip.x)] =
                    whole_mask.value[std::size_t(y - whole_area.y) * whole_area.w + std::size_t(x - whole_area.x)];
}

void light_sprite_points_by_rays(LightMask& m, const OccluderMap& occ, double height, const Params& p) {
    if (m.clip.empty()) return;
    sprite_points_by_rays(m, occ, height, p);
}

}  // namespace isolux
