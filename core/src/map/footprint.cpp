// Footprints on real art (footprint.hpp). Built on Algorithm 1
// (sprite_obstacle), which `paper` runs unchanged.
#include "isolux/footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "isolux/opacity_map.hpp"

namespace isolux {

namespace {

double luminance(const std::uint8_t* p) { return (0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]) / 255.0; }

// Whether sprite pixel (x, y) lies inside the floor diamond centred on the anchor.
bool in_diamond(int x, int y, int ax, int ay, int tw, int th, double scale = 1.0) {
    const double u = std::abs(x + 0.5 - ax) / (tw / 2.0), v = std::abs(y + 0.5 - ay) / (th / 2.0);
    return u + v <= scale;
}

// Algorithm 1's marking for a given run s: s itself, and run/4 pixels above
// and below its centre pixel (paper 3.1, steps 3 and 4).
Mask mark_run(int w, int h, int x0, int y, int length) {
    const int arm = length / 4;
    Mask out(Rect{0, -arm, w, h + 2 * arm});
    for (int x = x0; x < x0 + length; ++x) out.set(x, y);
    const int cx = x0 + length / 2;
    for (int d = -arm; d <= arm; ++d) out.set(cx, y + d);
    return out;
}

// The even-odd rule at each pixel's centre, a row at a time: a pixel is
// inside when an odd number of the row's edge crossings lie right of its
// centre. Time in pixels plus rows x corners, never pixels x corners.
Mask fill_polygon(int w, int h, const std::vector<std::pair<int, int>>& poly) {
    Mask m(Rect{0, 0, w, h});
    if (poly.size() < 3) return m;
    std::vector<double> crossings;
    for (int y = 0; y < h; ++y) {
        const double py = y + 0.5;
        crossings.clear();
        for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
            const double xi = poly[i].first, yi = poly[i].second, xj = poly[j].first, yj = poly[j].second;
            if ((yi > py) != (yj > py)) crossings.push_back((xj - xi) * (py - yi) / (yj - yi) + xi);
        }
        std::sort(crossings.begin(), crossings.end());
        std::size_t left = 0;  // crossings at or left of the pixel's centre
        for (int x = 0; x < w; ++x) {
            const double px = x + 0.5;
            while (left < crossings.size() && crossings[left] <= px) ++left;
            if ((crossings.size() - left) % 2 == 1) m.set(x, y);
        }
    }
    return m;
}

// A whole base: an object that fills its tile or spans several (a mountain,
// a walled city, a building) shows the two front edges of its base as the
// bottom of its outline, a V at the tiles' slope (th / tw) from its left and
// right extremes down to its lowest point. Its base is the parallelogram
// those edges close. Found when the outline is at least 75 % of a tile wide
// (amplio2's mountains reach 85 %), each side of the V a quarter tile or
// more, and 75 % of each side's columns end within 3 px (plus 8 % of their
// distance from the lowest point) of the edge (a mountain's or a ruin's
// outline is ragged); the corners are the outermost columns that do.
bool find_whole_base(const Mask& est, int tw, int th, std::vector<std::pair<int, int>>& corners) {
    const int w = est.width, h = est.height;
    std::vector<int> bottom(std::size_t(std::max(0, w)), -1);
    int xl = -1, xr = -1, yb = -1;
    for (int x = 0; x < w; ++x) {
        for (int y = h - 1; y >= 0; --y)
            if (est.get(est.x0 + x, est.y0 + y)) {
                bottom[std::size_t(x)] = y;
                break;
            }
        if (bottom[std::size_t(x)] < 0) continue;
        if (xl < 0) xl = x;
        xr = x;
        yb = std::max(yb, bottom[std::size_t(x)]);
    }
    if (xl < 0 || xr - xl + 1 < 0.75 * tw) return false;
    double sum = 0;
    int n = 0;
    for (int x = xl; x <= xr; ++x)
        if (bottom[std::size_t(x)] >= yb - 1) sum += x, ++n;
    const double xb = sum / n + 0.5, k = double(th) / tw;  // the lowest point's column centre
    auto fits = [&](int x) {
        const double d = std::abs(x + 0.5 - xb), expected = yb - d * k;
        return bottom[std::size_t(x)] >= 0 && std::abs(bottom[std::size_t(x)] - expected) <= 3 + 0.08 * d;
    };
    int left = -1, right = -1, left_n = 0, left_fit = 0, right_n = 0, right_fit = 0;
    for (int x = xl; x <= xr; ++x) {
        const bool f = fits(x);
        if (x + 0.5 < xb) {
            ++left_n, left_fit += f;
            if (f && left < 0) left = x;
        } else {
            ++right_n, right_fit += f;
            if (f) right = x;
        }
    }
    if (left < 0 || right < 0 || xb - left < tw / 4.0 || right + 1 - xb < tw / 4.0) return false;
    if (left_fit < 0.75 * left_n || right_fit < 0.75 * right_n) return false;
    const double by = yb + 1.0;  // the lowest pixel's bottom edge
    const double lx = left, ly = by - (xb - left) * k, rx = right + 1.0, ry = by - (right + 1.0 - xb) * k;
    auto at = [&](double x, double y) { return std::pair<int, int>{int(std::lround(x)) + est.x0, int(std::lround(y)) + est.y0}; };
    corners = {at(lx, ly), at(xb, by), at(rx, ry), at(lx + rx - xb, ly + ry - by)};
    return true;
}

}  // namespace

namespace {

// Calls fn(region) with each region of the set pixels of a w x h grid
// (`set`, row by row, 0 or 1), each a list of indices y * w + x: the pixels
// joined through neighbours (8 of them with `diagonal`, else 4) for which
// joins(from, to) holds, in row-major order of their first pixel, so the
// same on every machine.
template <class Joins, class Fn>
void for_each_region(std::vector<std::uint8_t> set, int w, int h, bool diagonal, Joins joins, Fn fn) {
    std::vector<int> stack, region;
    for (int start = 0; start < w * h; ++start) {
        if (!set[std::size_t(start)]) continue;
        set[std::size_t(start)] = 0;
        stack.assign(1, start);
        region.clear();
        while (!stack.empty()) {
            const int i = stack.back();
            stack.pop_back();
            region.push_back(i);
            const int x = i % w, y = i / w;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if ((dx == 0 && dy == 0) || (!diagonal && dx != 0 && dy != 0)) continue;
                    const int nx = x + dx, ny = y + dy, n = ny * w + nx;
                    if (nx < 0 || ny < 0 || nx >= w || ny >= h || !set[std::size_t(n)] || !joins(i, n)) continue;
                    set[std::size_t(n)] = 0;
                    stack.push_back(n);
                }
        }
        fn(region);
    }
}

// Each 8-connected component of the set pixels (for_each_region).
template <class Fn>
void for_each_component(std::vector<std::uint8_t> set, int w, int h, Fn fn) {
    for_each_region(std::move(set), w, h, true, [](int, int) { return true; }, fn);
}

}  // namespace

// A grove painted as one sprite (LinCity-NG's tree2 and tree3) shows its
// trees apart only by colour: their canopies merge into one silhouette, and
// Algorithm 1 finds one run under it. A trunk is bark: an opaque pixel redder
// than it is green (r > g + 6, r >= b, r < 200; foliage and grass are
// greener, sand and stone greyer or brighter) and brown rather than orange
// or grey (bark_saturation_min and _max), in an 8-connected component at
// least 6 pixels tall, taller than wide, of 15 pixels or more (a berry, a
// flower or a speck of soil is smaller or wider). Components are found in
// row-major order, so the list is the same on every machine.
// Bark's saturation (max - min) / max, percent: LinCity-NG's bark is 41-56,
// the town tileset's 46; autumn crowns and tiled roofs, as red, are 72-84,
// stone walls in shade, as red, 18-20.
constexpr int bark_saturation_min = 30, bark_saturation_max = 65;

bool is_bark(const std::uint8_t* p) {
    return p[3] >= 128 && p[0] > p[1] + 6 && p[0] >= p[2] && p[0] < 200 &&
           (p[0] - std::min(p[1], p[2])) * 100 <= bark_saturation_max * p[0] &&
           (p[0] - std::min(p[1], p[2])) * 100 >= bark_saturation_min * p[0];
}

std::vector<TrunkFoot> find_trunks(const Image& image) {
    const int w = image.width, h = image.height;
    std::vector<std::uint8_t> bark(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) bark[std::size_t(y) * w + x] = is_bark(image.at(x, y));
    std::vector<TrunkFoot> feet;
    for_each_component(std::move(bark), w, h, [&](const std::vector<int>& component) {
        int x0 = w, x1 = -1, y0 = h, y1 = -1;
        for (int i : component)
            x0 = std::min(x0, i % w), x1 = std::max(x1, i % w), y0 = std::min(y0, i / w), y1 = std::max(y1, i / w);
        const int tall = y1 - y0 + 1, wide = x1 - x0 + 1;
        if (component.size() < 15 || tall < 6 || tall < wide) return;
        double sum = 0;
        int n = 0;
        for (int i : component)
            if (i / w >= y1 - 2) sum += i % w, ++n;
        feet.push_back({sum / n, y1});
    });
    return feet;
}

// A tree grows from its tile's ground: a foot off the floor diamond is a
// branch's (FreedroidRPG's trees show a dozen in their crowns). One trunk
// shaded in bands, or crossed by a bough, shows as pieces: feet closer on
// the ground (x / 2 + y and y - x / 2 apart) than an eighth of a tile's
// width, or in columns closer than a sixteenth, directly or through others,
// are one trunk standing on the lowest (a grove's trees stand further
// apart: LinCity's by 36 px or more on 128-px tiles; FreedroidRPG's pieces
// lie 14 px apart at most, Widelands' aspen's one column apart).
std::vector<TrunkFoot> trunks_on_tile(const std::vector<TrunkFoot>& found, int ax, int ay, int tw, int th) {
    std::vector<TrunkFoot> feet;
    for (const TrunkFoot& f : found)
        if (in_diamond(int(std::floor(f.x)), f.y, ax, ay, tw, th)) feet.push_back(f);
    std::vector<std::size_t> tree(feet.size());
    for (std::size_t k = 0; k < feet.size(); ++k) tree[k] = k;
    auto root = [&](std::size_t k) {
        while (tree[k] != k) k = tree[k];
        return k;
    };
    for (std::size_t i = 0; i < feet.size(); ++i)
        for (std::size_t j = i + 1; j < feet.size(); ++j) {
            const double dx = feet[j].x - feet[i].x, dy = feet[j].y - feet[i].y;
            if (std::hypot(dy + dx / 2, dy - dx / 2) < tw / 8.0 || std::abs(dx) < tw / 16.0) tree[root(j)] = root(i);
        }
    std::vector<TrunkFoot> trunks;
    for (std::size_t k = 0; k < feet.size(); ++k) {
        if (root(k) != k) continue;
        TrunkFoot lowest = feet[k];
        for (std::size_t j = 0; j < feet.size(); ++j)
            if (root(j) == k && feet[j].y > lowest.y) lowest = feet[j];
        trunks.push_back(lowest);
    }
    std::stable_sort(trunks.begin(), trunks.end(), [](const TrunkFoot& p, const TrunkFoot& q) { return p.x < q.x; });
    return trunks;
}

// A grove's crowns (footprint.hpp). Crowns touch and overlap, but each is
// painted in one colour that shades smoothly across it, and two crowns meet
// at a jump in colour or a dark outline: a region grows over 4-neighbours
// whose colours differ by less than crown_colour_step (the sum of the
// channels' differences), through no bark and no outline (darker than
// crown_outline_luminance). The town's crowns change by 2-20 a step inside
// and 40 or more between them; a region under crown_share of the object's
// pixels is a highlight, a seam or a leaf, not a crown.
constexpr int crown_colour_step = 30;
constexpr double crown_outline_luminance = 40.0 / 255.0, crown_share = 0.05;

std::vector<Mask> crown_regions(const Image& sprite, const Mask& object) {
    const int w = object.width, h = object.height;
    auto pixel = [&](int i) { return sprite.at(object.x0 + i % w, object.y0 + i / w); };
    std::vector<std::uint8_t> open(std::size_t(w) * h, 0);
    for (int i = 0; i < w * h; ++i)
        open[std::size_t(i)] = object.bits[std::size_t(i)] && !is_bark(pixel(i)) && luminance(pixel(i)) >= crown_outline_luminance;
    const long least = std::max(16L, long(std::ceil(crown_share * double(object.count()))));
    std::vector<Mask> crowns;
    const auto alike = [&](int i, int n) {
        const std::uint8_t *p = pixel(i), *q = pixel(n);
        return std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) < crown_colour_step;
    };
    for_each_region(std::move(open), w, h, false, alike, [&](const std::vector<int>& region) {
        if (long(region.size()) < least) return;
        Mask crown(object.rect());
        for (int i : region) crown.bits[std::size_t(i)] = 1;
        crowns.push_back(std::move(crown));
    });
    return crowns;
}

std::string_view to_string(FootprintMode m) {
    switch (m) {
        case FootprintMode::automatic: return "auto";
        case FootprintMode::paper: return "paper";
        case FootprintMode::none: return "none";
        case FootprintMode::run: return "run";
        case FootprintMode::polygon: return "polygon";
    }
    return "auto";
}

std::string_view to_string(ObjectModel m) {
    switch (m) {
        case ObjectModel::revolution: return "revolution";
        case ObjectModel::prism: return "prism";
        case ObjectModel::mound: return "mound";
    }
    return "revolution";
}

std::optional<ObjectModel> object_model_named(std::string_view name) {
    for (ObjectModel m : {ObjectModel::revolution, ObjectModel::prism, ObjectModel::mound})
        if (to_string(m) == name) return m;
    return std::nullopt;
}

namespace {

// The object's parts that stand apart on the tile (footprint.hpp): its
// 8-connected components of at least part_share of its pixels (and 16),
// whose lowest pixel lies on the floor diamond; none unless two or more.
constexpr double part_share = 0.02;

std::vector<ObjectPart> standing_parts(const Mask& est, int ax, int ay, int tw, int th, int delta_y) {
    const long total = est.count(), least = std::max(16L, long(std::ceil(part_share * double(total))));
    const int w = est.width;
    std::vector<ObjectPart> parts;
    // A mask only for a part (at most 1 / part_share of them), so a sprite
    // of many specks stays linear in its pixels.
    for_each_component(est.bits, w, est.height, [&](const std::vector<int>& component) {
        int lowest = component[0];
        for (int i : component)
            if (i / w > lowest / w || (i / w == lowest / w && i % w < lowest % w)) lowest = i;
        if (long(component.size()) < least || !in_diamond(est.x0 + lowest % w, est.y0 + lowest / w, ax, ay, tw, th))
            return;
        Mask part(est.rect());
        for (int i : component) part.bits[std::size_t(i)] = 1;
        Mask foot = sprite_obstacle(part, delta_y);
        parts.push_back({std::move(part), std::move(foot)});
    });
    if (parts.size() < 2) parts.clear();
    return parts;
}

Mask footprint_by_mode(const Image& sprite, const Mask& opacity, int ax, int ay, int tw, int th, int delta_y,
                       FootprintMode mode, const FootprintSpec& spec, FootprintReport& rep);

}  // namespace

Mask sprite_footprint(const Image& sprite, const Mask& opacity, int ax, int ay, int tw, int th, int delta_y,
                      FootprintMode mode, const FootprintSpec& spec, FootprintReport* report) {
    FootprintReport local;
    FootprintReport& rep = report ? *report : local;
    rep = FootprintReport{};
    Mask footprint = footprint_by_mode(sprite, opacity, ax, ay, tw, th, delta_y, mode, spec, rep);
    rep.trunks = trunks_on_tile(find_trunks(sprite), ax, ay, tw, th);
    if (rep.trunks.size() >= 2 && !rep.whole_base) rep.crowns = crown_regions(sprite, rep.estimate);
    // A footprint the manifest draws, or a whole base, is the object's own.
    if ((mode == FootprintMode::automatic || mode == FootprintMode::paper) && !rep.whole_base)
        rep.parts = standing_parts(rep.estimate, ax, ay, tw, th, delta_y);
    return footprint;
}

namespace {

Mask footprint_by_mode(const Image& sprite, const Mask& opacity, int ax, int ay, int tw, int th, int delta_y,
                       FootprintMode mode, const FootprintSpec& spec, FootprintReport& rep) {
    const int w = opacity.width, h = opacity.height;
    switch (mode) {
        case FootprintMode::none: rep.estimate = opacity; return Mask(Rect{0, 0, w, h});
        case FootprintMode::run: rep.estimate = opacity; return mark_run(w, h, spec.run_x, spec.run_y, spec.run_length);
        case FootprintMode::polygon: rep.estimate = opacity; return fill_polygon(w, h, spec.polygon);
        case FootprintMode::paper: rep.estimate = opacity; return sprite_obstacle(opacity, delta_y, &rep.trace);
        case FootprintMode::automatic: break;
    }
    Mask est = opacity;
    // 1. Baked shadows: translucent dark pixels belong to no object. Only
    // when there are enough of them to be a shadow (1% of the opaque pixels),
    // not the antialiased edge of a dark trunk.
    long shadow = 0, solid = 0;
    auto is_shadow = [&](int x, int y) {
        const std::uint8_t* p = sprite.at(x, y);
        return p[3] / 255.0 < spec.shadow_alpha && luminance(p) < spec.shadow_luminance;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (est.get(x, y)) {
                ++solid;
                shadow += is_shadow(x, y);
            }
    if (shadow > 0 && shadow * 100 >= solid) {
        rep.baked_shadow = true;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (est.get(x, y) && is_shadow(x, y)) est.set(x, y, false);
    }
    // The outline's V (find_whole_base) is read before a baked ground
    // diamond is taken out: a mountain's skirt of grass is its base's edge.
    std::vector<std::pair<int, int>> base;
    const bool v_shaped = find_whole_base(est, tw, th, base);
    const Mask before_ground = est;
    int ground[3] = {0, 0, 0};
    auto is_ground = [&](int x, int y) {
        const std::uint8_t* p = sprite.at(x, y);
        double d = 0;
        for (int k = 0; k < 3; ++k) d += double(p[k] - ground[k]) * double(p[k] - ground[k]);
        return std::sqrt(d / 3) / 255.0 <= spec.ground_tolerance;
    };
    // 2. A baked ground diamond: the floor diamond's half below the anchor,
    // where an object standing on the anchor rarely reaches, is mostly opaque,
    // and the band just outside its lower edges mostly transparent (a diamond,
    // not roots or a wide base spreading past it). Its colour is the median of
    // the diamond's outer ring.
    long below = 0, opaque = 0, band = 0, band_opaque = 0;
    std::array<std::vector<int>, 3> ring;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!in_diamond(x, y, ax, ay, tw, th)) {
                if (y >= ay && in_diamond(x, y, ax, ay, tw, th, 1.2)) {
                    ++band;
                    band_opaque += est.get(x, y);
                }
                continue;
            }
            if (y >= ay) {
                ++below;
                opaque += est.get(x, y);
            }
            if (est.get(x, y) && !in_diamond(x, y, ax, ay, tw, th, 0.8))
                for (int k = 0; k < 3; ++k) ring[std::size_t(k)].push_back(sprite.at(x, y)[k]);
        }
    const bool diamond_shaped = band == 0 || band_opaque * 10 <= band * 3;
    if (below > 0 && opaque * 10 >= below * 7 && diamond_shaped && !ring[0].empty()) {
        rep.baked_ground = true;
        for (int k = 0; k < 3; ++k) {
            auto& v = ring[std::size_t(k)];
            std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
            ground[k] = v[v.size() / 2];
        }
        // Ground-coloured pixels of the diamond are the ground, and so is
        // whatever of the diamond the object does not reach: keep the diamond
        // pixels connected to the object above it through non-ground pixels.
        Mask object(Rect{0, 0, w, h});
        std::vector<std::pair<int, int>> stack;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (est.get(x, y) && !in_diamond(x, y, ax, ay, tw, th)) {
                    object.set(x, y);
                    stack.push_back({x, y});
                }
        while (!stack.empty()) {
            const auto [x, y] = stack.back();
            stack.pop_back();
            for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                const int nx = x + dx, ny = y + dy;
                if (!est.get(nx, ny) || object.get(nx, ny) || !in_diamond(nx, ny, ax, ay, tw, th) || is_ground(nx, ny))
                    continue;
                object.set(nx, ny);
                stack.push_back({nx, ny});
            }
        }
        est = object;
    }
    rep.estimate = est;
    // 3. An object that fills its tile or spans several stands on its whole
    // base, not on a run at its front: when the object's own pixels (the
    // ground taken out) cover half its base or more. A tree on a baked grass
    // diamond has the diamond's V but covers a few percent of it. An object
    // that fills its tile (a mountain) reads as a baked diamond too, and the
    // diamond's test takes most of it for ground, its rock being near the
    // ring's colour; but an eighth of its base or more is not that colour
    // (amplio2's mountains: 16 % and 28 %; LinCity-NG's trees on their grass
    // diamonds: 5 % and 6 %): then it is all object, and no ground is baked.
    if (v_shaped) {
        const Mask whole = fill_polygon(w, h, base);
        long in = 0, covered = 0, coloured = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (whole.get(x, y)) {
                    ++in;
                    covered += est.get(x, y);
                    coloured += before_ground.get(x, y) && !is_ground(x, y);
                }
        const bool fills = in > 0 && covered * 2 >= in;
        const bool fills_its_tile = in > 0 && rep.baked_ground && coloured * 8 >= in;
        if (fills || fills_its_tile) {
            if (fills_its_tile && !fills) {
                est = before_ground;
                rep.baked_ground = false;
                rep.estimate = est;
            }
            rep.whole_base = true;
            rep.base = base;
            return whole;
        }
    }
    // 4. Algorithm 1 on what is left, its Δy scaled with the tile (the paper's
    // 25 lines are for 128-pixel tiles).
    const int lines = std::max(1, int(std::lround(delta_y * tw / 128.0)));
    return sprite_obstacle(est, lines, &rep.trace);
}

}  // namespace

Mask tileset_footprint(const Tileset& ts, const Sprite& s, const Params& p, FootprintReport* report) {
    const Mask op = opacity_map(s.image, sprite_threshold(s, p.opacity_threshold));
    const FootprintMode mode = s.footprint.mode.value_or(p.footprint == Footprint::paper ? FootprintMode::paper
                                                                                         : FootprintMode::automatic);
    return sprite_footprint(s.image, op, s.anchor_x, s.anchor_y, ts.tile_width, ts.tile_height, p.delta_y, mode,
                            s.footprint, report);
}

std::int64_t footprint_pixels(int w, int h, const FootprintSpec& spec) {
    const std::int64_t algorithm1 = std::int64_t(w) * (2 * (w / 4) + 1);
    const std::int64_t run = std::int64_t(w) * (h + 2 * (std::max(0, spec.run_length) / 4));
    return std::max({algorithm1, run, std::int64_t(w) * h});
}

bool mask_centre(const Mask& m, double& x, double& y, Rect& box) {
    long n = 0;
    double sx = 0, sy = 0;
    int x0 = 1 << 30, y0 = 1 << 30, x1 = -(1 << 30), y1 = -(1 << 30);
    for (int j = 0; j < m.height; ++j)
        for (int i = 0; i < m.width; ++i)
            if (m.bits[std::size_t(j) * m.width + i]) {
                const int px = m.x0 + i, py = m.y0 + j;
                ++n, sx += px + 0.5, sy += py + 0.5;
                x0 = std::min(x0, px), y0 = std::min(y0, py), x1 = std::max(x1, px), y1 = std::max(y1, py);
            }
    if (n == 0) return false;
    x = sx / double(n);
    y = sy / double(n);
    box = {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
    return true;
}

}  // namespace isolux
