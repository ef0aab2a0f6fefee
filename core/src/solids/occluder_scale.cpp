// The occluders' resolution as a knob (occluder_map.hpp, Params::occluder_scale):
// the coarse map, the coarse light of a fine one, and the fine mask taken
// back from the coarse answer.
#include <algorithm>
#include <cassert>
#include <cstdlib>
#include <vector>

#include "isolux/occluder_map.hpp"
#include "solids/occluder_index.hpp"

namespace isolux {

namespace {

// floor(v / s) for s > 0, negative v included (world pixels may be negative).
int floor_div(std::int64_t v, int s) { return int(v >= 0 ? v / s : -((-v + s - 1) / s)); }

// The coarse rectangle covering fine rectangle r.
Rect cover(Rect r, int s) {
    const int x0 = floor_div(r.x, s), y0 = floor_div(r.y, s);
    const int x1 = floor_div(std::int64_t(r.x) + r.w - 1, s), y1 = floor_div(std::int64_t(r.y) + r.h - 1, s);
    return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

constexpr int border = 2;  // coarse pixels of bare ground all round: the coarse light's a / s + 1, and the tallest point's rounding

Rect coarse_rect_of(Rect fine, int s) {
    const Rect covered = cover(fine, s);
    return {covered.x - border, covered.y - border, covered.w + 2 * border, covered.h + 2 * border};
}

// The blocks of `blocks` (coarse pixels, inside c.rect, starting empty)
// made from the fine map: the union of their pixels' spans, over s, and
// their top-left pixel's surface, its height over s.
void fill_blocks(OccluderMap& c, const OccluderMap& fine, int s, Rect blocks) {
    const Rect part = intersect(Rect{blocks.x * s, blocks.y * s, blocks.w * s, blocks.h * s}, fine.rect);
    if (part.empty()) return;
    const float inv = 1.0f / float(s);
    const bool has_surface = fine.surface.instance.size() == std::size_t(fine.rect.w) * std::size_t(fine.rect.h);
    const int X0 = floor_div(part.x, s), first_in_block = part.x - X0 * s;
    for (int y = part.y; y < part.y + part.h; ++y) {
        const int cy = floor_div(y, s);
        const bool top_row = std::int64_t(cy) * s == y;
        const std::size_t from = std::size_t(y - fine.rect.y) * std::size_t(fine.rect.w) + std::size_t(part.x - fine.rect.x);
        const std::size_t to = std::size_t(cy - c.rect.y) * std::size_t(c.rect.w) + std::size_t(X0 - c.rect.x);
        // The block's column kept as x steps (no division a pixel).
        int in_block = first_in_block;
        std::size_t j = 0;
        for (int i = 0; i < part.w; ++i) {
            const Spans& sp = fine.spans[from + std::size_t(i)];
            if (sp.lower.any()) c.spans[to + j].add(sp.lower.low * inv, sp.lower.high * inv);
            if (sp.upper.any()) c.spans[to + j].add(sp.upper.low * inv, sp.upper.high * inv);
            if (has_surface && top_row && in_block == 0) {
                c.surface.instance[to + j] = fine.surface.instance[from + std::size_t(i)];
                c.surface.height[to + j] = fine.surface.height[from + std::size_t(i)] * inv;
            }
            if (++in_block == s) in_block = 0, ++j;
        }
    }
}

// The blocks of `blocks` (inside c.rect) made again from the fine map: their
// spans, surface and has_span flags; reach_rows grown by their heights.
void remake_blocks(OccluderMap& c, const OccluderMap& fine, int s, Rect blocks) {
    for (int y = blocks.y; y < blocks.y + blocks.h; ++y) {
        const std::size_t i = std::size_t(y - c.rect.y) * std::size_t(c.rect.w) + std::size_t(blocks.x - c.rect.x);
        std::fill_n(&c.spans[i], blocks.w, Spans{});
        std::fill_n(&c.surface.instance[i], blocks.w, std::int32_t(-1));
        std::fill_n(&c.surface.height[i], blocks.w, 0.0f);
    }
    fill_blocks(c, fine, s, blocks);
    for (int y = blocks.y; y < blocks.y + blocks.h; ++y)
        for (int x = blocks.x; x < blocks.x + blocks.w; ++x) {
            const std::size_t i = std::size_t(y - c.rect.y) * std::size_t(c.rect.w) + std::size_t(x - c.rect.x);
            c.flags[i] = std::uint8_t(c.spans[i].any() ? OccluderMap::has_span : 0);
            if (c.surface.instance[i] >= 0)
                c.reach_rows = std::max(c.reach_rows, int(rows_above(std::max(c.surface.height[i], 0.f))));
        }
}

// The blocks lying wholly inside fine rectangle r.
Rect blocks_inside(Rect r, int s) {
    if (r.empty()) return {};
    const int x0 = -floor_div(-std::int64_t(r.x), s), y0 = -floor_div(-std::int64_t(r.y), s);  // ceil
    const int x1 = floor_div(std::int64_t(r.x) + r.w, s), y1 = floor_div(std::int64_t(r.y) + r.h, s);
    return x1 > x0 && y1 > y0 ? Rect{x0, y0, x1 - x0, y1 - y0} : Rect{};
}

}  // namespace

OccluderMap coarse_occluders(const OccluderMap& fine, int s) {
    assert(s >= 1);
    OccluderMap c;
    if (fine.rect.empty()) return c;
    c.rect = coarse_rect_of(fine.rect, s);
    const std::size_t n = std::size_t(c.rect.w) * std::size_t(c.rect.h);
    c.spans.assign(n, Spans{});
    c.surface.rect = c.rect;
    c.surface.instance.assign(n, -1);
    c.surface.height.assign(n, 0.0f);
    fill_blocks(c, fine, s, c.rect);
    index_occluders(c);
    return c;
}

Params coarse_params(const Params& p) {
    Params c = p;
    c.falloff_scale = 1e6;  // the largest accepted: 254 or 255 wherever lit, never 0
    c.occluder_scale = 1;
    return c;
}

void start_coarse_mask(LightMask& coarse, const LightMask& fine, int s, const Params& coarse_p) {
    const int a = fine.a / s + 1, b = fine.b / s + 1;
    const std::int64_t cx = floor_div(fine.cx, s), cy = floor_div(fine.cy, s);
    const Rect area{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
    const Rect clip = fine.clip.empty() ? Rect{} : intersect(cover(fine.clip, s), area);
    start_mask(coarse, cx, cy, a, b, coarse_p, clip, coarse_p.mode == Mode::shadow);
}

namespace {

// A fine pixel's choice among its block (0) and the block's neighbours: the
// block first, then the four sides, then the corners.
constexpr int pick_dx[9] = {0, 0, -1, 1, 0, -1, 1, -1, 1};
constexpr int pick_dy[9] = {0, -1, 0, 0, 1, -1, -1, 1, 1};

// The picks of the fine pixels of `part` (inside fine.rect).
void pick_pixels(std::vector<std::uint8_t>& picks, const Surface& fine, const OccluderMap& coarse, int s, Rect part) {
    const Surface& cs = coarse.surface;
    const float inv = 1.0f / float(s);
    const int X0 = floor_div(part.x, s), first_in_block = part.x - X0 * s;
    for (int y = part.y; y < part.y + part.h; ++y) {
        const int Y = floor_div(y, s);
        const std::size_t row = std::size_t(y - fine.rect.y) * std::size_t(fine.rect.w) + std::size_t(part.x - fine.rect.x);
        const std::size_t block_row = std::size_t(Y - cs.rect.y) * std::size_t(cs.rect.w);
        int X = X0, in_block = first_in_block;
        for (int i = 0; i < part.w; ++i) {
            const std::int32_t shows = fine.instance[row + std::size_t(i)];
            const float h = fine.height[row + std::size_t(i)] * inv;
            const std::size_t block = block_row + std::size_t(X - cs.rect.x);
            std::uint8_t pick = 0;
            // Most pixels show what their block shows at its height (the
            // ground's 0 above all): the block, with no search.
            if (!(cs.instance[block] == shows && cs.height[block] == h)) {
                int best = -1;
                float best_gap = 0;
                for (int k = 0; k < 9 && !(best >= 0 && best_gap == 0); ++k) {  // none nearer than 0: ties keep the first
                    const int u = X + pick_dx[k], v = Y + pick_dy[k];
                    if (!cs.rect.contains(u, v)) continue;
                    const std::size_t j = std::size_t(v - cs.rect.y) * std::size_t(cs.rect.w) + std::size_t(u - cs.rect.x);
                    if (cs.instance[j] != shows) continue;
                    const float gap = std::abs(cs.height[j] - h);
                    if (best < 0 || gap < best_gap) best = k, best_gap = gap;
                }
                pick = std::uint8_t(std::max(best, 0));
            }
            picks[row + std::size_t(i)] = pick;
            if (++in_block == s) in_block = 0, ++X;
        }
    }
}

}  // namespace

std::vector<std::uint8_t> coarse_picks(const Surface& fine, const OccluderMap& coarse, int s) {
    std::vector<std::uint8_t> picks(fine.instance.size(), 0);
    pick_pixels(picks, fine, coarse, s, fine.rect);
    return picks;
}

void pan_coarse_occluders(OccluderMap& c, std::vector<std::uint8_t>& picks, const OccluderMap& fine, Rect old_fine,
                          int s) {
    // The blocks wholly inside the part both fine maps hold are the same
    // blocks: kept, moved to the new layout; the rest made again.
    // Their sprite index too, but for the rows within reach below the kept
    // blocks' top (pan_occluder_map).
    const Rect inner = blocks_inside(intersect(old_fine, fine.rect), s);
    const Rect to = coarse_rect_of(fine.rect, s);
    pan_occluder_map(c, to, inner, {}, [&](Rect r) { remake_blocks(c, fine, s, r); });
    // A pixel's pick reads its block and the eight around it: kept where
    // all nine are kept blocks.
    const Rect same = inner.w > 2 && inner.h > 2 ? Rect{(inner.x + 1) * s, (inner.y + 1) * s, (inner.w - 2) * s, (inner.h - 2) * s}
                                                 : Rect{};
    move_grid(picks, old_fine, fine.rect, std::uint8_t(0));
    const Rect kept = intersect(same, fine.rect);
    for (const Rect& r : kept.empty() ? std::vector<Rect>{fine.rect} : outside(fine.rect, kept))
        pick_pixels(picks, fine.surface, c, s, r);
}

void edit_coarse_occluders(OccluderMap& c, std::vector<std::uint8_t>& picks, const OccluderMap& fine, Rect changed,
                           int s) {
    // The blocks that hold a changed pixel, made again; then their index.
    const Rect blocks = intersect(cover(intersect(changed, fine.rect), s), c.rect);
    if (blocks.empty()) return;
    remake_blocks(c, fine, s, blocks);
    reindex_part(c, blocks);
    // A fine pixel's pick reads its block and the eight around it.
    const Rect near{(blocks.x - 1) * s, (blocks.y - 1) * s, (blocks.w + 2) * s, (blocks.h + 2) * s};
    if (picks.size() == fine.surface.instance.size()) pick_pixels(picks, fine.surface, c, s, intersect(near, fine.rect));
    else picks = coarse_picks(fine.surface, c, s);
}

void upsample_mask(LightMask& fine, const LightMask& coarse, int s, const Params& p, const Surface* fine_surface,
                   const std::vector<std::uint8_t>* picks) {
    if (p.mode == Mode::shadow) fine.reached.assign(fine.value.size(), 1);
    const Rect area = intersect(Rect{int(fine.cx) - fine.a, int(fine.cy) - fine.b, 2 * fine.a + 1, 2 * fine.b + 1}, fine.clip);
    if (area.empty()) return;
    thread_local std::vector<std::uint8_t> table;
    table.resize(std::size_t(std::max(fine.a, fine.b)) + 1);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), p.falloff_scale);
    const bool by_surface = fine_surface && picks && picks->size() == fine_surface->instance.size();
    const Rect& fr = by_surface ? fine_surface->rect : Rect{};
    const std::uint32_t cw = std::uint32_t(coarse.clip.w), ch = std::uint32_t(coarse.clip.h);
    for (int y = area.y; y < area.y + area.h; ++y) {
        const int Y = floor_div(y, s);
        const std::size_t dy = std::size_t(std::llabs(std::int64_t(y) - fine.cy));
        std::uint8_t* to = fine.value.data() + std::size_t(y - fine.clip.y) * std::size_t(fine.clip.w);
        assert(Y >= coarse.clip.y && Y < coarse.clip.y + coarse.clip.h);
        const bool row_picks = by_surface && y >= fr.y && y < fr.y + fr.h;
        const std::uint8_t* pick = row_picks ? picks->data() + std::size_t(y - fr.y) * std::size_t(fr.w) : nullptr;
        // The row's pixels with a pick (inside the fine surface), [p0, p1).
        const int p0 = row_picks ? std::max(area.x, fr.x) : area.x, p1 = row_picks ? std::min(area.x + area.w, fr.x + fr.w) : area.x;
        const std::uint8_t* from = coarse.value.data() + std::size_t(Y - coarse.clip.y) * cw;
        const int v = Y - coarse.clip.y;
        // The block's column kept as x steps (no division a pixel).
        int X = floor_div(area.x, s), in_block = area.x - X * s;
        for (int x = area.x; x < area.x + area.w; ++x) {
            int u = X - coarse.clip.x;
            const std::uint8_t* row = from;
            if (x >= p0 && x < p1) {
                // The picked neighbour, or the block where it lies past the coarse clip.
                const int k = pick[x - fr.x];
                const int pu = u + pick_dx[k], pv = v + pick_dy[k];
                if (std::uint32_t(pu) < cw && std::uint32_t(pv) < ch) u = pu, row = from + std::ptrdiff_t(pick_dy[k]) * std::ptrdiff_t(cw);
            }
            const std::size_t d = std::max(dy, std::size_t(std::llabs(std::int64_t(x) - fine.cx)));
            to[x - fine.clip.x] = row[u] ? table[d] : 0;
            if (++in_block == s) in_block = 0, ++X;
        }
    }
}

void trace_solids_at_scale(LightMask& fine, const OccluderMap& coarse, int s, double height, const Params& p,
                           bool sprite_points, int threads, const Surface* fine_surface,
                           const std::vector<std::uint8_t>* picks) {
    const Params cp = coarse_params(p);
    thread_local LightMask c;
    start_coarse_mask(c, fine, s, cp);
    if (!c.clip.empty()) {
        const double H = std::max(height, 0.0) / s;
        c = trace_light_solids(coarse, c.cx, c.cy, c.a, c.b, H, cp, c.clip, threads);
        if (sprite_points) light_sprite_points(c, coarse, H, cp, threads);
    }
    upsample_mask(fine, c, s, p, fine_surface, picks);
}

}  // namespace isolux
