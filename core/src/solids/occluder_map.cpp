// Beyond the paper: the occluder map, each ground pixel's spans of solid
// height and the sprite points standing over it (occluder_map.hpp), built
// for a region and kept across pans.
#include "isolux/occluder_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "isolux/error.hpp"
#include "solids/occluder_index.hpp"

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
    for (std::uint32_t k : near) {
        const SpriteInstance& in = world.placed.instances[k];
        const std::size_t si = std::size_t(in.sprite);
        const SpriteSolids& ss = cached_solids(cache, world.tileset, si, p);
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
        const auto g = ground_box(solids.solids[k]);
        const Rect box = intersect(Rect{int(g[0]), int(g[1]), int(g[2]), int(g[3])}, m.rect);
        for (int y = box.y; y < box.y + box.h; ++y)
            for (int x = box.x; x < box.x + box.w; ++x) {
                const Vec3 q = ground_frame(x + 0.5, y + 0.5, 0);
                double lo = 0, hi = 0;
                if (vertical_span(solids.solids[k], q.x, q.y, lo, hi))
                    fill(m, std::size_t(y - m.rect.y) * m.rect.w + (x - m.rect.x), lo, hi);
            }
    }
}

// The has_span flags of the pixels of `part` (inside the map), from their spans.
void flag_spans(OccluderMap& m, Rect part) {
    for (int y = part.y; y < part.y + part.h; ++y) {
        const std::size_t at = std::size_t(y - m.rect.y) * std::size_t(m.rect.w) + std::size_t(part.x - m.rect.x);
        for (std::size_t i = at; i < at + std::size_t(part.w); ++i)
            m.flags[i] = std::uint8_t(m.spans[i].any() ? OccluderMap::has_span : 0);
    }
}

// The most memory the last update's lists keep for the next (per thread).
constexpr std::size_t kept_spare_bytes = std::size_t(64) << 20;

// The lists of a map before a pan or an edit, the parts of the region (in
// both the old region and the new) whose lists it cannot change, and the
// rest, listed anew.
struct KeptIndex {
    Rect rect;
    std::vector<Rect> unchanged, anew;
    std::vector<std::uint32_t> start;
    std::vector<OccluderMap::Shown> shown;
};

// The sprite points by ground pixel, and the has_shown flags (the has_span
// flags set). A ground pixel's points are the sprite pixels of its own
// column, at most reach_rows above it: with `kept`, the pixels it holds
// unchanged keep their lists, and only the others are listed from the
// surface (a pan: the strips that came in, and the rows below a top that
// moved, which gain or lose the points of sprites above; an edit: the
// columns it changed, down to reach_rows below it). What remains for the
// whole region is a running sum and copies of the kept lists.
void index_shown(OccluderMap& m, const KeptIndex* kept = nullptr) {
    m.padding = 0;
    const Surface& s = m.surface;
    const std::size_t n = s.instance.size();
    if (n >= std::numeric_limits<std::uint32_t>::max() - 1)
        throw Error("occluders: the region of " + std::to_string(n) + " pixels is too large to trace against solids");
    const Rect region = s.rect;
    const std::size_t w = std::size_t(std::max(0, region.w));
    std::vector<Rect> unchanged;
    if (kept)
        for (Rect r : kept->unchanged)
            if (const Rect c = intersect(r, region); !c.empty()) unchanged.push_back(c);
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
    const std::vector<Rect> anew = kept ? kept->anew : std::vector<Rect>{region};
    for (Rect part : anew) {
        part = intersect(part, region);
        if (part.empty()) continue;
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
    for (const Rect u : unchanged) {
        const std::size_t ux0 = std::size_t(u.x - region.x), uy0 = std::size_t(u.y - region.y);
        for (std::size_t y = uy0; y < uy0 + std::size_t(u.h); ++y) {
            const std::size_t o = old_index(y, ux0);
            for (std::size_t x = 0; x < std::size_t(u.w); ++x)
                start[y * w + ux0 + x + 2] = kept->start[o + x + 1] - kept->start[o + x];
        }
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
    for (const Rect u : unchanged) {
        const std::size_t ux0 = std::size_t(u.x - region.x), uy0 = std::size_t(u.y - region.y);
        for (std::size_t y = uy0; y < uy0 + std::size_t(u.h); ++y) {
            const std::size_t g = y * w + ux0, o = old_index(y, ux0);
            const std::uint32_t first = kept->start[o], last = kept->start[o + std::size_t(u.w)];
            std::copy(kept->shown.begin() + first, kept->shown.begin() + last, m.shown.begin() + start[g + 1]);
            for (std::uint32_t k = first; k < last; ++k) tallest = std::max(tallest, kept->shown[k].rows);
            for (std::size_t x = 0; x < std::size_t(u.w); ++x) start[g + x + 1] = start[g + x + 2];
        }
    }
    for (const Point& p : points) m.shown[start[p.ground + 1]++] = p.shown;
    start.pop_back();
    m.tallest = int(tallest);
    m.reach_rows = unchanged.empty() ? int(reach) : std::max(m.reach_rows, int(reach));
}

// The lists without their padding, in place (before a pan's index_shown
// copies them by rows).
void drop_padding(OccluderMap& m) {
    if (m.padding == 0) return;
    std::uint32_t to = 0;
    for (std::size_t g = 0; g + 1 < m.shown_start.size(); ++g) {
        const std::uint32_t from = m.shown_start[g], end = m.shown_start[g + 1];
        m.shown_start[g] = to;
        for (std::uint32_t k = from; k < end; ++k)
            if (m.shown[k].rows != OccluderMap::unlisted) m.shown[to++] = m.shown[k];
    }
    m.shown_start.back() = to;
    m.shown.resize(to);
    m.padding = 0;
}

// An edit in place's lists (index_shown's, for `lists`, region pixels).
// Where each row's new lists fit the room its old ones took (their padding
// included), they are written there, padding ending the row's last list:
// nothing else moves. Else the entries from the lists' first pixel to
// their last (row-major) are written anew, the other columns' lists among
// them copied, each row's lists given as much room again as they need (for
// the next edits there), and the entries after them moved up. The has_shown
// flags and the tallest point as index_shown leaves them: the same lists
// but for the padding.
void relist_shown(OccluderMap& m, Rect lists) {
    const Surface& s = m.surface;
    const Rect region = s.rect;
    const std::size_t w = std::size_t(region.w);
    const std::size_t x0 = std::size_t(lists.x - region.x), x1 = x0 + std::size_t(lists.w);
    const std::size_t g0 = std::size_t(lists.y - region.y), g1 = g0 + std::size_t(lists.h);  // ground rows
    constexpr std::uint32_t unlisted = OccluderMap::unlisted;
    const OccluderMap::Shown pad{0.f, unlisted};
    std::vector<std::uint32_t>& start = m.shown_start;
    // 1. The points over the lists' pixels, by ground pixel in scan order
    // (as index_shown places them), and the rows each sprite pixel reaches.
    struct Point {
        std::uint32_t ground;
        OccluderMap::Shown shown;
    };
    thread_local std::vector<Point> points;
    points.clear();
    std::uint32_t reach = 0, new_tallest = 0;
    for (std::size_t y = g0 - std::min<std::size_t>(g0, std::size_t(m.reach_rows)); y < g1; ++y)
        for (std::size_t i = y * w + x0; i < y * w + x1; ++i) {
            if (s.instance[i] < 0) continue;
            const float height = std::max(s.height[i], 0.f);
            const std::uint32_t rows = std::uint32_t(rows_above(height));
            reach = std::max(reach, rows);
            if (y + rows < g0 || y + rows >= g1) continue;
            points.push_back({std::uint32_t(i + rows * w), {height, rows}});
            new_tallest = std::max(new_tallest, rows);
        }
    std::stable_sort(points.begin(), points.end(), [](const Point& a, const Point& b) { return a.ground < b.ground; });
    // 2. Per row, the new count against the old room; the old tallest's
    // entries and the padding among the old lists counted.
    thread_local std::vector<std::uint32_t> counts;  // per row of the lists
    counts.assign(g1 - g0, 0);
    for (const Point& p : points) ++counts[p.ground / w - g0];
    bool fits = true;
    std::size_t lost_tallest = 0, old_padding = 0;
    for (std::size_t y = g0; y < g1; ++y) {
        const std::uint32_t from = start[y * w + x0], to = start[y * w + x1];
        fits = fits && counts[y - g0] <= to - from;
        for (std::uint32_t k = from; k < to; ++k) {
            lost_tallest += m.shown[k].rows == std::uint32_t(m.tallest);
            old_padding += m.shown[k].rows == unlisted;
        }
    }
    // 3. The lists' flags, and their entries where they are to go.
    auto place_row = [&](std::size_t y, std::uint32_t at, std::uint32_t room, std::vector<Point>::const_iterator& p) {
        for (std::size_t g = y * w + x0; g < y * w + x1; ++g) {
            start[g] = at;
            const std::uint32_t before = at;
            for (; p != points.cend() && p->ground == g; ++p) m.shown[at++] = p->shown;
            m.flags[g] = std::uint8_t((m.flags[g] & OccluderMap::has_span) | (at > before ? OccluderMap::has_shown : 0));
        }
        std::fill(m.shown.begin() + at, m.shown.begin() + std::ptrdiff_t(start[y * w + x0] + room), pad);
        return room - (at - start[y * w + x0]);  // the row's padding
    };
    std::size_t new_padding = 0;
    auto p = points.cbegin();
    if (fits) {
        for (std::size_t y = g0; y < g1; ++y)
            new_padding += place_row(y, start[y * w + x0], start[y * w + x1] - start[y * w + x0], p);
    } else {
        // The span [first, last): each lists row with room for twice its
        // count (or its old room), the columns between copied less padding.
        const std::size_t first = g0 * w + x0, last = (g1 - 1) * w + x1;
        thread_local std::vector<OccluderMap::Shown> between;  // the other columns' lists, in order
        thread_local std::vector<std::uint32_t> between_count, rooms;
        between.clear();
        between_count.assign(last - first, 0);
        rooms.assign(g1 - g0, 0);
        std::size_t total = 0;
        for (std::size_t g = first; g < last; ++g) {
            const std::size_t x = g % w;
            if (x == x0) {
                const std::size_t y = g / w;
                const std::uint32_t old_room = start[y * w + x1] - start[g], need = counts[y - g0];
                rooms[y - g0] = need <= old_room ? old_room : 2 * need;
                total += rooms[y - g0];
                g = y * w + x1 - 1;
                continue;
            }
            const std::size_t before = between.size();
            for (std::uint32_t k = start[g]; k < start[g + 1]; ++k)
                if (m.shown[k].rows != unlisted) between.push_back(m.shown[k]);
                else ++old_padding;
            between_count[g - first] = std::uint32_t(between.size() - before);
            total += between.size() - before;
        }
        const std::size_t had = start[last] - start[first];
        if (total > had) {
            const std::size_t grow = total - had;
            if (m.shown.size() + grow >= std::numeric_limits<std::uint32_t>::max())
                throw Error("occluders: the region's sprite points are too many to trace against solids");
            m.shown.insert(m.shown.begin() + std::ptrdiff_t(start[last]), grow, pad);
            for (std::size_t g = last; g < start.size(); ++g) start[g] += std::uint32_t(grow);
        }
        std::uint32_t at = start[first];
        std::size_t b = 0;
        for (std::size_t g = first; g < last; ++g) {
            const std::size_t x = g % w;
            if (x == x0) {
                const std::size_t y = g / w;
                new_padding += place_row(y, at, rooms[y - g0], p);
                at += rooms[y - g0];
                g = y * w + x1 - 1;
                continue;
            }
            start[g] = at;
            std::copy_n(between.begin() + std::ptrdiff_t(b), between_count[g - first], m.shown.begin() + at);
            b += between_count[g - first];
            at += between_count[g - first];
        }
        // What is left before the entries after the span: the last row's padding.
        std::fill(m.shown.begin() + at, m.shown.begin() + start[last], pad);
        new_padding += start[last] - at;
    }
    m.padding = m.padding - old_padding + new_padding;
    // 4. The tallest point: higher if the lists' is; lower only when every
    // one of the old tallest's entries was among the lists' (then sought).
    m.reach_rows = std::max(m.reach_rows, int(reach));
    if (int(new_tallest) >= m.tallest) {
        m.tallest = int(new_tallest);
    } else if (lost_tallest > 0) {
        std::uint32_t tallest = 0;
        for (const OccluderMap::Shown& e : m.shown)
            if (e.rows != unlisted) tallest = std::max(tallest, e.rows);
        m.tallest = int(tallest);
    }
    if (m.padding > m.shown.size() / 2) drop_padding(m);  // edits all over: compacted now and then
}

}  // namespace

const SpriteSolids& cached_solids(SolidsCache& cache, const Tileset& tileset, std::size_t index, const Params& p) {
    if (cache.made.size() != tileset.sprites.size()) {
        cache.sprites.assign(tileset.sprites.size(), SpriteSolids{});
        cache.made.assign(tileset.sprites.size(), 0);
    }
    if (!cache.made[index]) {
        cache.sprites[index] = sprite_solids(tileset, tileset.sprites[index], p);
        cache.made[index] = 1;
    }
    return cache.sprites[index];
}

void reindex_part(OccluderMap& m, Rect part) {
    part = intersect(part, m.rect);
    if (m.flags.size() != m.spans.size()) return index_occluders(m);  // never indexed
    if (part.empty()) return;
    relist_shown(m, intersect(m.rect, Rect{part.x, part.y, part.w, part.h + m.reach_rows}));
}

void index_occluders(OccluderMap& m) {
    m.flags.resize(m.surface.instance.size());
    flag_spans(m, m.rect);
    index_shown(m);
}

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
    // Part r built and copied in, reach_rows grown by its sprite pixels' heights.
    auto build_part = [&](Rect r) {
        OccluderMap part;
        fill_occluders(part, world, p, r, cache);
        copy_part(m, part, r);
        for (std::size_t i = 0; i < part.surface.instance.size(); ++i)
            if (part.surface.instance[i] >= 0)
                m.reach_rows = std::max(m.reach_rows, int(rows_above(std::max(part.surface.height[i], 0.f))));
    };
    // An edit in place: its part built, and only the lists it can change
    // (its columns, from its top to reach_rows below its bottom, where its
    // sprite pixels' points land) listed again, in place (relist_shown).
    const Rect edited = intersect(changed, region);
    if (!edited.empty() && region == m.rect) {
        build_part(edited);
        relist_shown(m, intersect(region, Rect{edited.x, edited.y, edited.w, edited.h + m.reach_rows}));
        return;
    }
    // A pan: the parts that came into the region built, and what the world
    // changed.
    pan_occluder_map(m, region, keep, edited.empty() ? std::vector<Rect>{} : std::vector<Rect>{edited}, build_part);
}

void pan_occluder_map(OccluderMap& m, Rect to, Rect keep, const std::vector<Rect>& changed,
                      const std::function<void(Rect)>& make) {
    // The old lists trade places with the last pan's (their storage kept
    // per thread).
    drop_padding(m);
    thread_local KeptIndex kept;
    kept.rect = m.rect;
    kept.unchanged = {keep};
    kept.anew.clear();
    kept.start.swap(m.shown_start);
    kept.shown.swap(m.shown);
    move_grid(m.spans, m.rect, to);
    move_grid(m.surface.instance, m.rect, to, -1);
    move_grid(m.surface.height, m.rect, to);
    move_grid(m.flags, m.rect, to);
    m.rect = m.surface.rect = to;
    keep = intersect(keep, to);
    std::vector<Rect> parts = keep.empty() ? std::vector<Rect>{to} : outside(to, keep);
    parts.insert(parts.end(), changed.begin(), changed.end());
    for (Rect r : parts) make(r);
    // The lists that cannot change after a pan: all but the rows below the
    // kept part's top where anything above it was made or dropped, within
    // reach of the sprites there. A pan and a change at once: listed whole.
    if (!changed.empty()) {
        index_shown(m);
    } else {
        if (keep.y > to.y || keep.y > kept.rect.y) {
            const int top = keep.y + m.reach_rows;
            kept.unchanged = {intersect(keep, Rect{keep.x, top, keep.w, std::max(0, keep.y + keep.h - top)})};
        }
        kept.anew = kept.unchanged[0].empty() ? std::vector<Rect>{to} : outside(to, kept.unchanged[0]);
        index_shown(m, &kept);
    }
    // A large map's spare lists are not kept past the update.
    if (kept.start.capacity() * sizeof(std::uint32_t) + kept.shown.capacity() * sizeof(OccluderMap::Shown) > kept_spare_bytes)
        kept = KeptIndex{};
}

}  // namespace isolux
