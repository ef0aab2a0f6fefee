// Beyond the paper: rays stopped by solids with height, not by footprints
// (Params::occluders). Each ground pixel holds the span of heights
// [z_low, z_high) the solids standing over it fill; each sprite pixel, the
// height of the 3D point it shows. A light stands at its height H.
//
// Ground pixels keep the paper's border rays: along one ray every ground
// pixel shares the occluders before it, and a span [z_low, z_high) s steps
// out shades the steps from s H / (H - z_low) to s H / (H - z_high) (to the
// area's border where z_high >= H; nothing where z_low >= H), so one pass per
// ray suffices. A sprite pixel showing a point at height h over ground pixel g
// (h pixels below it on screen) is lit when the segment from the light to
// that point clears the spans along a ray that reaches g: walking a ray, the
// spans passed so far block a set of descents (H - h) / d that only grows, so
// each point is tested where the ray meets its ground pixel, one pass per ray
// again. That replaces the opacity correction (light_sprite_points, timed as
// that stage), which only guesses which sprite pixels stand above a light.
//
// The files: occluder_map.cpp builds the map (spans and sprite points per
// ground pixel) for a region, occluder_stamp.cpp stamps a sprite's estimated
// solids, solids_pass.cpp traces ray by ray and solids_pass_tree.cpp over the
// border rays' prefix tree.
#pragma once
#include <cstdint>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/params.hpp"
#include "isolux/solid_estimate.hpp"
#include "isolux/truth.hpp"
#include "isolux/world.hpp"

namespace isolux {

// The heights [low, high) one solid, or several that meet, fill over a
// ground pixel; high <= low: none.
struct Span {
    float low = 0, high = 0;
    bool any() const { return high > low; }
    bool operator==(const Span& o) const { return low == o.low && high == o.high; }
};

// What stands over one ground pixel: up to two spans, `lower` below `upper`
// with a gap between them (a canopy over a bush, a crown over the ground
// beside a trunk: one span holding both would shade the gap). A third
// solid's span closes the narrowest gap. upper.any() implies lower.any().
struct Spans {
    Span lower, upper;
    bool any() const { return lower.any(); }
    bool operator==(const Spans& o) const { return lower == o.lower && upper == o.upper; }
    // Adds the heights [lo, hi) (lo < hi).
    void add(float lo, float hi);
    // Whether height z lies inside a span.
    bool holds(double z) const { return (z >= lower.low && z < lower.high) || (z >= upper.low && z < upper.high); }
};

// The rows a point h high lies above its ground pixel on screen: h rounded
// half away from zero, as std::llround (inline: the library call was a
// sizeable share of the sprite pass).
inline std::int64_t rows_above(double h) {
    if (h < 0) return -rows_above(-h);
    const std::int64_t r = std::int64_t(h);
    return r + std::int64_t(h - double(r) >= 0.5);  // no branch: a height's fraction is as likely either way
}

struct OccluderMap {
    Rect rect;                // world pixels, as the obstacle map's
    std::vector<Spans> spans;  // per ground pixel (16 bytes, on one cache line: a step reads them at once)
    Surface surface;          // per pixel: what it shows (ground or an overlay) and its height
    // Per ground pixel g, the sprite pixels whose point stands over it (h
    // rows above g): shown[shown_start[g] .. shown_start[g + 1]). The sprite
    // pass tests them where a ray meets g. Each entry is the height h of the
    // point the pixel shows (one below the ground counts as on it) and the
    // rows the pixel lies above g (rows_above(h)), so the pass reads nothing
    // else of it.
    struct Shown {
        float height;
        std::uint32_t rows;
        bool operator==(const Shown&) const = default;
    };
    std::vector<std::uint32_t> shown_start;
    std::vector<Shown> shown;
    // An edit relists its pixels in place: where their lists shrink, the
    // entries left over stay at the end of the last pixel's list as padding,
    // rows = unlisted (so far above any pixel that every pass skips it), for
    // the next edit there to reuse. `padding` counts them; a build or a pan
    // lists without any.
    static constexpr std::uint32_t unlisted = 1u << 30;
    std::size_t padding = 0;
    int tallest = 0;  // the most rows any such pixel lies above its ground pixel
    // At least the most rows any sprite pixel of the surface lies above its
    // ground pixel, listed or not (its ground below the map): how far up a
    // pan looks for the points of the ground pixels it lists anew.
    int reach_rows = 0;
    // Per pixel: has_span | has_shown, one byte a step reads before the rest
    // (most steps of a ray cross bare ground that no sprite stands over).
    enum : std::uint8_t { has_span = 1, has_shown = 2 };
    std::vector<std::uint8_t> flags;

    // The spans over ground pixel (x, y); none outside the map.
    Spans spans_at(std::int64_t x, std::int64_t y) const {
        if (!rect.contains(int(x), int(y))) return {};
        return spans[std::size_t(y - rect.y) * rect.w + std::size_t(x - rect.x)];
    }
};

// One sprite's estimated objects, the spans each fills over the ground
// pixels (a stamp per object: the pixels of `rect`, in sprite pixels, row
// by row; (0, 0) where it fills none), and the height of the point each
// sprite pixel shows (and which object shows it: `shown_by`, an index into
// `objects`, -1 where none does and the height is its row's above the
// nearest foot, or the sprite shows nothing). A world pixel's offset from its sprite is whole, so a
// stamp holds exactly the spans at the pixels' centres wherever it lands.
struct SpanStamp {
    Rect rect;
    std::vector<std::pair<float, float>> spans;
};
struct SpriteSolids {
    std::vector<EstimatedObject> objects;
    std::vector<SpanStamp> stamps;
    std::vector<float> heights;
    std::vector<std::int32_t> shown_by;
};
SpriteSolids sprite_solids(const Tileset& tileset, const Sprite& s, const Params& p);

// Each sprite's solids, estimated once (they depend on the sprite and the
// parameters only): build_occluders fills it as sprites come into view. The
// owner empties it when the tileset or the obstacle map's parameters change.
struct SolidsCache {
    std::vector<SpriteSolids> sprites;
    std::vector<char> made;
    void clear() { sprites.clear(), made.clear(); }
};
// Sprite `index`'s solids, estimated into `cache` when missing.
const SpriteSolids& cached_solids(SolidsCache& cache, const Tileset& tileset, std::size_t index, const Params& p);

// The most pixels an occluder map's region may hold: the map takes about 35
// bytes a pixel (two spans, the surface, the sprite points' index), so this
// bounds it near 2.3 GB. A larger region (a huge map rendered whole, a light
// thousands of pixels wide) is refused by Error, with its size.
inline constexpr long long max_occluder_pixels = 1LL << 26;

// The occluders of every overlay meeting `region` (and those standing near
// it), by `p.occluders`: solids estimated from the sprites (kept in `cache`
// when given), or the manifest's shapes (Error naming the tileset and the
// sprite when an overlay has none). Error when `region` holds more than
// max_occluder_pixels.
OccluderMap build_occluders(const World& world, const Params& p, Rect region, SolidsCache* cache = nullptr);

// Makes `m` build_occluders(world, p, region, cache) in the storage it holds:
// a map rebuilt over a region no larger (a parameter changed, the camera
// still) touches no new memory, where a fresh one faults in every page of
// its 30-odd bytes a pixel.
void rebuild_occluders(OccluderMap& m, const World& world, const Params& p, Rect region,
                       SolidsCache* cache = nullptr);

// Makes `m` (built with the same parameters) the occluder map of `region`,
// keeping what it holds there: only the parts of `region` that `m` did not
// cover, and `changed` (where the world changed since: the sprites edited,
// grown by occluder_reach), are built, and the index's lists they can change
// are listed again (an edit in the same region: in place, with padding where
// they shrink). The same map as build_occluders (each pixel depends only on
// the sprites near it) but for the padding, at the cost of the parts. With
// shapes, the whole region is built.
void update_occluders(OccluderMap& m, const World& world, const Params& p, Rect region, Rect changed,
                      SolidsCache* cache = nullptr);

// How far below its sprite's rectangle an estimated solid's ground reaches:
// the margin around a changed sprite that update_occluders rebuilds.
int occluder_reach(const Tileset& tileset);

// Fills `m.shown` from its surface and `m.flags` from its spans and surface
// (build_occluders does the same, flagging spans as it fills them; a map
// made by hand calls it once its spans and surface are set). Error when the
// region has 2^32 - 2 pixels or more.
void index_occluders(OccluderMap& m);

// One light at (cx, cy), half-extents a, b, at `height` above the ground,
// traced against `occ` as ground everywhere: value = falloff(max(|dx|, |dy|))
// where lit, as trace_light's (shape_light applies the falloff's shape
// after). Border rays with ray skip, or every pixel; light and shadow modes
// (`reached` filled in shadow mode: every pixel of the area). `threads`:
// how many threads walk the rays (the same bytes on any number).
LightMask trace_light_solids(const OccluderMap& occ, std::int64_t cx, std::int64_t cy, int a, int b, double height,
                             const Params& p, Rect clip, int threads = 1);

// Then every pixel of the mask that shows a sprite, lit (or not) by the 3D
// point it shows, tested along the same rays as the ground (ray skip, or
// every pixel): in place of the opacity correction, and timed as it. A pixel
// whose ground point lies outside the area (or the map) is tested along its
// own line from the light's centre. `threads` as trace_light_solids.
void light_sprite_points(LightMask& mask, const OccluderMap& occ, double height, const Params& p, int threads = 1);

// Beyond the paper: the occluders' resolution as an accuracy-for-time knob
// (Params::occluder_scale, s). Both passes run over a map s times coarser
// in x, y and height (the projection is the same at any scale, so the
// coarse scene is the fine one shrunk), each fine pixel then taking the
// lit-or-dark answer of the coarse pixel that holds it, with its own
// falloff. A coarse pixel covers an s x s block: its spans are the union
// of the block's (no solid is lost, however thin), its surface the block's
// top-left pixel's, height over s. Two pixels' more, all round, of empty
// ground: a coarse light's area covers its fine one's and stays inside the
// map. s = 1 is the map itself (callers keep it and skip this).
OccluderMap coarse_occluders(const OccluderMap& fine, int scale);

// The coarse light of a fine mask (clip, centre and a, b set): centre and
// clip the fine ones' blocks, half-extents a / s + 1 (covering the fine
// area), the falloff flat so that every lit pixel is non-zero. `coarse_p`
// (coarse_params) traces it; its height is the fine one's over s.
Params coarse_params(const Params& p);
void start_coarse_mask(LightMask& coarse, const LightMask& fine, int scale, const Params& coarse_p);

// Which coarse pixel each fine pixel of `fine` (the fine map's surface)
// takes its answer from: of its block and the block's eight neighbours (the
// block first, then the four sides, then the corners), the first of those
// showing the pixel's own surface (its overlay, or the ground) nearest its
// height; its block where none does. A sprite pixel whose block samples the
// ground beside it so takes its sprite's answer, not the ground's. One byte
// a fine pixel (0 the block), made with the coarse map.
std::vector<std::uint8_t> coarse_picks(const Surface& fine, const OccluderMap& coarse, int scale);

// After the fine map panned (update_occluders over a new region, nothing
// changed) from `old_fine`, its region when `coarse` and `picks` were made
// from it: both made what coarse_occluders and coarse_picks give the map
// as it is, the blocks wholly inside the part both regions share kept (and
// the picks that read only those), the rest made again.
void pan_coarse_occluders(OccluderMap& coarse, std::vector<std::uint8_t>& picks, const OccluderMap& fine, Rect old_fine,
                          int scale);

// After an edit changed the fine map's spans and surface within `changed`
// alone (update_occluders with solids, in the same region): `coarse` and
// `picks` made what coarse_occluders and coarse_picks give the map as it
// is, only the blocks holding a changed pixel made again, their index
// relisted in place (OccluderMap::padding where lists shrink), and the
// picks that read those blocks.
void edit_coarse_occluders(OccluderMap& coarse, std::vector<std::uint8_t>& picks, const OccluderMap& fine, Rect changed,
                           int scale);

// Each pixel of the fine mask's area (in its clip, started unlit) lit,
// with its own falloff, where the coarse pixel it takes its answer from is
// lit: its block's, or with `fine_surface` and its `picks`
// (coarse_picks), the one picked (its block's where that lies past the
// coarse mask's clip). In shadow mode every pixel of the clip is reached,
// as trace_light_solids leaves it.
void upsample_mask(LightMask& fine, const LightMask& coarse, int scale, const Params& p,
                   const Surface* fine_surface = nullptr, const std::vector<std::uint8_t>* picks = nullptr);

// trace_light_solids then, with `sprite_points`, light_sprite_points, over
// `coarse` (coarse_occluders(fine, scale)): the fine mask (started as
// trace_light_solids starts it) from the coarse one, by the picks when
// given (upsample_mask).
void trace_solids_at_scale(LightMask& fine, const OccluderMap& coarse, int scale, double height, const Params& p,
                           bool sprite_points, int threads = 1, const Surface* fine_surface = nullptr,
                           const std::vector<std::uint8_t>* picks = nullptr);

}  // namespace isolux
