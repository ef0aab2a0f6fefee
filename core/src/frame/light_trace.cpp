// Paper 3.2, Algorithm 2: the adapted Bresenham. Rays go from the light's
// centre to the border of its a x b area (or to every pixel of it), drawing
// pixels from the centre outward and halting at the first obstacle pixel.
#include "isolux/light_trace.hpp"

#include <cassert>
#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <tuple>
#include <utility>

#include "base/bounded_cache.hpp"
#include "base/huge_pages.hpp"
#include "frame/ray_tree.hpp"
#include "base/rows_ahead.hpp"
#include "frame/trace_hooks.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace isolux {

namespace {
int sign(std::int64_t v) { return (v > 0) - (v < 0); }

// Obstacle lookup in 64-bit coordinates: a ray may run far outside int range.
bool blocked_at(const Mask& m, std::int64_t x, std::int64_t y) {
    x -= m.x0;
    y -= m.y0;
    return x >= 0 && y >= 0 && x < m.width && y < m.height && m.bits[std::size_t(y) * m.width + std::size_t(x)];
}
}  // namespace

BresenhamRay::BresenhamRay(std::int64_t x0, std::int64_t y0, std::int64_t x1, std::int64_t y1) : x(x0), y(y0) {
    const std::int64_t w = x1 - x0, h = y1 - y0;
    // The paper writes "if (w < 0) dx1 = -1; dx2 = -1; else ..." without
    // braces; the Bresenham it adapts sets both dx1 and dx2 to sign(w).
    dx1 = dx2 = sign(w);
    dy1 = sign(h);
    longest = std::llabs(w);
    shortest = std::llabs(h);
    if (!(longest > shortest)) {
        longest = std::llabs(h);
        shortest = std::llabs(w);
        dx2 = 0;
        dy2 = sign(h);
    }
    numerator = longest >> 1;
}

std::uint8_t falloff(std::int64_t d, double falloff_scale) {
    assert(d >= 0 && falloff_scale > 0);
    if (falloff_scale == 1.0) return std::uint8_t(255 / (1 + d));  // the paper's integer function
    double v = 255.0 / (1.0 + double(d) / falloff_scale);
    return std::uint8_t(std::min(255.0, v));
}

namespace {
// A light's distance d for offsets |dx|, |dy| under the falloff shape, |dy|
// counted dy_scale times (the ground's r, or 1 on the screen).
double shaped_distance(double ax, double ay, const Params& p, double dy_scale) {
    const double gy = ay * dy_scale;
    return p.falloff_shape == FalloffShape::euclidean ? std::sqrt(ax * ax + gy * gy) : std::max(ax, gy);
}
}  // namespace

std::uint8_t shaped_falloff(std::int64_t dx, std::int64_t dy, int a, int b, const Params& p, double dy_scale) {
    if (!p.edge_fade) {
        if (p.falloff_shape == FalloffShape::chebyshev && dy_scale == 1.0)
            return falloff(std::max(std::llabs(dx), std::llabs(dy)), p.falloff_scale);  // the paper's integers
        const double d = shaped_distance(double(std::llabs(dx)), double(std::llabs(dy)), p, dy_scale);
        return std::uint8_t(255.0 / (1.0 + d / p.falloff_scale));
    }
    return std::uint8_t(faded_intensity(double(std::llabs(dx)), double(std::llabs(dy)), a, b, p, dy_scale));
}

double faded_intensity(double dx, double dy, int a, int b, const Params& p, double dy_scale) {
    const double ax = std::abs(dx), ay = std::abs(dy);
    const bool round = p.falloff_shape == FalloffShape::euclidean;
    const double d = shaped_distance(ax, ay, p, dy_scale);
    // The share of the way to the border: an ellipse for round lights, the rectangle for square ones.
    const double u = ax / (a + 1.0), v = ay / (b + 1.0);
    const double t = std::min(1.0, round ? std::sqrt(u * u + v * v) : std::max(u, v));
    // smooth: 1 - smoothstep(t), whose slope is 0 at the border, where the
    // linear fade's kink reads as a ring on bright ground.
    const double fade = p.fade_curve == FadeCurve::smooth ? 1.0 - t * t * (3.0 - 2.0 * t) : 1.0 - t;
    return 255.0 / (1.0 + d / p.falloff_scale) * fade;
}

double falloff_dy_scale(const Params& p, int tile_width, int tile_height) {
    if (p.falloff_space == FalloffSpace::screen || tile_width <= 0 || tile_height <= 0) return 1.0;
    return double(tile_width) / double(tile_height);
}

void shape_light(LightMask& m, const Params& p) {
    for (int y = 0; y < m.clip.h; ++y)
        for (int x = 0; x < m.clip.w; ++x) {
            std::uint8_t& v = m.value[std::size_t(y) * m.clip.w + x];
            if (v) v = shaped_falloff(m.clip.x + x - m.cx, m.clip.y + y - m.cy, m.a, m.b, p, m.dy_scale);
        }
}

std::vector<std::pair<int, int>> border_offsets(int a, int b) {
    std::vector<std::pair<int, int>> out;
    for (int x = -a; x <= a; ++x) out.push_back({x, -b});                // top, left to right
    for (int y = -b + 1; y <= b; ++y) out.push_back({a, y});             // right, downward
    if (b > 0)
        for (int x = a - 1; x >= -a; --x) out.push_back({x, b});         // bottom, right to left
    if (a > 0)
        for (int y = b - 1; y >= -b + 1; --y) out.push_back({-a, y});    // left, upward
    return out;
}

bool area_is_clear(const Mask& obstacles, Rect area) {
    const Rect r = intersect(area, obstacles.rect());
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::uint8_t* row = &obstacles.bits[std::size_t(y - obstacles.y0) * obstacles.width + (r.x - obstacles.x0)];
        if (std::memchr(row, 1, std::size_t(r.w))) return false;  // glibc's vectorised search
    }
    return true;
}

std::uint64_t& bresenham_steps() {
    thread_local std::uint64_t steps = 0;
    return steps;
}

TreeTraces& tree_traces() {
    thread_local TreeTraces counts;
    return counts;
}

namespace {

// One ray from the centre, stepping two pointers (obstacle map, mask) with
// the paper's Bresenham decisions. Returns the steps taken.
// Step i of a ray is at distance d = i (the major axis gains one a step).
template <Mode M>
std::int64_t trace_fast(const std::uint8_t* ob, std::ptrdiff_t ob_stride, const std::uint8_t* table, std::uint8_t* lit,
                        std::uint8_t* reached, std::ptrdiff_t lit_stride, std::int64_t w, std::int64_t h) {
    const int sx = sign(w), sy = sign(h);
    std::int64_t longest = std::llabs(w), shortest = std::llabs(h);
    int dx2 = sx, dy2 = 0;
    if (!(longest > shortest)) {
        std::swap(longest, shortest);
        dx2 = 0;
        dy2 = sy;
    }
    const std::ptrdiff_t ob_diag = sy * ob_stride + sx, ob_straight = dy2 * ob_stride + dx2;
    const std::ptrdiff_t lit_diag = sy * lit_stride + sx, lit_straight = dy2 * lit_stride + dx2;
    std::int64_t numerator = longest >> 1;
    std::ptrdiff_t at_ob = 0, at_lit = 0;
    std::int64_t i = 0;
    for (; i <= longest; ++i) {
        if (M != Mode::flat && ob[at_ob]) break;
        lit[at_lit] = table[i];
        if (M == Mode::shadow) reached[at_lit] = 1;
        numerator += shortest;
        const bool diag = !(numerator < longest);
        numerator -= diag ? longest : 0;
        at_ob += diag ? ob_diag : ob_straight;
        at_lit += diag ? lit_diag : lit_straight;
    }
    if (M == Mode::shadow) {
        // Beyond the first obstacle: reached, not lit.
        for (; i <= longest; ++i) {
            reached[at_lit] = 1;
            numerator += shortest;
            const bool diag = !(numerator < longest);
            numerator -= diag ? longest : 0;
            at_lit += diag ? lit_diag : lit_straight;
        }
    }
    return i;
}

}  // namespace

namespace {

// A tree's values for one falloff scale, kept per (a, b, k, scale) like the
// trees (within 128 MiB). `node`: each node's `word`, its index in an
// area-sized buffer (from the top-left, never negative) times 256 plus its
// falloff (table[depth]), so a walk step is one load and one shift (indices
// fit: 1025 * 1025 < 2^24), and beside it the node's subtree end, so that an
// obstacle's end is on the cache line the walk just read (from the tree's own
// array it was a miss: 30% of the walk by perf). `clear`: the mask with
// nothing in the way, each pixel some ray reaches at its falloff.
struct WalkNode {
    std::uint32_t word;
    std::int32_t end;
};
struct TreeValues {
    std::vector<WalkNode> node;
    std::vector<std::uint8_t> clear;
};
std::shared_ptr<const TreeValues> tree_values(const RayTree& tree, int a, int b, int k,
                                              const std::vector<std::uint8_t>& table, double scale) {
    static BoundedCache<std::tuple<int, int, int, double>, TreeValues> cache(std::size_t(128) << 20);
    auto build = [&] {
        auto v = std::make_shared<TreeValues>();
        assign_huge(v->node, tree.depth.size());
        assign_huge(v->clear, tree.pixel_start.size() - 1);
        const std::int32_t centre = b * (2 * a + 1) + a;
        for (std::size_t i = 0; i < tree.depth.size(); ++i) {
            const std::uint32_t at = std::uint32_t(centre + tree.offset[i]);
            v->node[i] = {at << 8 | table[tree.depth[i]], tree.end[i]};
            v->clear[at] = table[tree.depth[i]];
        }
        return v;
    };
    return cache.get({a, b, k, scale}, build,
                     [](const TreeValues& v) { return vector_bytes(v.node) + vector_bytes(v.clear); });
}

constexpr int max_tree_extent = 512;  // larger areas trace ray by ray (the tree would be too big to keep)

// Walks the tree over an area-local copy of the obstacles (`ob`, the same
// layout as the mask), so one index serves both. Returns the nodes visited
// (pruned subtrees are skipped). Kept out of line and lean: it is most of a
// dense scene's tracing (inlined into trace_light, its pointers were spilled
// and reloaded at every node).
template <Mode M>
[[gnu::noinline]] std::int64_t walk_tree(const WalkNode* __restrict node, std::int32_t n, const std::uint8_t* __restrict ob,
                                         std::uint8_t* __restrict value, std::uint8_t* __restrict reached) {
    std::int64_t skipped = 0;
    const WalkNode* at = node;
    const WalkNode* const stop = node + n;
    while (at < stop) {
        if (M == Mode::light) {
            // Four nodes at a time while none is an obstacle (about one node
            // in 200 is, in the default map): one branch per four, not one
            // per node; the loop was bound by its instructions, not by memory.
            while (at + 4 <= stop) {
                const std::uint32_t w0 = at[0].word, w1 = at[1].word, w2 = at[2].word, w3 = at[3].word;
                const std::size_t o0 = w0 >> 8, o1 = w1 >> 8, o2 = w2 >> 8, o3 = w3 >> 8;
                if (ob[o0] | ob[o1] | ob[o2] | ob[o3]) break;
                value[o0] = std::uint8_t(w0);
                value[o1] = std::uint8_t(w1);
                value[o2] = std::uint8_t(w2);
                value[o3] = std::uint8_t(w3);
                at += 4;
            }
            if (at >= stop) break;
        }
        const std::uint32_t w = at->word;
        const std::size_t o = w >> 8;
        if (ob[o]) {
            const WalkNode* const end = node + at->end;
            if (M == Mode::shadow)  // this pixel and every one behind it on these rays
                for (const WalkNode* j = at; j < end; ++j) reached[j->word >> 8] = 1;
            skipped += end - at - 1;
            at = end;
            continue;
        }
        value[o] = std::uint8_t(w);
        if (M == Mode::shadow) reached[o] = 1;
        ++at;
    }
    return n - skipped;
}

// The nodes at obstacle pixels: the sum of `nodes` (each pixel's node
// count) where `ob` is 1 (bytes 0 or 1), sixteen pixels a step (SSE2's sum
// of absolute differences adds bytes without widening them first).
std::size_t obstacle_nodes(const std::uint8_t* ob, const std::uint8_t* nodes, std::size_t w) {
    std::size_t sum = 0, x = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    __m128i acc = zero;
    for (; x + 16 <= w; x += 16) {
        const __m128i o = _mm_loadu_si128(reinterpret_cast<const __m128i*>(ob + x));
        const __m128i k = _mm_loadu_si128(reinterpret_cast<const __m128i*>(nodes + x));
        acc = _mm_add_epi64(acc, _mm_sad_epu8(_mm_and_si128(k, _mm_sub_epi8(zero, o)), zero));
    }
    sum = std::size_t(_mm_cvtsi128_si64(acc)) + std::size_t(_mm_cvtsi128_si64(_mm_unpackhi_epi64(acc, acc)));
#endif
    for (; x < w; ++x) sum += ob[x] ? nodes[x] : 0;
    return sum;
}

// The obstacle pixels of ob[0, pixels) (bytes 0 or 1), in order, sixteen
// bytes a step: a step with no obstacle is a compare and a branch. (By
// memchr per row and per obstacle, the listing took 14 us of a pruned light.)
[[gnu::noinline]] void obstacle_pixels(const std::uint8_t* ob, std::size_t pixels, std::vector<std::uint32_t>& out) {
    out.clear();
    std::size_t p = 0;
#if defined(__SSE2__)
    const __m128i zero = _mm_setzero_si128();
    for (; p + 16 <= pixels; p += 16)
        for (unsigned hits = unsigned(_mm_movemask_epi8(_mm_cmpgt_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(ob + p)), zero)));
             hits; hits &= hits - 1)
            out.push_back(std::uint32_t(p + std::size_t(__builtin_ctz(hits))));
#endif
    for (; p < pixels; ++p)
        if (ob[p]) out.push_back(std::uint32_t(p));
}

// The same bytes from the other side, for areas with few obstacles: start
// from the clear mask and darken only what the obstacles cut off. The walk
// prunes the subtree of every obstacle node it meets, [j, end[j]); those are
// exactly the outermost of all obstacle nodes' subtrees (depth-first
// subtrees nest or are disjoint). A pixel stays lit unless every one of its
// nodes lies in them. In shadow mode every node is reached, pruned or not.
// Costs about one walk step per pruned node instead of per visited node;
// gives up (returns -1, nothing written) when that would not pay.
std::int64_t prune_tree(const RayTree& t, const TreeValues& v, const std::uint8_t* ob, int w, int h, std::uint8_t* value,
                        std::uint8_t* reached) {
    if (!t.prunable) return -1;
    thread_local std::vector<std::int32_t> cut;
    thread_local std::vector<std::uint8_t> left;  // per pixel: its nodes not yet found cut off
    const std::int32_t n = std::int32_t(t.end.size());
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    const std::size_t most = std::size_t(n) / 256;  // beyond, sorting the cuts costs more than it saves
    // 1. Dense areas give up first, having only counted their obstacle nodes
    // (a vector pass: listing them one by one to give up at the same count
    // took a fifth of a walk).
    std::size_t count = 0;
    for (std::size_t p = 0; p < pixels; p += 4096) {
        const std::size_t len = std::min<std::size_t>(4096, pixels - p);
        count += obstacle_nodes(ob + p, &t.nodes_at[p], len);
        if (count > most) return -1;  // dense: the walk is cheaper
    }
    // 2. The obstacle nodes listed. The tree's arrays are large and read
    // here at random (one place per obstacle pixel, one per node): each
    // round of reads is asked for first, so that their trips to memory
    // overlap (one after the other they were most of a pruned light).
    thread_local std::vector<std::uint32_t> hit;
    obstacle_pixels(ob, pixels, hit);
    for (const std::uint32_t p : hit) __builtin_prefetch(&t.pixel_start[p]);
    for (const std::uint32_t p : hit) __builtin_prefetch(&t.pixel_nodes[std::size_t(t.pixel_start[p])]);
    cut.clear();
    for (const std::uint32_t p : hit)
        cut.insert(cut.end(), t.pixel_nodes.begin() + t.pixel_start[p], t.pixel_nodes.begin() + t.pixel_start[p + 1]);
    for (const std::int32_t j : cut) __builtin_prefetch(&v.node[std::size_t(j)]);
    // 3. The outermost of their subtrees, and how many nodes they cut (each
    // node's subtree end read beside its word, on the line just asked for).
    std::sort(cut.begin(), cut.end());
    std::size_t kept = 0;
    std::int64_t skipped = 0;
    for (const std::int32_t j : cut)
        if (kept == 0 || j >= v.node[std::size_t(cut[kept - 1])].end) {
            cut[kept++] = j;
            skipped += v.node[std::size_t(j)].end - j - 1;
        }
    cut.resize(kept);
    if (skipped > n - skipped) return -1;  // most of the tree is cut off: the walk is cheaper
    // 4. The clear mask, then every pixel whose last node is cut off goes dark.
    std::memcpy(value, v.clear.data(), pixels);
    if (reached)
        for (std::size_t i = 0; i < pixels; ++i) reached[i] = t.nodes_at[i] != 0;
    left.assign(t.nodes_at.begin(), t.nodes_at.end());
    // (Plain pointers: through the vectors, each byte stored to `value`
    // might have moved them, and every step reloaded a thread_local's data.)
    std::uint8_t* const to_find = left.data();
    const WalkNode* const node = v.node.data();
    for (const std::int32_t first : cut)
        for (std::int32_t j = first, last = node[first].end; j < last; ++j) {
            const std::size_t p = node[j].word >> 8;
            if (--to_find[p] == 0) value[p] = 0;
        }
    return n - skipped;
}

// Rows [0, h) of `w` bytes from `from` (rows `stride` apart) into `to`,
// contiguous: rows of a world-wide array, asked for ahead (rows_ahead.hpp).
void copy_area_rows(const std::uint8_t* from, std::ptrdiff_t stride, int w, int h, std::uint8_t* to) {
    for (int y = 0; y < std::min(h, rows_ahead); ++y) ask_for_row(from + y * stride, std::size_t(w));
    for (int y = 0; y < h; ++y) {
        if (y + rows_ahead < h) ask_for_row(from + (y + rows_ahead) * stride, std::size_t(w));
        std::memcpy(to + std::size_t(y) * std::size_t(w), from + y * stride, std::size_t(w));
    }
}

// Rays counted for a TraceControl: every 64 rays their estimated steps are
// added and the cancel flag read; once cancelled, next() says skip the rest.
struct RayTally {
    const TraceControl* control;
    std::int64_t per_ray;  // max(a, b) + 1
    std::int64_t added = 0;
    int pending = 0;
    bool stopped = false;
    bool next() {
        if (!control) return true;
        if (stopped) return false;
        if (++pending == 64) {
            control->add(64 * per_ray);
            added += 64 * per_ray;
            pending = 0;
            stopped = control->cancelled();
        }
        return !stopped;
    }
    // The light's whole estimate once done, whatever path traced it.
    void finish(double estimate) {
        if (control && !stopped) control->add(std::max<std::int64_t>(0, std::int64_t(estimate) - added));
    }
};

}  // namespace

void start_mask(LightMask& m, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Rect clip,
                bool with_reached) {
    m.clip = clip;
    m.cx = cx;
    m.cy = cy;
    m.a = a;
    m.b = b;
    m.falloff_scale = p.falloff_scale;
    const std::size_t n = std::size_t(std::max(0, clip.w)) * std::max(0, clip.h);
    m.value.assign(n, 0);
    m.reached.assign(with_reached ? n : 0, 0);
}

double light_trace_work(int a, int b, const Params& p) {
    const double m = std::max(a, b);
    const double rays = p.rays == Rays::every_pixel ? (2.0 * a + 1) * (2.0 * b + 1) : (8 * m + 4) / p.ray_skip;
    return rays * (m + 1);
}

void trace_light_into(LightMask& m, const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b,
                      const Params& p, Rect clip, bool area_is_clear, const TraceControl* control) {
    assert(a >= 0 && b >= 0 && p.ray_skip >= 1 && p.falloff_scale > 0);
    start_mask(m, cx, cy, a, b, p, clip, p.mode == Mode::shadow);
    if (clip.empty()) return;
    RayTally tally{control, std::int64_t(std::max(a, b)) + 1};
    const double estimate = light_trace_work(a, b, p);
    // The falloff by distance: no division per pixel.
    const int dmax = std::max(a, b);
    std::vector<std::uint8_t> table(std::size_t(dmax) + 1);
    for (int d = 0; d <= dmax; ++d) table[std::size_t(d)] = falloff(d, p.falloff_scale);

    const bool representable = std::llabs(cx) < 1000000000 && std::llabs(cy) < 1000000000;
    const Rect area = representable ? Rect{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1} : Rect{};
    const bool covered = representable && (p.mode == Mode::flat || intersect(obstacles.rect(), area) == area);
    // A light cut by the view's edge: its rays do not depend on the clip, so
    // the fast path traces the whole area and the clip is copied out (the
    // same bytes as the general path, many times faster), unless the area is
    // far larger than the clip.
    const double area_px = double(area.w) * area.h, clip_px = double(clip.w) * clip.h;
    if (covered && !(clip == area) && intersect(clip, area) == clip && area_px <= std::max(4 * clip_px, 1048576.0)) {
        thread_local LightMask whole;  // kept: its vectors' capacity is reused
        trace_light_into(whole, obstacles, cx, cy, a, b, p, area, area_is_clear, control);
        for (int y = 0; y < clip.h; ++y) {
            const std::size_t from = std::size_t(clip.y + y - area.y) * area.w + std::size_t(clip.x - area.x);
            std::memcpy(&m.value[std::size_t(y) * clip.w], &whole.value[from], std::size_t(clip.w));
            if (p.mode == Mode::shadow) std::memcpy(&m.reached[std::size_t(y) * clip.w], &whole.reached[from], std::size_t(clip.w));
        }
        return;
    }
    const bool fast = covered && clip == area;
    if (fast) {
        const bool every_pixel_lit = p.mode == Mode::flat || area_is_clear;
        if (every_pixel_lit && (p.rays == Rays::every_pixel || p.ray_skip == 1)) {
            // Closed form: with nothing in the way, the rays cover the whole
            // area, each pixel at falloff(max(|dx|, |dy|)) = min of the two
            // (falloff never increases).
            std::vector<std::uint8_t> by_x(std::size_t(clip.w));
            for (int x = -a; x <= a; ++x) by_x[std::size_t(x + a)] = table[std::size_t(std::abs(x))];
            for (int y = -b; y <= b; ++y) {
                std::uint8_t* row = &m.value[std::size_t(y + b) * clip.w];
                const std::uint8_t vy = table[std::size_t(std::abs(y))];
                const std::uint8_t* fx = by_x.data();
                const int w = clip.w;  // a local: the byte stores could alias clip.w, and re-reading it stops vectorising
                for (int x = 0; x < w; ++x) row[x] = fx[x] < vy ? fx[x] : vy;
            }
            if (p.mode == Mode::shadow) std::fill(m.reached.begin(), m.reached.end(), 1);
            tally.finish(estimate);
            return;
        }
        static const std::uint8_t none = 0;
        const std::uint8_t* ob = p.mode == Mode::flat
                                     ? &none
                                     : &obstacles.bits[std::size_t(cy - obstacles.y0) * obstacles.width +
                                                       std::size_t(cx - obstacles.x0)];
        const std::ptrdiff_t ob_stride = p.mode == Mode::flat ? 0 : obstacles.width;
        std::uint8_t* lit = &m.value[std::size_t(b) * clip.w + a];
        std::uint8_t* reached = p.mode == Mode::shadow ? &m.reached[std::size_t(b) * clip.w + a] : nullptr;
        std::uint64_t steps = 0;
        auto ray = [&](std::int64_t w, std::int64_t h) {
            if (!tally.next()) return;
            switch (p.mode) {
                case Mode::light: steps += trace_fast<Mode::light>(ob, ob_stride, table.data(), lit, reached, clip.w, w, h); break;
                case Mode::shadow: steps += trace_fast<Mode::shadow>(ob, ob_stride, table.data(), lit, reached, clip.w, w, h); break;
                case Mode::flat: steps += trace_fast<Mode::flat>(ob, 0, table.data(), lit, reached, clip.w, w, h); break;
            }
        };
        if (p.rays == Rays::every_pixel) {
            for (int y = -b; y <= b; ++y)
                for (int x = -a; x <= a; ++x) ray(x, y);
        } else if (p.mode != Mode::flat && a <= max_tree_extent && b <= max_tree_extent) {
            const auto tree = ray_tree(a, b, p.ray_skip);
            const auto values = tree_values(*tree, a, b, p.ray_skip, table, p.falloff_scale);
            const std::int32_t nodes = std::int32_t(values->node.size());
            std::uint8_t* reached_all = p.mode == Mode::shadow ? m.reached.data() : nullptr;
            // The area's obstacles copied row by row into the mask's layout
            // first: both the prune and the walk read them so. The rows are
            // short pieces of the world-wide map, which have left the caches
            // since the last frame: each is asked for `rows_ahead` rows before
            // it is copied (the copy was a trip to memory per row, 16.7 us a
            // light; with this 7.5 us).
            const std::uint8_t* ob_area =
                &obstacles.bits[std::size_t(clip.y - obstacles.y0) * obstacles.width + std::size_t(clip.x - obstacles.x0)];
            thread_local std::vector<std::uint8_t> local;
            local.resize(m.value.size());
            copy_area_rows(ob_area, obstacles.width, clip.w, clip.h, local.data());
            std::int64_t visited = prune_tree(*tree, *values, local.data(), clip.w, clip.h, m.value.data(), reached_all);
            ++(visited < 0 ? tree_traces().walked : tree_traces().pruned);
            if (visited < 0)
                visited = p.mode == Mode::light
                              ? walk_tree<Mode::light>(values->node.data(), nodes, local.data(), m.value.data(), nullptr)
                              : walk_tree<Mode::shadow>(values->node.data(), nodes, local.data(), m.value.data(),
                                                        reached_all);
            steps += std::uint64_t(visited);
        } else {
            const auto border = border_offsets(a, b);
            for (std::size_t i = 0; i < border.size(); i += std::size_t(p.ray_skip)) ray(border[i].first, border[i].second);
        }
        bresenham_steps() += steps;
        tally.finish(estimate);
        return;
    }

    // General path: any clip, any centre (also far outside int range).
    auto trace = [&](std::int64_t tx, std::int64_t ty) {
        if (!tally.next()) return;
        bool blocked = false;
        for (BresenhamRay r(cx, cy, tx, ty); !r.done(); r.step()) {
            ++bresenham_steps();
            if (p.mode != Mode::flat && !blocked && blocked_at(obstacles, r.x, r.y)) {
                if (p.mode == Mode::light) return;
                blocked = true;  // shadow mode: what lies beyond, this pixel included
            }
            const std::int64_t lx = r.x - clip.x, ly = r.y - clip.y;
            if (lx < 0 || ly < 0 || lx >= clip.w || ly >= clip.h) continue;
            const std::size_t i = std::size_t(ly) * clip.w + std::size_t(lx);
            if (!blocked) m.value[i] = table[std::size_t(std::max(std::llabs(r.x - cx), std::llabs(r.y - cy)))];
            if (p.mode == Mode::shadow) m.reached[i] = 1;
        }
    };
    for_each_ray_target(cx, cy, a, b, p, trace);
    tally.finish(estimate);
}

LightMask trace_light(const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p,
                      Rect clip, bool area_is_clear, const TraceControl* control) {
    LightMask m;
    trace_light_into(m, obstacles, cx, cy, a, b, p, clip, area_is_clear, control);
    return m;
}

void trace_light_ray_paper(const Mask& obstacles, std::int64_t orgX, std::int64_t orgY, std::int64_t dstX,
                           std::int64_t dstY, Rect clip, std::vector<std::uint8_t>& texture) {
    // Algorithm 2, line for line.
    const std::int64_t cX = orgX, cY = orgY;
    std::int64_t w = dstX - orgX, h = dstY - orgY;
    int dx1 = 0, dy1 = 0, dx2 = 0, dy2 = 0;
    if (w < 0) dx1 = -1, dx2 = -1;
    else if (w > 0) dx1 = 1, dx2 = 1;
    if (h < 0) dy1 = -1;
    else if (h > 0) dy1 = 1;
    std::int64_t longest = std::llabs(w), shortest = std::llabs(h);
    if (!(longest > shortest)) {
        longest = std::llabs(h);
        shortest = std::llabs(w);
        dx2 = 0;
        if (h < 0) dy2 = -1;
        else if (h > 0) dy2 = 1;
    }
    std::int64_t numerator = longest >> 1;
    bool finished = false;
    for (std::int64_t i = 0; i <= longest && !finished; i++) {
        if (!blocked_at(obstacles, orgX, orgY)) {
            if (orgX >= clip.x && orgY >= clip.y && orgX < std::int64_t(clip.x) + clip.w &&
                orgY < std::int64_t(clip.y) + clip.h) {
                const std::int64_t d = std::max(std::llabs(orgX - cX), std::llabs(orgY - cY));
                texture[std::size_t(orgY - clip.y) * clip.w + std::size_t(orgX - clip.x)] = std::uint8_t(255 / (1 + d));
            }
        } else {
            finished = true;
        }
        numerator += shortest;
        if (!(numerator < longest)) {
            numerator -= longest;
            orgX += dx1;
            orgY += dy1;
        } else {
            orgX += dx2;
            orgY += dy2;
        }
    }
}

}  // namespace isolux
