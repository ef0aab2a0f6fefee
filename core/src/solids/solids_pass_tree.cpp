// The passes of occluder_map.hpp over the border rays' prefix tree
// (solids_pass_tree.hpp). A node is one step of every ray through its prefix:
// its depth is the step count, and its subtree [i, end) all the rays' steps
// beyond it. What a ray carries (the shades of the spans it passed, the
// descents they block) depends only on its path, so it is carried down the
// tree. Below no span at all a node is simply lit: those parts are walked
// four nodes at a time, reading one flag byte each.
#include "solids/solids_pass_tree.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <tuple>
#include <type_traits>

#include "base/bounded_cache.hpp"
#include "frame/ray_tree.hpp"
#include "base/worker_pool.hpp"

namespace isolux {

namespace {

constexpr int max_extent = 512;  // as the paper's tracer: larger areas go ray by ray

// A node as the walks read it: its area index (from the top-left) times 1024
// plus its depth (< 1024), and the end of its subtree.
struct Node {
    std::uint32_t at_depth;
    std::int32_t end;
};
constexpr std::uint32_t depth_bits = 10;
constexpr std::uint32_t depth_mask = (1u << depth_bits) - 1;

// A mask's byte as a walk reads and writes it. `Shared`: walks on several
// threads may light a pixel several rays reach from two subtrees at once,
// always with the same value (its falloff), so relaxed order suffices; one
// thread's walk keeps plain bytes (atomics cost it a few percent).
using Shared = std::true_type;
using Alone = std::false_type;
template <class S>
inline void store(std::uint8_t& v, std::uint8_t x) {
    if constexpr (S::value) std::atomic_ref<std::uint8_t>(v).store(x, std::memory_order_relaxed);
    else v = x;
}
template <class S>
inline std::uint8_t load(std::uint8_t& v) {
    if constexpr (S::value) return std::atomic_ref<std::uint8_t>(v).load(std::memory_order_relaxed);
    else return v;
}

// The tree's nodes as the walks read them, kept per (a, b, k) like the
// trees (within 128 MiB).
std::shared_ptr<const std::vector<Node>> tree_nodes(int a, int b, int k) {
    static BoundedCache<std::tuple<int, int, int>, std::vector<Node>> cache(std::size_t(128) << 20);
    auto build = [&] {
        const auto tree = ray_tree(a, b, k);
        auto nodes = std::make_shared<std::vector<Node>>(tree->end.size());
        const std::int32_t centre = b * (2 * a + 1) + a;
        for (std::size_t i = 0; i < nodes->size(); ++i)
            (*nodes)[i] = {std::uint32_t(centre + tree->offset[i]) << depth_bits | tree->depth[i], tree->end[i]};
        return nodes;
    };
    return cache.get({a, b, k}, build, [](const std::vector<Node>& v) { return vector_bytes(v); });
}

// The light's area (the mask's clip) in the occluder map: an area index's
// row and column, and the map index of the same pixel.
struct AreaInMap {
    std::uint32_t w;
    double inv_w;  // (o + 0.5) / w never lies within rounding of a whole number
    std::size_t base, map_w;
    AreaInMap(const OccluderMap& occ, Rect area)
        : w(std::uint32_t(area.w)), inv_w(1.0 / area.w),
          base(std::size_t(area.y - occ.rect.y) * occ.rect.w + std::size_t(area.x - occ.rect.x)),
          map_w(std::size_t(occ.rect.w)) {}
    std::uint32_t row(std::uint32_t o) const { return std::uint32_t((o + 0.5) * inv_w); }
    std::size_t map(std::uint32_t o) const {
        const std::uint32_t r = row(o);
        return base + r * map_w + (o - r * w);
    }
};

// A flag of the areas' copies alone: from this pixel on, a ray only moves
// farther from the pixels a pass is asked about.
constexpr std::uint8_t moving_away = 4;

// The occluder flags of the area (centred on the light), rows copied into
// the area's layout. A pass asks only about the ground pixels in `wanted`
// (the clip; for the sprite pass, those whose points can show in it):
// has_shown is cleared outside it, and `moving_away` set where a pixel lies
// outside it on the far side from the light. (A ray only climbs or only
// sinks, and only goes left or only right, so such a node's whole subtree
// lies there too.)
const std::uint8_t* area_flags(const OccluderMap& occ, Rect area, const AreaInMap& in, Rect wanted) {
    thread_local std::vector<std::uint8_t> local;
    local.resize(std::size_t(area.w) * area.h);
    for (int y = 0; y < area.h; ++y)
        std::memcpy(&local[std::size_t(y) * area.w], &occ.flags[in.base + std::size_t(y) * in.map_w], std::size_t(area.w));
    if (wanted == area) return local.data();
    const int cx = area.w / 2, cy = area.h / 2;  // the light, in the area
    const int x0 = std::clamp(wanted.x - area.x, 0, area.w), x1 = std::clamp(wanted.x + wanted.w - area.x, x0, area.w);
    const int y0 = wanted.y - area.y, y1 = y0 + wanted.h;
    auto mark = [](std::uint8_t* from, int count, bool away) {
        constexpr auto unshown = std::uint8_t(~OccluderMap::has_shown);
        const std::uint8_t set = away ? moving_away : 0;
        for (int x = 0; x < count; ++x) from[x] = std::uint8_t((from[x] & unshown) | set);
    };
    const int left_away = std::min(x0, cx), right_away = std::max(x1, cx + 1);
    for (int y = 0; y < area.h; ++y) {
        std::uint8_t* row = &local[std::size_t(y) * area.w];
        if (y < y0 || y >= y1) {
            mark(row, area.w, (y < y0 && y < cy) || (y >= y1 && y > cy));
            continue;
        }
        mark(row, left_away, true);
        mark(row + left_away, x0 - left_away, false);
        mark(row + x1, right_away - x1, false);
        mark(row + right_away, area.w - right_away, true);
    }
    return local.data();
}

// The spans are map-wide, 16 bytes a pixel, so a light's rows of them are
// far apart and mostly out of cache: the walks ask for a node's spans this
// many nodes before they read them.
constexpr std::int32_t spans_ahead = 16;
inline void ask_for_spans(const OccluderMap& occ, const AreaInMap& in, const std::uint8_t* flags, const Node* node,
                          std::int32_t j, std::int32_t end) {
    if (j >= end) return;
    const std::uint32_t o = node[j].at_depth >> depth_bits;
    if (flags[o] & OccluderMap::has_span) __builtin_prefetch(&occ.spans[in.map(o)]);
}

// Walks nodes from `i` while no node holds a span, calling at(o, depth) for
// each whose flags have a bit of `wanted` and skipping the subtrees moving
// away; four nodes a step while none of them has any. Returns the first
// node holding a span (or n).
template <class At>
std::int32_t walk_clear(const Node* node, std::int32_t i, std::int32_t n, const std::uint8_t* flags,
                        std::uint8_t wanted, At&& at) {
    const std::uint8_t any = wanted | OccluderMap::has_span | moving_away;
    for (;;) {
        while (i + 4 <= n) {
            const std::uint32_t w0 = node[i].at_depth, w1 = node[i + 1].at_depth, w2 = node[i + 2].at_depth,
                                w3 = node[i + 3].at_depth;
            if ((flags[w0 >> depth_bits] | flags[w1 >> depth_bits] | flags[w2 >> depth_bits] | flags[w3 >> depth_bits]) & any)
                break;
            i += 4;
        }
        if (i >= n) return n;
        const std::uint32_t w = node[i].at_depth;
        const std::uint8_t f = flags[w >> depth_bits];
        if (f & moving_away) {
            i = node[i].end;
            continue;
        }
        if (f & OccluderMap::has_span) return i;
        if (f & wanted) at(w >> depth_bits, w & depth_mask);
        ++i;
    }
}

// The same, writing each node's falloff (ground pass: a node before any span
// on its rays is lit), and skipping the subtree of each node moving away or
// at depth `endless` or more (shaded to the border by a span before them).
template <class S>
std::int32_t light_clear(const Node* node, std::int32_t i, std::int32_t n, const std::uint8_t* flags,
                         const std::uint8_t* table, std::uint8_t* value, std::uint32_t endless) {
    for (;;) {
        if (endless > depth_mask)  // nothing shaded: four nodes a step
            while (i + 4 <= n) {
                const std::uint32_t w0 = node[i].at_depth, w1 = node[i + 1].at_depth, w2 = node[i + 2].at_depth,
                                    w3 = node[i + 3].at_depth;
                const std::uint32_t o0 = w0 >> depth_bits, o1 = w1 >> depth_bits, o2 = w2 >> depth_bits, o3 = w3 >> depth_bits;
                if ((flags[o0] | flags[o1] | flags[o2] | flags[o3]) & (OccluderMap::has_span | moving_away)) break;
                store<S>(value[o0], table[w0 & depth_mask]);
                store<S>(value[o1], table[w1 & depth_mask]);
                store<S>(value[o2], table[w2 & depth_mask]);
                store<S>(value[o3], table[w3 & depth_mask]);
                i += 4;
            }
        if (i >= n) return n;
        const std::uint32_t w = node[i].at_depth;
        const std::uint8_t f = flags[w >> depth_bits];
        if (f & OccluderMap::has_span) return i;
        if ((w & depth_mask) >= endless || (f & moving_away)) {
            i = node[i].end;
            continue;
        }
        store<S>(value[w >> depth_bits], table[w & depth_mask]);
        ++i;
    }
}

// The walk's pieces for `threads` threads: the subtrees below the nodes
// within split_depth steps of the light that hold no span, each walked on
// its own (`walk(i)` walks node i's subtree, its rays carrying nothing in:
// no span before it), those nodes themselves by `head(i)`, and none below a
// node moving away. Each pixel's answer is the same whichever walk lights
// it first, so the bytes do not depend on the thread count. One thread, or
// a tree of under min_split_nodes, walks the whole tree as one piece:
// waking other threads would cost about what they save (a 129x129 light's
// ground pass, 17,000 nodes, takes longer on two).
constexpr int split_depth = 3;
constexpr std::int32_t min_split_nodes = 32768;
template <class Head, class Walk>
void walk_pieces(const Node* node, const std::uint8_t* flags, int threads, Head&& head, Walk&& walk) {
    if (threads <= 1 || node[0].end < min_split_nodes) return walk(Alone{}, 0);
    std::vector<std::int32_t> pieces;
    auto split = [&](auto&& self, std::int32_t i) -> void {
        const std::uint32_t w = node[i].at_depth;
        const std::uint8_t f = flags[w >> depth_bits];
        if (f & moving_away) return;
        if ((w & depth_mask) >= split_depth || (f & OccluderMap::has_span)) return pieces.push_back(i);
        head(i);
        for (std::int32_t c = i + 1; c < node[i].end; c = node[c].end) self(self, c);
    };
    split(split, 0);
    // Threads take runs of neighbouring pieces (the tree is in angular
    // order), four a thread of about equal nodes: pieces taken one by one
    // would put neighbouring rays on different threads, writing the same
    // cache lines of the mask.
    std::vector<std::size_t> runs{0};
    const std::int32_t per_run = node[0].end / (4 * threads) + 1;
    std::int32_t in_run = 0;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
        in_run += node[pieces[k]].end - pieces[k];
        if (in_run >= per_run) runs.push_back(k + 1), in_run = 0;
    }
    if (runs.back() != pieces.size()) runs.push_back(pieces.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t r; (r = next++) + 1 < runs.size();)
            for (std::size_t k = runs[r]; k < runs[r + 1]; ++k) walk(Shared{}, pieces[k]);
    };
    run_on_threads(std::min(threads, int(runs.size()) - 1), work);
}

}  // namespace

bool occluder_tree_extent(int a, int b, const Params& p) {
    return p.rays == Rays::border && a <= max_extent && b <= max_extent;
}

bool occluder_tree_serves(const OccluderMap& occ, Rect area, const Params& p) {
    return occluder_tree_extent(area.w / 2, area.h / 2, p) && intersect(area, occ.rect) == area &&
           occ.flags.size() == occ.spans.size();
}

void trace_ground_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                       const Params& p, Rect wanted, int threads) {
    const auto tree = tree_nodes(m.a, m.b, p.ray_skip);
    const Node* node = tree->data();
    const AreaInMap in(occ, m.clip);
    const std::uint8_t* flags = area_flags(occ, m.clip, in, wanted);
    std::uint8_t* value = m.value.data();
    // Below a span: a stack of the subtrees whose shades differ from their
    // parent's. A span standing on the ground shades from its own node's
    // depth to some depth beyond: on the rays below, every depth up to the
    // farthest such end (`until`, a running maximum). A crown over the
    // ground shades the whole depths [ceil(from), ceil(to)) beyond its
    // node, kept as one bit per depth (a frame's row of bits, its parent's
    // when it adds none); and the depth from which everything is shaded to
    // the border. Beyond the area's last depth a shade shades nothing (a
    // canopy far out shades past the border).
    const int last = std::max(m.a, m.b);
    const double last_depth = double(last);
    const int words = last / 64 + 1;
    constexpr int none = std::numeric_limits<int>::max();
    struct Frame {
        std::int32_t end;
        int endless;  // none, or the depth from which all is shaded
        int until;    // the depths below it are shaded (spans on the ground)
        int reach;    // the crowns' bits end before it
        int row;      // the stack level whose row of bits this frame reads
    };
    // (The scalars by value: the mask's byte stores may alias anything the
    // walk holds by reference, which would be read again after each.)
    auto walk = [&, node, flags, value, H, last, last_depth, words](auto shared, std::int32_t piece) {
        using S = decltype(shared);
        const std::int32_t n = node[piece].end;
        thread_local std::vector<Frame> frames;
        thread_local std::vector<std::uint64_t> bit_arena;
        frames.resize(std::size_t(last) + 2);
        bit_arena.resize(frames.size() * std::size_t(words));
        std::fill_n(bit_arena.begin(), words, 0);  // a frame adding bits copies its row first
        Frame* frame = frames.data();
        std::uint64_t* bits = bit_arena.data();
        int t = 0;
        frame[0] = Frame{n, none, 0, 0, 0};
        for (std::int32_t i = piece; i < n;) {
            while (frame[t].end <= i) --t;
            const Frame top = frame[t];
            ask_for_spans(occ, in, flags, node, i + spans_ahead, n);
            const std::uint32_t w = node[i].at_depth, o = w >> depth_bits;
            const int k = int(w & depth_mask);
            const std::uint8_t f = flags[o];
            if (f & moving_away) {
                i = node[i].end;
                continue;
            }
            if (top.reach <= k && top.until <= k && !(f & OccluderMap::has_span)) {
                // No shade reaches this node or any below it: lit unless past
                // the endless shade, up to the next span (in its subtree, or
                // after it when the frame is empty).
                const bool empty = top.reach == 0 && top.until == 0 && top.endless == none;
                i = light_clear<S>(node, i, empty ? top.end : node[i].end, flags, table.data(), value,
                                   std::uint32_t(top.endless));
                continue;
            }
            // This node's shades (one per span below the light): a span on
            // the ground shades [k, to) (this node too), a crown [from, to)
            // with from > k.
            int endless = top.endless, until = top.until;
            std::array<int, 2> from{0, 0}, to{0, 0};
            bool grounded_here = false;
            if (f & OccluderMap::has_span) {
                const Spans& sps = occ.spans[in.map(o)];
                const double kd = double(k);
                for (int j = 0; j < 2; ++j) {
                    const Span sp = j == 0 ? sps.lower : sps.upper;
                    if (!sp.any() || sp.low >= H) continue;
                    const double f = sp.low <= 0 ? kd : kd * H / (H - sp.low);
                    if (f > last_depth) continue;
                    if (sp.high >= H) {
                        endless = std::min(endless, int(std::ceil(f)));
                        continue;
                    }
                    const double e = kd * H / (H - sp.high);
                    const int end = e > last_depth ? last + 1 : int(std::ceil(e));
                    if (sp.low <= 0) {
                        grounded_here = grounded_here || k < end;
                        until = std::max(until, end);
                    } else {
                        from[std::size_t(j)] = int(std::ceil(f));
                        to[std::size_t(j)] = end;
                    }
                }
            }
            if (endless <= k) {  // this node and its whole subtree are shaded
                i = node[i].end;
                continue;
            }
            until = std::min(until, endless);
            const std::uint64_t* at = bits + std::size_t(top.row) * words;
            const bool shaded = grounded_here || k < top.until || (k < top.reach && (at[k >> 6] >> (k & 63) & 1));
            int reach = top.reach;
            bool new_bits = false;
            for (std::size_t j = 0; j < 2; ++j) {
                from[j] = std::max({from[j], k + 1, until});  // the grounded spans' depths shade them already
                to[j] = std::min(to[j], endless);
                if (from[j] < to[j]) new_bits = true, reach = std::max(reach, to[j]);
            }
            if (!shaded) store<S>(value[o], table[std::size_t(k)]);
            if ((new_bits || until > top.until || endless < top.endless) && node[i].end > i + 1) {
                int row = top.row;
                if (new_bits) {
                    row = t + 1;
                    std::uint64_t* mine = bits + std::size_t(row) * words;
                    std::memcpy(mine, at, std::size_t(words) * sizeof(std::uint64_t));
                    for (std::size_t j = 0; j < 2; ++j)
                        for (int d = from[j]; d < to[j];) {  // the depths [from, to), a word at a time
                            const int word_end = std::min(to[j], (d & ~63) + 64);
                            const int count = word_end - d;
                            mine[d >> 6] |= (count == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << count) - 1)) << (d & 63);
                            d = word_end;
                        }
                }
                frame[t + 1] = Frame{node[i].end, endless, until, reach, row};
                ++t;
            }
            ++i;
        }
    };
    // The nodes above the pieces hold no span: lit.
    auto head = [&](std::int32_t i) {
        store<Shared>(value[node[i].at_depth >> depth_bits], table[std::size_t(node[i].at_depth & depth_mask)]);
    };
    walk_pieces(node, flags, threads, head, walk);
}

void light_sprite_points_tree(LightMask& m, const OccluderMap& occ, double H, const std::vector<std::uint8_t>& table,
                              const Params& p, int own_steps, Rect wanted, int threads) {
    // The rays' area: the light's, grown by the tallest point's rows above
    // and below (light_sprite_points).
    const int b = m.b + occ.tallest;
    const Rect rays{int(m.cx) - m.a, int(m.cy) - b, 2 * m.a + 1, 2 * b + 1};
    const auto tree = tree_nodes(m.a, b, p.ray_skip);
    const Node* node = tree->data();
    const AreaInMap in(occ, rays);
    // The ground pixels whose points can show in `wanted`: its columns, its
    // rows and the tallest point's rows below them.
    const std::uint8_t* flags =
        area_flags(occ, rays, in, intersect(rays, Rect{wanted.x, wanted.y, wanted.w, wanted.h + occ.tallest}));
    std::uint8_t* value = m.value.data();
    const std::uint32_t W = std::uint32_t(rays.w);
    const std::uint32_t first_row = std::uint32_t(occ.tallest), last_row = first_row + std::uint32_t(2 * m.b);
    const double top = occ.tallest + 0.5;  // no point stands higher
    // The sprite pixels standing over ground pixel o of the rays' area (its
    // map index g), lit unless the ray's shadow blocks the descent down to
    // them; those in the light's area only. Several rays reach a pixel: any
    // one lights it.
    auto light_shown = [&](auto shared, std::uint32_t o, std::uint32_t k, const RayShadow* r) {
        using S = decltype(shared);
        const std::size_t g = in.map(o);
        const std::uint32_t row = in.row(o), c = o - row * W;
        for (std::uint32_t e = occ.shown_start[g]; e < occ.shown_start[g + 1]; ++e) {
            const std::uint32_t rows = occ.shown[e].rows;
            if (rows > row || row - rows < first_row || row - rows > last_row) continue;  // outside the light's area
            std::uint8_t& v = value[(row - rows - first_row) * W + c];
            if (load<S>(v)) continue;
            if (int(k) <= own_steps || !r->blocks((H - occ.shown[e].height) / double(k)))
                store<S>(v, table[std::size_t(std::max(std::abs(int(c) - m.a), std::abs(int(row) - int(rows) - b)))]);
        }
    };
    // Below a span: per depth on the current path, the node's spans and
    // the ray's shadow after it (a node's parent is the last node walked
    // one depth up, so the path's shadows need no stack): shadow[k + 1]
    // after the node at depth k, the parent's own unless a span passed there.
    const int depths = std::max(m.a, b) + 1;
    const RayShadow clear;
    auto walk = [&, node, flags, H, own_steps, top, depths](auto shared, std::int32_t piece) {
        const std::int32_t n = node[piece].end;
        thread_local std::vector<const Spans*> span;  // none: nullptr
        thread_local std::vector<RayShadow> changed;  // changed[k + 1]: the shadow after a span passed at depth k
        thread_local std::vector<const RayShadow*> shadow;
        span.assign(std::size_t(depths), nullptr);
        changed.resize(std::size_t(depths) + 1);
        shadow.resize(std::size_t(depths) + 1);
        thread_local std::vector<std::int32_t> next_shown;  // per node: the first node from it with points
        next_shown.resize(std::size_t(n) + 1);
        for (std::int32_t i = piece; i < n;) {
            // Before any span on its rays a node lights every point over it.
            i = walk_clear(node, i, n, flags, OccluderMap::has_shown,
                           [&](std::uint32_t o, std::uint32_t k) { light_shown(shared, o, k, &clear); });
            if (i >= n) break;
            // Node i holds a span and no node before it on its rays does.
            const std::int32_t last = node[i].end;
            const int first = int(node[i].at_depth & depth_mask);
            // A subtree with no points has nothing to light: what its spans
            // block matters only within it, so the walk skips it whole.
            next_shown[std::size_t(last)] = last;
            for (std::int32_t j = last - 1; j >= i; --j)
                next_shown[std::size_t(j)] = flags[node[j].at_depth >> depth_bits] & OccluderMap::has_shown ? j : next_shown[std::size_t(j) + 1];
            if (next_shown[std::size_t(i)] >= last) {
                i = last;
                continue;
            }
            for (int d = std::max(0, first - own_steps); d < first; ++d) span[std::size_t(d)] = nullptr;
            shadow[std::size_t(first)] = &clear;
            for (; i < last; ++i) {
                ask_for_spans(occ, in, flags, node, i + spans_ahead, last);
                const std::uint32_t w = node[i].at_depth, o = w >> depth_bits;
                const int k = int(w & depth_mask);
                const std::uint8_t f = flags[o];
                if ((f & moving_away) || next_shown[std::size_t(i)] >= node[i].end) {
                    i = node[i].end - 1;
                    continue;
                }
                span[std::size_t(k)] = (f & OccluderMap::has_span) ? &occ.spans[in.map(o)] : nullptr;
                const RayShadow* r = shadow[std::size_t(k)];
                const int s = k - own_steps;
                if (s >= 0 && span[std::size_t(s)]) {
                    changed[std::size_t(k) + 1].set(*r);
                    changed[std::size_t(k) + 1].pass(*span[std::size_t(s)], s, H);
                    r = &changed[std::size_t(k) + 1];
                }
                shadow[std::size_t(k) + 1] = r;
                if (f & OccluderMap::has_shown) light_shown(shared, o, std::uint32_t(k), r);
                // Hidden from here on, or the horizon past every point's top and
                // only rising (a span as tall as the light): nothing below lit.
                if (k >= own_steps && (r->hidden() || (r->standing <= 0 && H - double(k) * r->standing > top)))
                    i = node[i].end - 1;
            }
        }
    };
    // The nodes above the pieces hold no span: each lights the points over it.
    auto head = [&](std::int32_t i) {
        const std::uint32_t w = node[i].at_depth;
        if (flags[w >> depth_bits] & OccluderMap::has_shown) light_shown(Shared{}, w >> depth_bits, w & depth_mask, &clear);
    };
    walk_pieces(node, flags, threads, head, walk);
}

}  // namespace isolux
