// Beyond the paper: solids fitted to a sprite's silhouette (solid_estimate.hpp).
#include "isolux/solid_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "isolux/footprint.hpp"

namespace isolux {

namespace {

constexpr double sqrt2 = 1.4142135623730951;
// How many columns an axis whose foot moved off the footprint may move
// sideways: the rounding of a footprint's centre on an equator's lines.
constexpr int axis_shift = 2;
// The foot search's budget, in disc-row tests: it fits a solid at each row
// below the footprint in up to 1 + 2 * axis_shift columns, each fit a disc
// per pixel of height, each disc 16 bisections over its rows. An object
// whose search would cost more (a sprite a thousand pixels tall) keeps the
// footprint's foot: the search is a refinement, and its cost grows with the
// fourth power of the object's size.
constexpr double foot_search_budget = 2e10;
// How much better (in silhouette_fit) a prism or a mound must fit an object
// than its solid of revolution to replace it.
constexpr double model_fit_margin = 0.03;
// The V of a prism's front corners: the share of the columns below which a
// column's ground line may lie (eaves and rails stand above the ground; none
// stands below it), and the distance, pixels, within which a column is on it.
constexpr double prism_ground_quantile = 0.75;
constexpr double prism_on_ground = 1.5;
// The share of an object's columns whose lowest pixel must lie on a prism's
// V for the rule to pick it: a box's lie on it in most columns; a tree's
// are its crown's rounded underside, with only a trunk's or a conifer's
// lowest boughs' columns on any V (RealArt.otherGamesTreesStaySolidsOfRevolution).
constexpr double prism_v_share = 0.75;
// How far apart, pixels, the 10 % and 90 % quantiles of a prism's column
// rises may lie for its top to be flat (rounding, a hedge's leaves).
constexpr double prism_flat_spread = 2;
// The jump between neighbouring columns' rises, as a share of a prism's
// height, from which it is boxes side by side and steps (step_prism).
constexpr double prism_step_jump = 1.0 / 3;
// How much better than both other models a low prism off its V must fit.
constexpr double prism_clear_margin = 0.05;
// How far above a mound's base centre, pixels, the middle of its widest
// rows may lie (a dome's widest rows straddle its base's centre; a crown's
// its equator, above the ground).
constexpr double mound_equator_rise = 3;
// ... or this share of its base's depth on screen, where that is more.
constexpr double mound_equator_share = 0.1;
// How much less a pitched roof's top rows must miss the object's than a
// flat top's (ridge_prism), and how far, pixels, its ridge must rise above
// its eaves.
constexpr double ridge_fit_margin = 0.25;
constexpr int ridge_least_rise = 3;
// How much better than the dome alone, at most, the union of a mound's dome
// and the object's solid of revolution may fit its silhouette for the
// mound to be a heap of both (the union hides nothing the dome does not).
constexpr double heap_fit_gain = 0.01;
// How much better than the dome a peak's cone must fit a mound's silhouette.
constexpr double cone_fit_margin = 0.05;

// Per row of the object's mask: the opaque run through column `c`, as the
// first and last column (first > last: column c is transparent there).
struct RunsThrough {
    int y0 = 0;
    std::vector<int> first, last;
};

RunsThrough runs_through(const Mask& m, int c) {
    RunsThrough r;
    r.y0 = m.y0;
    r.first.assign(std::size_t(m.height), 1);
    r.last.assign(std::size_t(m.height), 0);
    for (int j = 0; j < m.height; ++j) {
        const int y = m.y0 + j;
        if (!m.get(c, y)) continue;
        int a = c, b = c;
        while (m.get(a - 1, y)) --a;
        while (m.get(b + 1, y)) ++b;
        r.first[std::size_t(j)] = a;
        r.last[std::size_t(j)] = b;
    }
    return r;
}

// Whether the disc of radius r at screen centre (fx, yc) lies within two
// masks' runs through its axis's column (both of one rectangle): on every
// row its ellipse's pixel centres reach no further left than `left`'s run
// and no further right than `right`'s, neither run empty. Such a row's
// pixels always include column floor(fx), so the runs decide.
bool disc_within(const RunsThrough& left, const RunsThrough& right, double fx, double yc, double r) {
    const double a = r * sqrt2, b = r / sqrt2;
    const int y_top = int(std::floor(yc - b - 0.5)), y_bottom = int(std::ceil(yc + b - 0.5));
    for (int y = y_top; y <= y_bottom; ++y) {
        const double v = (y + 0.5 - yc) / b;
        if (v * v > 1) continue;
        const double hw = a * std::sqrt(1 - v * v);
        const int x0 = int(std::ceil(fx - hw - 0.5)), x1 = int(std::floor(fx + hw - 0.5));
        if (x0 > x1) continue;  // no pixel centre on this row
        const int j = y - left.y0;
        if (j < 0 || j >= int(left.first.size())) return false;
        const std::size_t k = std::size_t(j);
        if (left.first[k] > left.last[k] || right.first[k] > right.last[k]) return false;
        if (x0 < left.first[k] || x1 > right.last[k]) return false;
    }
    return true;
}

// Whether the disc fits the object whose runs are `runs`: every pixel its ellipse holds is opaque.
bool disc_fits(const RunsThrough& runs, double fx, double yc, double r) { return disc_within(runs, runs, fx, yc, r); }

}  // namespace

bool EstimatedObject::holds(std::size_t z, double x, double y) const {
    const double d = radius[z], a = across_at(z);
    if (d <= 0) return false;
    if (model == ObjectModel::prism)
        return std::abs(x) <= half_x && std::abs(y) <= half_y &&
               ((steps.empty() && ridge_axis < 0) || double(z) < top_at(x, y)) && behind_front(x, y) && in_hull(z, x, y);
    const double u = (x - y) / sqrt2, v = (x + y) / sqrt2;  // across the view, in depth
    return (u * u) / (a * a) + (v * v) / (d * d) <= 1;
}

bool EstimatedObject::in_hull(std::size_t z, double x, double y) const {
    // The level's middle, z + 1/2 high, shows at screen (x - y, (x + y) / 2 - z - 1/2) from the foot.
    return hull_shows(int(std::floor(center_x + x - y)), int(std::floor(center_y + (x + y) / 2 - double(z) - 0.5)));
}

namespace {

// The entry of a per-column table (a prism's steps or fronts) for screen
// column sx relative to the axis: columns from -reach, one a pixel, the
// outermost standing for any beyond.
double column_entry(const std::vector<double>& table, double sx, double reach) {
    const double i = std::floor(sx + reach);
    return table[std::size_t(std::clamp(i, 0.0, double(table.size() - 1)))];
}

}  // namespace

double EstimatedObject::step_at(double sx) const {
    return steps.empty() ? height() : column_entry(steps, sx, half_x + half_y);
}

double EstimatedObject::top_at(double x, double y) const {
    const double step = step_at(x - y);
    if (ridge_axis < 0) return step;
    const double off = ridge_axis == 0 ? std::abs(y) / half_y : std::abs(x) / half_x;
    return std::min(step, height() - (height() - eaves) * std::min(off, 1.0));
}

double EstimatedObject::front_at(double sx) const {
    return fronts.empty() ? std::numeric_limits<double>::infinity() : column_entry(fronts, sx, half_x + half_y);
}

bool EstimatedObject::span_at(double x, double y, double& z_low, double& z_high) const {
    int lo = -1, hi = -1;
    for (std::size_t z = 0; z < radius.size(); ++z)
        if (holds(z, x, y)) {
            if (lo < 0) lo = int(z);
            hi = int(z);
        }
    if (lo < 0) return false;
    z_low = lo;
    z_high = hi + 1;
    return true;
}

bool EstimatedObject::contains(Vec3 p) const {
    if (p.z < 0 || p.z >= height()) return false;
    return holds(std::size_t(p.z), p.x, p.y);
}

Vec3 EstimatedObject::normal_at(Vec3 p) const {
    const Vec3 up{0, 0, 1};
    if (radius.empty()) return up;
    if (model == ObjectModel::prism) {
        const double to_top = std::abs(top_at(p.x, p.y) - p.z);
        const double to_x = half_x - std::abs(p.x), to_y = half_y - std::abs(p.y);
        if (to_top <= to_x && to_top <= to_y) {
            if (ridge_axis < 0) return up;
            // A roof's slope falls (height - eaves) over the half-width across its ridge.
            const double fall = height() - eaves;
            const Vec3 n = ridge_axis == 0 ? Vec3{0, (p.y < 0 ? -1 : 1) * fall / half_y, 1}
                                           : Vec3{(p.x < 0 ? -1 : 1) * fall / half_x, 0, 1};
            return glm::normalize(n);
        }
        return to_x <= to_y ? Vec3{p.x < 0 ? -1 : 1, 0, 0} : Vec3{0, p.y < 0 ? -1 : 1, 0};
    }
    const long n = long(radius.size()), level = std::clamp(long(std::floor(p.z)), 0L, n - 1);
    // Below the ground a cross-section is the lowest's; above the top, none.
    auto depth = [&](long k) { return k >= n ? 0.0 : radius[std::size_t(std::max(k, 0L))]; };
    auto wide = [&](long k) { return k >= n ? 0.0 : across_at(std::size_t(std::max(k, 0L))); };
    const double d = depth(level), a = wide(level);
    if (!(d > 0 && a > 0)) return up;
    const double dd = (depth(level + 1) - depth(level - 1)) / 2, da = (wide(level + 1) - wide(level - 1)) / 2;
    const double u = (p.x - p.y) / sqrt2, v = (p.x + p.y) / sqrt2;  // across the view, in depth
    const double gu = u / (a * a), gv = v / (d * d), gz = -(u * u * da / (a * a * a) + v * v * dd / (d * d * d));
    const Vec3 g{(gu + gv) / sqrt2, (gv - gu) / sqrt2, gz};
    const double len = glm::length(g);
    return len > 0 ? g / len : up;
}

namespace {

// The object's top row: nothing of it stands above (y0 + height when empty).
int top_row(const Mask& object) {
    for (int j = 0; j < object.height; ++j)
        for (int i = 0; i < object.width; ++i)
            if (object.bits[std::size_t(j) * object.width + i]) return object.y0 + j;
    return object.y0 + object.height;
}

// The discs of a solid whose axis meets the ground at screen (fx, fy): one
// per pixel of height, from the ground up to the outline's top row, each the
// largest that fits (a bisection: a smaller disc of the same centre fits
// wherever a larger one does), so the solid is the largest of its kind the
// outline allows. A dome's outline reaches above its top, and the discs up
// there are small. With `flat_top` the discs stop once their ellipses reach
// the top row: a flat roof seen from above is one disc's ellipse. With
// `height` (a user's correction) exactly that many discs, one that does not
// fit taking the radius of the one below.
template <class Fits>
std::vector<double> fit_discs_by(Fits&& fits, double fy, int top, double widest, bool flat_top, int height = 0) {
    std::vector<double> radius;
    double reached = fy;  // the highest screen row the discs' ellipses reach
    for (int z = 0;; ++z) {
        const double yc = fy - (z + 0.5);
        if (height > 0 ? z >= height : (yc < top || (flat_top && reached <= top + 0.5))) break;
        double r = 0;
        if (fits(yc, 0.5)) {
            double lo = 0.5, hi = widest;
            for (int k = 0; k < 16; ++k) {
                const double mid = (lo + hi) / 2;
                (fits(yc, mid) ? lo : hi) = mid;
            }
            r = lo;
        }
        if (r == 0 && height > 0 && !radius.empty()) r = radius.back();
        radius.push_back(r);
        if (r > 0) reached = std::min(reached, yc - r / sqrt2);
    }
    while (!radius.empty() && radius.back() == 0) radius.pop_back();
    return radius;
}

std::vector<double> fit_discs(const RunsThrough& runs, double fx, double fy, int top, double widest, bool flat_top,
                              int height = 0) {
    return fit_discs_by([&](double yc, double r) { return disc_fits(runs, fx, yc, r); }, fy, top, widest, flat_top, height);
}

// The object's pixels, and per row how many of them lie left of each column,
// so that a row's count between two columns is two reads.
struct ObjectPixels {
    const Mask& mask;
    std::vector<int> before;  // per row, width + 1 counts

    explicit ObjectPixels(const Mask& m) : mask(m), before(std::size_t(m.height) * std::size_t(m.width + 1), 0) {
        for (int j = 0; j < m.height; ++j) {
            int* row = &before[std::size_t(j) * std::size_t(m.width + 1)];
            for (int i = 0; i < m.width; ++i) row[i + 1] = row[i] + (m.bits[std::size_t(j) * m.width + i] != 0);
        }
    }
    // The object's pixels of row y in columns [x0, x1].
    long in_row(int y, int x0, int x1) const {
        const int j = y - mask.y0;
        if (j < 0 || j >= mask.height) return 0;
        x0 = std::max(x0 - mask.x0, 0), x1 = std::min(x1 - mask.x0, mask.width - 1);
        if (x0 > x1) return 0;
        const int* row = &before[std::size_t(j) * std::size_t(mask.width + 1)];
        return row[x1 + 1] - row[x0];
    }
};

// How many of the object's pixels the discs' ellipses cover (the pixels
// solid_silhouette draws there). The discs share their axis, so on a row
// their runs are nested: the widest disc's run is the union of them all.
long covered(const ObjectPixels& object, const EstimatedObject& o) {
    const Mask& m = object.mask;
    std::vector<double> widest(std::size_t(m.height), -1);  // per row: the widest run's half-width
    for (std::size_t z = 0; z < o.radius.size(); ++z) {
        const double r = o.radius[z], a = o.across_at(z) * sqrt2, b = r / sqrt2, yc = o.center_y - (double(z) + 0.5);
        if (r <= 0) continue;
        for (int y = std::max(int(std::floor(yc - b)), m.y0); y <= std::min(int(std::ceil(yc + b)), m.y0 + m.height - 1); ++y) {
            const double v = (y + 0.5 - yc) / b;
            if (v * v > 1) continue;
            double& w = widest[std::size_t(y - m.y0)];
            w = std::max(w, a * std::sqrt(1 - v * v));
        }
    }
    long n = 0;
    for (int j = 0; j < m.height; ++j) {
        const double hw = widest[std::size_t(j)];
        if (hw < 0 || m.y0 + j < 0) continue;  // solid_silhouette draws no row above 0
        const int x0 = std::max(int(std::ceil(o.center_x - hw - 0.5)), 0);
        n += object.in_row(m.y0 + j, x0, int(std::floor(o.center_x + hw - 0.5)));
    }
    return n;
}

// The widest disc's height (the lowest of equals).
std::size_t widest_disc(const EstimatedObject& o) {
    return std::size_t(std::max_element(o.radius.begin(), o.radius.end()) - o.radius.begin());
}

// The discs below the widest stand on a hidden stem when the widest hides
// them (hidden_below_widest): each keeps at most hidden_stem_ratio of the
// widest radius. The largest discs that fit would otherwise stand a cone of
// foliage on the ground, and a low light would cast its shadow far too wide.
void stand_on_hidden_stem(const Mask& object, EstimatedObject& o) {
    if (!hidden_below_widest(object, o)) return;
    const std::size_t widest = widest_disc(o);
    const double stem = hidden_stem_ratio * o.radius[widest];
    for (std::size_t z = 0; z < widest; ++z) o.radius[z] = std::min(o.radius[z], stem);
}

// Each disc widened across the view to the silhouette's half-width (on its
// narrower side) on the row where the disc's centre shows: a cross-section
// there reaches that far left and right of the axis, and no farther. The
// largest disc that fits stops at the narrowest part of its ellipse (a
// bush's or a rock's lower front), while side lobes standing low (a bush's
// smaller clumps) show as the silhouette's width at their height. The
// depth stays the disc's radius: the silhouette cannot tell it. Discs on a
// hidden stem stay round: the rows where they show are the foliage's.
void widen_across_view(const Mask& object, EstimatedObject& o) {
    const std::size_t stem_below = hidden_below_widest(object, o) ? widest_disc(o) : 0;
    const RunsThrough runs = runs_through(object, int(std::floor(o.center_x)));
    o.across = o.radius;
    for (std::size_t z = stem_below; z < o.radius.size(); ++z) {
        if (o.radius[z] <= 0) continue;
        const int j = int(std::floor(o.center_y - (double(z) + 0.5))) - runs.y0;
        if (j < 0 || j >= int(runs.first.size()) || runs.first[std::size_t(j)] > runs.last[std::size_t(j)]) continue;
        const double half = std::min(o.center_x - runs.first[std::size_t(j)], runs.last[std::size_t(j)] + 1 - o.center_x);
        o.across[z] = std::max(o.radius[z], half / sqrt2);
    }
}

// A solid standing at one foot, and how many of the object's pixels it covers.
struct FootCandidate {
    EstimatedObject object;
    long covered = 0;
};

// `runs`: the object's runs through the axis's column.
FootCandidate fit_at(const ObjectPixels& object, const EstimatedObject& o, const RunsThrough& runs, double fx, double fy,
                     int top, double widest, int height) {
    FootCandidate f{o, 0};
    f.object.center_x = fx;
    f.object.center_y = fy;
    f.object.radius = fit_discs(runs, fx, fy, top, widest, false, height);
    f.covered = covered(object, f.object);
    return f;
}

// The best of `best` and the feet in column (footprint column + dx), from the
// footprint's row (the row below it in the footprint's own column) down to
// the object's lowest row there: the one covering most, the first among equals.
FootCandidate lowest_best_foot(const ObjectPixels& object, const EstimatedObject& o, int c, int dx, int top,
                               double widest, int height, FootCandidate best) {
    const RunsThrough runs = runs_through(object.mask, c + dx);
    int bottom = int(std::floor(o.center_y));
    for (int j = 0; j < int(runs.first.size()); ++j)
        if (runs.first[std::size_t(j)] <= runs.last[std::size_t(j)]) bottom = std::max(bottom, runs.y0 + j);
    for (double fy = o.center_y + (dx == 0 ? 1 : 0); fy <= bottom + 1; fy += 1) {
        FootCandidate t = fit_at(object, o, runs, o.center_x + dx, fy, top, widest, height);
        if (t.covered > best.covered) best = std::move(t);
    }
    return best;
}

// Whether any pixel of `part` has its centre inside the ellipse a disc of
// radius r shows as at screen centre (fx, yc).
bool disc_touches(const Mask& part, double fx, double yc, double r) {
    const double a = r * sqrt2, b = r / sqrt2;
    for (int y = int(std::floor(yc - b - 0.5)); y <= int(std::ceil(yc + b - 0.5)); ++y) {
        const double v = (y + 0.5 - yc) / b;
        if (v * v > 1) continue;
        const double hw = a * std::sqrt(1 - v * v);
        for (int x = int(std::ceil(fx - hw - 0.5)); x <= int(std::floor(fx + hw - 0.5)); ++x)
            if (part.get(x, y)) return true;
    }
    return false;
}

// A tree of a grove: where it stands, and the pixels that show it.
struct GroveTree {
    double x = 0;  // the foot's pixel column (its centre is x + 0.5)
    int y = 0;     // the foot's pixel row
    bool hidden = false;  // no trunk shows: its foot was inferred from its crown
    Mask part;
    Mask crown;  // its crowns' pixels (crown_regions; empty: the colours parted none)
};

// The share of a hidden trunk's column, from its crown down to its foot,
// that must be opaque: a trunk that would show is not hidden.
constexpr double hidden_trunk_cover = 0.8;

// A grove's trees from its crowns (crown_regions) and the trunks that show
// (docs/beyond.md, *Groves*). Each trunk takes the crown its column meets
// first going up from its foot. A crown no trunk takes is a tree whose
// trunk is hidden behind the trees in front, when its column is opaque from
// the crown down to where the trunk's foot would be: its crown's top row
// plus the median of the trunk trees' (foot row - crown top row), under
// the middle of its top; a foot within a quarter of the crown's width of
// another tree's on the ground is that tree's (one crown in two colours).
// The object's other pixels (outlines, trunks, seams) go to the tree of
// the nearest crown or trunk pixel. Empty where a trunk meets no crown of
// its own, so the caller keeps what the trunks alone give.
std::vector<GroveTree> grove_trees(const Mask& object, const std::vector<TrunkFoot>& feet, const std::vector<Mask>& crowns) {
    const int w = object.width, h = object.height;
    std::vector<int> owner(std::size_t(w) * h, -1);  // per object pixel: its tree
    // Each crown's columns and lowest row. A region over two trunks' columns
    // is foliage the colours did not part (LinCity-NG's leaves, textured
    // pixel by pixel), not one crown.
    struct Extent {
        int x0, x1, y1;
    };
    std::vector<Extent> extent;
    for (const Mask& crown : crowns) {
        Extent e{w, -1, -1};
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                if (crown.bits[std::size_t(j) * w + i]) e.x0 = std::min(e.x0, i), e.x1 = std::max(e.x1, i), e.y1 = j;
        int over = 0;
        for (const TrunkFoot& f : feet) over += f.x >= object.x0 + e.x0 && f.x < object.x0 + e.x1 + 1;
        if (over >= 2) return {};
        extent.push_back(e);
    }
    std::vector<GroveTree> trees;
    std::vector<int> crown_tree(crowns.size(), -1);
    std::vector<double> lifts;
    for (const TrunkFoot& f : feet) {
        const int c = int(std::floor(f.x));
        int crown = -1;
        for (int y = f.y; y >= object.y0 && crown < 0; --y)
            for (std::size_t k = 0; k < crowns.size() && crown < 0; ++k)
                if (crowns[k].get(c, y)) crown = int(k);
        if (crown < 0 || crown_tree[std::size_t(crown)] >= 0) return {};
        crown_tree[std::size_t(crown)] = int(trees.size());
        lifts.push_back(f.y - top_row(crowns[std::size_t(crown)]));
        trees.push_back({f.x, f.y, false, Mask(object.rect())});
    }
    std::nth_element(lifts.begin(), lifts.begin() + std::ptrdiff_t(lifts.size() / 2), lifts.end());
    const int lift = int(std::lround(lifts[lifts.size() / 2]));
    for (std::size_t k = 0; k < crowns.size(); ++k) {
        if (crown_tree[k] >= 0) continue;
        const auto [x0, x1, y1] = extent[k];
        // The axis shows at the crown's top (its two highest rows), which the
        // trees in front, standing lower on screen, hide last.
        const int top = top_row(crowns[k]);
        double sum = 0;
        int n = 0;
        for (int y = top; y < top + 2; ++y)
            for (int i = x0; i <= x1; ++i)
                if (crowns[k].get(object.x0 + i, y)) sum += object.x0 + i, ++n;
        const double fx = sum / n;
        const int fy = top + lift, c = int(std::floor(fx));
        int opaque = 0, rows = 0;
        for (int y = object.y0 + y1 + 1; y < fy; ++y, ++rows) opaque += object.get(c, y);
        if (fy <= object.y0 + y1 || opaque < hidden_trunk_cover * rows) continue;
        const double near = (x1 - x0 + 1) / 4.0 / sqrt2;  // a quarter of the crown's width, on the ground
        int joins = -1;
        for (std::size_t t = 0; t < trees.size() && joins < 0; ++t) {
            const double dx = trees[t].x - fx, dy = trees[t].y - fy;
            if (std::hypot(dy + dx / 2, dy - dx / 2) < near) joins = int(t);
        }
        if (joins < 0) {
            joins = int(trees.size());
            trees.push_back({fx, fy, true, Mask(object.rect())});
        }
        crown_tree[k] = joins;
    }
    // Seeds: the crowns, and each trunk's column from its foot up to its crown.
    std::vector<int> queue;
    for (std::size_t k = 0; k < crowns.size(); ++k)
        if (crown_tree[k] >= 0)
            for (int i = 0; i < w * h; ++i)
                if (crowns[k].bits[std::size_t(i)] && owner[std::size_t(i)] < 0) owner[std::size_t(i)] = crown_tree[k], queue.push_back(i);
    for (std::size_t t = 0; t < trees.size(); ++t) {
        if (trees[t].hidden) continue;
        const int c = int(std::floor(trees[t].x)) - object.x0;
        for (int j = trees[t].y - object.y0; j >= 0; --j) {
            if (j >= h) continue;
            bool any = false;
            for (int i = std::max(c - 2, 0); i <= std::min(c + 2, w - 1); ++i) {
                const int n = j * w + i;
                if (!object.bits[std::size_t(n)] || owner[std::size_t(n)] >= 0) continue;
                owner[std::size_t(n)] = int(t), queue.push_back(n), any = true;
            }
            if (!any && j < trees[t].y - object.y0 - 2) break;
        }
    }
    // The rest, breadth first from the seeds (in their order: deterministic).
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const int i = queue[q], x = i % w, y = i / w;
        for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
            const int nx = x + dx, ny = y + dy, n = ny * w + nx;
            if (nx < 0 || ny < 0 || nx >= w || ny >= h || !object.bits[std::size_t(n)] || owner[std::size_t(n)] >= 0) continue;
            owner[std::size_t(n)] = owner[std::size_t(i)];
            queue.push_back(n);
        }
    }
    for (int i = 0; i < w * h; ++i)
        if (owner[std::size_t(i)] >= 0) trees[std::size_t(owner[std::size_t(i)])].part.bits[std::size_t(i)] = 1;
    for (std::size_t k = 0; k < crowns.size(); ++k) {
        if (crown_tree[k] < 0) continue;
        Mask& crown = trees[std::size_t(crown_tree[k])].crown;
        if (crown.bits.empty()) crown = Mask(object.rect());
        for (std::size_t i = 0; i < crown.bits.size(); ++i) crown.bits[i] |= crowns[k].bits[i];
    }
    return trees;
}

// One grove tree's solid: its discs fit within `may_hide` (its pixels and
// those of the trees in front), as grove_solids says.
std::optional<EstimatedObject> grove_solid(const GroveTree& t, const Mask& may_hide, const Mask& object, int width) {
    EstimatedObject o;
    o.center_x = t.x + 0.5;
    o.center_y = t.y + 0.5;
    o.rect = Rect{int(std::floor(t.x)) - 2, t.y - 2, 5, 3};
    const int c = int(std::floor(o.center_x));
    const RunsThrough runs = runs_through(may_hide, c), whole = runs_through(object, c);
    // A crown is round: where one side shows it whole, the other may reach
    // as far into any of the grove's pixels (a crown in another tree's
    // colour may stand in front of it there, which the feet cannot tell).
    o.radius = fit_discs_by(
        [&](double yc, double r) {
            return disc_within(runs, whole, o.center_x, yc, r) || disc_within(whole, runs, o.center_x, yc, r);
        },
        o.center_y, top_row(t.part), width / sqrt2 + 1, false);
    // The lowest disc that shows the tree's own crown (else its own pixels):
    // the outlines and seams between the crowns in front, which go to the
    // nearest crown, are not foliage of its own down there.
    const Mask& own = t.crown.bits.empty() ? t.part : t.crown;
    std::size_t shown = o.radius.size();
    for (std::size_t z = 0; z < o.radius.size(); ++z)
        if (o.radius[z] > 0 && disc_touches(own, o.center_x, o.center_y - (double(z) + 0.5), o.radius[z])) {
            shown = z;
            break;
        }
    if (shown == o.radius.size()) return std::nullopt;
    const double stem = hidden_stem_ratio * *std::max_element(o.radius.begin() + std::ptrdiff_t(shown), o.radius.end());
    for (std::size_t z = 0; z < shown; ++z) o.radius[z] = std::min(o.radius[z] > 0 ? o.radius[z] : stem, stem);
    stand_on_hidden_stem(t.part, o);
    widen_across_view(t.part, o);
    return o;
}

// Each grove tree's solid of revolution, standing on its foot: its discs
// fit the pixels that show it together with those of the trees in front
// (nearer the viewer: a foot lower on screen), which may hide any of it,
// and a disc that shows none of its own pixels is hidden wholly, so holds
// only its stem (hidden_stem_ratio of the widest disc): a hidden tree's
// discs would otherwise fill the crowns in front of it down to the ground.
std::vector<EstimatedObject> grove_solids(const Mask& object, const std::vector<GroveTree>& trees) {
    // Front to back, each tree's pixels joining `in_front` once every tree
    // standing on its row has been fitted: one pass over the pixels a tree.
    std::vector<std::size_t> order(trees.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t p, std::size_t q) { return trees[p].y > trees[q].y; });
    Mask in_front(object.rect());
    std::vector<std::optional<EstimatedObject>> solids(trees.size());
    for (std::size_t first = 0; first < order.size();) {
        std::size_t last = first;
        while (last < order.size() && trees[order[last]].y == trees[order[first]].y) ++last;
        for (std::size_t k = first; k < last; ++k) {
            const GroveTree& t = trees[order[k]];
            Mask may_hide = in_front;
            for (std::size_t i = 0; i < may_hide.bits.size(); ++i) may_hide.bits[i] |= t.part.bits[i];
            solids[order[k]] = grove_solid(t, may_hide, object, object.width);
        }
        for (std::size_t k = first; k < last; ++k)
            for (std::size_t i = 0; i < in_front.bits.size(); ++i) in_front.bits[i] |= trees[order[k]].part.bits[i];
        first = last;
    }
    std::vector<EstimatedObject> out;
    for (std::optional<EstimatedObject>& o : solids)
        if (o) out.push_back(std::move(*o));
    return out;
}

// One tree per trunk where the colours part no crowns: the object's pixels
// go to the trunk whose column is nearest (the lower index on a tie).
std::vector<GroveTree> column_trees(const Mask& object, const std::vector<TrunkFoot>& feet) {
    std::vector<GroveTree> trees;
    for (const TrunkFoot& f : feet) trees.push_back({f.x, f.y, false, Mask(object.rect())});
    for (int j = 0; j < object.height; ++j)
        for (int i = 0; i < object.width; ++i) {
            if (!object.bits[std::size_t(j) * object.width + i]) continue;
            const double x = object.x0 + i;
            std::size_t nearest = 0;
            for (std::size_t t = 1; t < feet.size(); ++t)
                if (std::abs(x - feet[t].x) < std::abs(x - feet[nearest].x)) nearest = t;
            trees[nearest].part.bits[std::size_t(j) * object.width + i] = 1;
        }
    return trees;
}

}  // namespace

bool hidden_below_widest(const Mask& object, const EstimatedObject& o) {
    constexpr int rounding = 2;  // rows a column: the largest disc that fits rounds to pixel centres
    if (o.radius.empty()) return false;
    const std::size_t widest = widest_disc(o);
    if (widest == 0) return false;
    EstimatedObject above = o;
    for (std::size_t z = 0; z < widest; ++z) above.radius[z] = 0;
    const Mask drawn = solid_silhouette({above}, object.x0 + object.width, object.y0 + object.height);
    const double centre_row = o.center_y - (double(widest) + 0.5);
    for (int i = 0; i < object.width; ++i) {
        int uncovered = 0;
        for (int j = 0; j < object.height; ++j) {
            const int y = object.y0 + j;
            if (y + 0.5 > centre_row && object.bits[std::size_t(j) * object.width + i] && !drawn.get(object.x0 + i, y))
                ++uncovered;
        }
        if (uncovered > rounding) return false;
    }
    return true;
}

namespace {

std::vector<EstimatedObject> revolution_objects(const Mask& object, const Mask& footprint, const FootprintSpec* correction,
                                                const std::vector<TrunkFoot>* trunks, bool whole_base,
                                                const std::vector<Mask>* crowns) {
    EstimatedObject o;
    const bool has_footprint = mask_centre(footprint, o.center_x, o.center_y, o.rect);
    const bool corrected = correction && correction->object_foot;
    if ((!has_footprint && !corrected) || object.count() == 0) return {};
    if (corrected) {
        // The user's foot: the footprint's box moved to it (a pixel there without one).
        const auto [fx, fy] = *correction->object_foot;
        if (!has_footprint) o.rect = Rect{fx, fy, 1, 1}, o.center_x = fx + 0.5, o.center_y = fy + 0.5;
        o.rect.x += int(std::lround(fx + 0.5 - o.center_x));
        o.rect.y += int(std::lround(fy + 0.5 - o.center_y));
        o.center_x = fx + 0.5, o.center_y = fy + 0.5;
    }
    // A grove: one object per trunk the colours show (two or more). Not on a
    // whole base: a building's beams and a mountain's earth are bark-coloured.
    if (trunks && !corrected && !whole_base) {
        const std::vector<TrunkFoot>& feet = *trunks;
        if (feet.size() >= 2) {
            if (crowns) {
                const std::vector<GroveTree> trees = grove_trees(object, feet, *crowns);
                if (!trees.empty()) {
                    std::vector<EstimatedObject> grove = grove_solids(object, trees);
                    if (grove.size() >= 2) return grove;
                }
            }
            std::vector<EstimatedObject> grove = grove_solids(object, column_trees(object, feet));
            if (grove.size() >= 2) return grove;
        }
    }
    const int height = correction ? correction->object_height : 0;
    const int c = int(std::floor(o.center_x));
    const RunsThrough runs = runs_through(object, c);
    const int top = top_row(object);
    const double widest = object.width / sqrt2 + 1;
    if (corrected || whole_base) {  // a whole base's centre is where it stands
        o.radius = fit_discs(runs, o.center_x, o.center_y, top, widest, whole_base, height);
        if (o.radius.empty()) return {};
        if (!whole_base) stand_on_hidden_stem(object, o);  // a building rests on its whole base
        widen_across_view(object, o);
        return {o};
    }
    // Where the axis meets the ground. Algorithm 1's footprint centre is a
    // trunk's base, but a bush's or a rock's widest rows: its equator, not
    // where it stands. So the foot may move down, to the object's lowest
    // row at most, to the row whose solid covers most of the object's pixels
    // (the nearest to the footprint among equals: moving a solid down only
    // lifts it off the ground without covering more), when that covers at
    // least 2 % more of them. The footprint's column then came from the
    // equator's lines too, so the axis may also move sideways, up to
    // `axis_shift` columns, where that covers more.
    const ObjectPixels pixels(object);
    const FootCandidate at_footprint = fit_at(pixels, o, runs, o.center_x, o.center_y, top, widest, height);
    const double rows = object.height;
    if (rows * (1 + 2 * axis_shift) * rows * 16 * (widest / sqrt2) > foot_search_budget) {
        if (at_footprint.object.radius.empty()) return {};
        EstimatedObject kept = at_footprint.object;
        stand_on_hidden_stem(object, kept);
        widen_across_view(object, kept);
        return {kept};
    }
    FootCandidate best = lowest_best_foot(pixels, o, c, 0, top, widest, height, at_footprint);
    // A pixel row's worth of gain is an outline's rounding, not a better foot.
    const long rounding = object.count() / 50;
    if (best.covered <= at_footprint.covered + rounding) {
        best = at_footprint;
    } else {
        for (int shift = 1; shift <= axis_shift; ++shift)
            for (int dx : {-shift, shift}) best = lowest_best_foot(pixels, o, c, dx, top, widest, height, best);
    }
    EstimatedObject moved = std::move(best.object);
    moved.rect.x += int(std::lround(moved.center_x - o.center_x));  // the footprint, moved with the foot
    moved.rect.y += int(std::lround(moved.center_y - o.center_y));
    if (moved.radius.empty()) return {};
    stand_on_hidden_stem(object, moved);
    widen_across_view(object, moved);
    return {moved};
}

// The object's pixels grown by one pixel up and down: a prism's hull. A
// level's middle shows half a pixel off its face's rows, and the outline's
// top and bottom pixels are partly covered (some below the threshold), so
// the hull carves only what stands a pixel clear of the outline: a fence's
// gaps under and between its rails, not its rails' own edges (grown each
// way it kept less of a fence's gaps; not grown, the rails' edges let light
// through them onto their far sides).
Mask prism_hull(const Mask& object) {
    Mask hull(Rect{object.x0, object.y0 - 1, object.width, object.height + 2});
    for (int y = object.y0; y < object.y0 + object.height; ++y)
        for (int x = object.x0; x < object.x0 + object.width; ++x)
            if (object.get(x, y))
                for (int dy = -1; dy <= 1; ++dy) hull.set(x, y + dy);
    return hull;
}

// The user's foot and height applied to a prism or a mound: the solid
// moved so its base's centre stands on the foot, its height replaced.
void apply_correction(EstimatedObject& o, const FootprintSpec& c) {
    if (c.object_foot) {
        const double dx = c.object_foot->first + 0.5 - o.center_x, dy = c.object_foot->second + 0.5 - o.center_y;
        o.center_x += dx, o.center_y += dy;
        o.rect.x += int(std::lround(dx)), o.rect.y += int(std::lround(dy));
    }
    if (c.object_height > 0 && !o.radius.empty()) {
        const std::size_t n = std::size_t(c.object_height);
        if (o.model == ObjectModel::prism) {
            o.radius.assign(n, o.radius[0]);
            o.steps.clear(), o.ridge_axis = -1;  // the user's height is the whole prism's
        } else {  // a mound keeps its profile, stretched to the new height
            std::vector<double> r(n), a(n);
            for (std::size_t z = 0; z < n; ++z) {
                const std::size_t k = std::min(o.radius.size() - 1, z * o.radius.size() / n);
                r[z] = o.radius[k], a[z] = o.across_at(k);
            }
            o.radius = std::move(r), o.across = std::move(a);
        }
    }
}

}  // namespace

std::vector<EstimatedObject> estimate_objects(const Mask& object, const Mask& footprint, const FootprintSpec* correction,
                                              const std::vector<TrunkFoot>* trunks, bool whole_base,
                                              const std::vector<Mask>* crowns) {
    // The user's model, where they chose one (a pointer: GCC 12 misreads an optional's use here).
    const ObjectModel* chosen = correction && correction->object_model ? &*correction->object_model : nullptr;
    std::vector<EstimatedObject> revolution;
    if (!chosen || *chosen == ObjectModel::revolution)
        revolution = revolution_objects(object, footprint, correction, trunks, whole_base, crowns);
    if (chosen && *chosen == ObjectModel::revolution) return revolution;
    // A foot or a height without a model corrects the solid of revolution,
    // as it did before there were models: manifests keep their solids.
    if (!chosen && correction && (correction->object_foot || correction->object_height > 0)) return revolution;
    // A grove (several trunks) stays trees of revolution: the models fit one
    // object. So does a whole base (a tile-filling mountain or city on real
    // art, RealArt.freecivMountainsAndCitiesStandOnTheirWholeBase), where
    // the fits were not measured to help.
    if (!chosen && (revolution.size() != 1 || whole_base)) return revolution;
    std::optional<EstimatedObject> prism, mound;
    double share = 0;
    if (!chosen || *chosen == ObjectModel::prism) prism = fit_prism(object, &share);
    if (!chosen || *chosen == ObjectModel::mound) mound = fit_mound(object);
    if (chosen) {  // the user's model; where it finds no fit, the estimate's own
        std::optional<EstimatedObject>& o = *chosen == ObjectModel::prism ? prism : mound;
        if (!o) return revolution_objects(object, footprint, correction, trunks, whole_base, crowns);
        if (o->model == ObjectModel::prism) top_prism(object, *o);
        if (o->model == ObjectModel::prism) o->hull = prism_hull(object);
        apply_correction(*o, *correction);
        return {*o};
    }
    // The model whose silhouette fits the object's pixels best; revolution
    // keeps ties (within model_fit_margin): it was measured first, and both
    // other models fill a bush's or a boulder's outline about as well as it
    // does, where it measured closer to 3D (docs/beyond.md).
    const double revolution_fit = silhouette_fit(revolution, object);
    const double prism_fit = prism ? silhouette_fit({*prism}, object) : 0, mound_fit = mound ? silhouette_fit({*mound}, object) : 0;
    // A prism is taken where most columns stand on its V, or where it is low
    // (no taller than half its width on screen) and fits clearly better than
    // both other models: a fence whose rails hide the ground between its
    // posts, a town of boxes on several V's. Every tree of the real art
    // whose prism fits better than its solid of revolution is taller than
    // that (RealArt.otherGamesTreesStaySolidsOfRevolution).
    if (prism && share < prism_v_share &&
        (prism->height() > prism->half_x + prism->half_y ||
         prism_fit <= std::max(revolution_fit, mound_fit) + prism_clear_margin))
        prism.reset();
    // A peak (a mound whose cross-section halfway up is half its base's: a
    // mountain) needs no margin: no bush's outline fits a cone, and a solid
    // of revolution stands at its base's front (its footprint), not its middle.
    // A conifer's skirt fits a cone as well, but hides the stem under it.
    const bool peak = mound && mound->radius.size() >= 2 &&
                      mound->radius[mound->radius.size() / 2] < 0.6 * mound->radius[0] &&
                      !hidden_below_widest(object, revolution[0]);
    double best = revolution_fit + model_fit_margin;
    std::vector<EstimatedObject> out = revolution;
    bool prism_taken = false;
    if (prism && prism_fit > best) best = prism_fit, out = {*prism}, prism_taken = true;
    const double mound_needs = peak && !prism_taken ? revolution_fit : best;
    if (mound && mound_fit > mound_needs) {
        // A dome that hides the solid of revolution (their union's
        // silhouette fits no better than the dome's) is a heap: the dome,
        // lowest where the outline's top is its broad back, and the solid
        // of revolution, the summit over its front, are both kept.
        const bool heap = !peak && silhouette_fit({*mound, revolution[0]}, object) <= mound_fit + heap_fit_gain;
        out = heap ? std::vector<EstimatedObject>{*mound, revolution[0]} : std::vector<EstimatedObject>{*mound};
        prism_taken = false;
    }
    // The model is picked on one height (the steps would fit any outline's
    // top, a tree's too); the prism taken gets its steps or its roof.
    if (prism_taken) top_prism(object, out[0]);
    // Carved by the object's pixels once taken: the pick compares the
    // models' shapes, where carving would favour the prism everywhere.
    if (prism_taken) out[0].hull = prism_hull(object);
    return out;
}

namespace {

// Per column of an object's mask that holds a pixel: its centre, the screen
// row under its lowest pixel (where a solid standing there meets the
// ground) and the row over its highest.
struct ColumnExtent {
    double x, ground, top;
};

// The first and last of n mask bits from `start`, `step` apart, that are
// set, as indices 0..n-1 ({-1, -1}: none): a column's or a row's extent.
std::pair<int, int> set_extent(const Mask& m, std::size_t start, std::size_t step, int n) {
    int first = -1, last = -1;
    for (int k = 0; k < n; ++k)
        if (m.bits[start + std::size_t(k) * step]) {
            if (first < 0) first = k;
            last = k;
        }
    return {first, last};
}

std::vector<ColumnExtent> column_extents(const Mask& object) {
    std::vector<ColumnExtent> cols;
    for (int i = 0; i < object.width; ++i) {
        const auto [first, last] = set_extent(object, std::size_t(i), std::size_t(object.width), object.height);
        if (first >= 0) cols.push_back({object.x0 + i + 0.5, double(object.y0 + last + 1), double(object.y0 + first)});
    }
    return cols;
}

double quantile(std::vector<double> v, double q) {
    const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size())));
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
    return v[k];
}

}  // namespace

std::optional<EstimatedObject> fit_prism(const Mask& object, double* v_share) {
    const std::vector<ColumnExtent> cols = column_extents(object);
    if (cols.size() < 6) return std::nullopt;
    // The front corner (xf, yf): each column's ground line lifted by the V's
    // slope from xf lies at yf. The corner is the one whose lifted lines
    // agree best (their errors capped, so eaves and the gaps between a
    // fence's posts count once), yf a high quantile of them.
    constexpr double cap = 6;
    double best = 1e300, xf = 0, yf = 0;
    std::vector<double> lifted(cols.size());
    for (double cand = cols.front().x; cand <= cols.back().x; cand += 0.5) {
        for (std::size_t k = 0; k < cols.size(); ++k) lifted[k] = cols[k].ground + std::abs(cols[k].x - cand) / 2;
        const double y = quantile(lifted, prism_ground_quantile);
        double cost = 0;
        for (double l : lifted) cost += std::min(std::abs(l - y), cap);
        if (cost < best) best = cost, xf = cand, yf = y;
    }
    // The left and right corners: the outermost columns on the V.
    double xl = 1e300, xr = -1e300;
    std::size_t on_v = 0;
    for (const ColumnExtent& c : cols)
        if (std::abs(c.ground + std::abs(c.x - xf) / 2 - yf) <= prism_on_ground)
            xl = std::min(xl, c.x - 0.5), xr = std::max(xr, c.x + 0.5), ++on_v;
    if (!(xl < xf && xf < xr)) return std::nullopt;
    if (v_share) *v_share = double(on_v) / double(cols.size());
    // The rectangle in the ground frame (ground_frame at z = 0, sprite pixels).
    const double X1 = yf + xf / 2, Y1 = yf - xf / 2;  // the front corner
    const double X0 = std::min(xl + Y1, X1 - 1), Y0 = std::min(X1 - xr, Y1 - 1);
    // The height: each column's rise from the back edges to its top.
    const double xb = X0 - Y0, yb = (X0 + Y0) / 2;  // the back corner on screen
    std::vector<double> rises;
    for (const ColumnExtent& c : cols)
        if (c.x > xl && c.x < xr) rises.push_back(yb + std::abs(c.x - xb) / 2 - c.top);
    if (rises.empty()) return std::nullopt;
    const double height = quantile(rises, 0.5);
    if (height < 1) return std::nullopt;
    EstimatedObject o;
    o.model = ObjectModel::prism;
    o.flat_top = quantile(rises, 0.9) - quantile(rises, 0.1) <= prism_flat_spread;
    o.half_x = (X1 - X0) / 2, o.half_y = (Y1 - Y0) / 2;
    const double Xc = (X0 + X1) / 2, Yc = (Y0 + Y1) / 2;
    o.center_x = Xc - Yc, o.center_y = (Xc + Yc) / 2;
    o.radius.assign(std::size_t(std::lround(height)), std::hypot(o.half_x, o.half_y));
    const int left = int(std::floor(xl)), back = int(std::floor(yb));
    o.rect = Rect{left, back, int(std::ceil(xr)) - left, int(std::ceil(yf)) - back};
    return o;
}

void step_prism(const Mask& object, EstimatedObject& o) {
    const double reach = o.half_x + o.half_y;
    const double xb = o.center_x - o.half_x + o.half_y, yb = o.center_y - reach / 2;  // the back corner on screen
    const std::size_t n = std::size_t(std::ceil(2 * reach));
    if (n == 0) return;
    std::vector<double> rise(n, -1), front(n, -1e300);
    for (const ColumnExtent& c : column_extents(object)) {
        const double i = std::floor(c.x - o.center_x + reach);
        if (i < 0 || i >= double(n)) continue;
        rise[std::size_t(i)] = yb + std::abs(c.x - xb) / 2 - c.top;
        front[std::size_t(i)] = c.ground - o.center_y;
    }
    // Empty columns take their nearest measured neighbour's rise (left first).
    std::vector<double> filled = rise;
    for (std::size_t i = 0; i < n; ++i) {
        if (rise[i] >= 0) continue;
        for (std::size_t d = 1; d < n; ++d) {
            if (i >= d && rise[i - d] >= 0) { filled[i] = rise[i - d]; break; }
            if (i + d < n && rise[i + d] >= 0) { filled[i] = rise[i + d]; break; }
        }
    }
    if (filled[0] < 0) return;  // no column measured
    std::vector<double> steps(n);
    double top = 1, jump = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double a = filled[i > 0 ? i - 1 : i], b = filled[i], c = filled[i + 1 < n ? i + 1 : i];
        const double median = std::max(std::min(a, b), std::min(std::max(a, b), c));
        steps[i] = std::max(1.0, std::round(median));
        top = std::max(top, steps[i]);
        if (i > 0) jump = std::max(jump, std::abs(steps[i] - steps[i - 1]));
    }
    // Only boxes of their own side by side (a town's houses) step: a roof's
    // slopes and a fence's posts rise by a few pixels a column, and a
    // column's whole depth raised to a ridge's height stands taller than
    // their front walls (measured worse against 3D, docs/beyond.md).
    if (jump < prism_step_jump * o.height()) return;
    o.steps = std::move(steps);
    o.fronts = std::move(front);
    o.radius.assign(std::size_t(top), o.radius.empty() ? std::hypot(o.half_x, o.half_y) : o.radius[0]);
}

void ridge_prism(const Mask& object, EstimatedObject& o) {
    if (!o.steps.empty() || o.flat_top || o.half_x <= 0 || o.half_y <= 0) return;
    // Per column inside the rectangle: its view lines' ground rows [lo, hi]
    // (relative to the foot) and the object's top row there.
    struct Column {
        double sx, lo, hi, top;
    };
    std::vector<Column> cols;
    double tallest = 1;
    for (const ColumnExtent& c : column_extents(object)) {
        const double sx = c.x - o.center_x;
        const double lo = std::max(-o.half_x - sx / 2, -o.half_y + sx / 2), hi = std::min(o.half_x - sx / 2, o.half_y + sx / 2);
        if (lo >= hi) continue;
        cols.push_back({sx, lo, hi, c.top - o.center_y});
        tallest = std::max(tallest, lo - (c.top - o.center_y));
    }
    if (cols.size() < 6) return;
    // How far a roof's predicted top rows lie from the object's (capped, as
    // fit_prism's V: a chimney or a gap counts once). On a column the view
    // lines' topmost point is the least of t - top(t), convex along it: at
    // an end or over the ridge.
    constexpr double cap = 6;
    auto cost = [&](int axis, double eaves, double ridge) {
        double sum = 0;
        for (const Column& c : cols) {
            auto row = [&](double t) {
                const double off = axis == 0 ? std::abs(t - c.sx / 2) / o.half_y : std::abs(t + c.sx / 2) / o.half_x;
                return t - (ridge - (ridge - eaves) * std::min(off, 1.0));
            };
            const double over = axis == 0 ? c.sx / 2 : -c.sx / 2;
            double best = std::min(row(c.lo), row(c.hi));
            if (c.lo < over && over < c.hi) best = std::min(best, row(over));
            sum += std::min(std::abs(best - c.top), cap);
        }
        return sum;
    };
    const int most = int(std::ceil(tallest)) + 1;
    // Whole pixels up to 64 heights, coarser beyond (a huge sprite's search
    // stays bounded: at most 64 x 64 roofs an axis).
    const int step = std::max(1, (most + 63) / 64);
    double flat = 1e300;
    for (int h = 1; h <= most; h += step) flat = std::min(flat, cost(0, h, h));
    double best = 1e300;
    int best_axis = -1, best_eaves = 0, best_ridge = 0;
    for (int axis = 0; axis < 2; ++axis)
        for (int ridge = 2; ridge <= most; ridge += step)
            for (int eaves = 1; eaves + ridge_least_rise <= ridge; eaves += step) {
                const double c = cost(axis, eaves, ridge);
                if (c < best) best = c, best_axis = axis, best_eaves = eaves, best_ridge = ridge;
            }
    if (best_axis < 0 || best > (1 - ridge_fit_margin) * flat) return;
    o.ridge_axis = best_axis;
    o.eaves = best_eaves;
    o.radius.assign(std::size_t(best_ridge), std::hypot(o.half_x, o.half_y));
}

void top_prism(const Mask& object, EstimatedObject& o) {
    if (o.flat_top) return;
    step_prism(object, o);
    ridge_prism(object, o);
}

std::optional<EstimatedObject> fit_mound(const Mask& object) {
    // The base, taken round: its width from the widest row, its front from
    // the object's lowest row, so its centre's row lies half its depth on
    // screen above that. The top row sets the height.
    int widest = 0, widest_row = -1, top = -1, bottom = -1;
    std::pair<int, int> base{0, -1};  // the base's columns: the lowest of the widest runs
    std::vector<std::pair<int, int>> runs(std::size_t(object.height), {1, 0});
    for (int j = 0; j < object.height; ++j) {
        const auto [a, b] = set_extent(object, std::size_t(j) * std::size_t(object.width), 1, object.width);
        if (a < 0) continue;
        runs[std::size_t(j)] = {a, b};
        if (top < 0) top = j;
        bottom = j;
        if (b - a + 1 >= widest) widest = b - a + 1, base = {a, b};
    }
    if (top < 0) return std::nullopt;
    int first_wide = -1;  // the band of rows within 3 % of the widest: its middle
    for (int j = top; j <= bottom; ++j)
        if (runs[std::size_t(j)].second - runs[std::size_t(j)].first + 1 >= 0.97 * widest) {
            if (first_wide < 0) first_wide = j;
            widest_row = j;
        }
    const double wide_middle = (first_wide + widest_row) / 2.0;
    const double across = widest / 2.0 / sqrt2, front = object.y0 + bottom + 1.0, fy = front - across / sqrt2;
    // The widest rows of a mound are its base's middle; where they stand
    // well above it, they are an equator above the ground (a bush's crown).
    // A mountain's side lobes may widen rows a little above its base's
    // centre: the rise allowed grows with the base's depth on screen.
    const double rise = std::max(mound_equator_rise, mound_equator_share * 2 * across / sqrt2);
    if (object.y0 + wide_middle + 0.5 < fy - rise) return std::nullopt;
    const double above = fy - (object.y0 + top);
    const auto [a, b] = base;
    // Two profiles: a dome (a half ellipsoid), whose outline's top lies
    // sqrt(H^2 + depth^2 / 2) above the base's centre, and a cone (a peak:
    // a mountain), whose apex is the outline's top. The cone is taken where
    // its silhouette fits better than the dome's by cone_fit_margin: a heap
    // of boulders, a town's roofs fit a cone about as well, and hold more
    // of their volume as domes or prisms.
    std::optional<EstimatedObject> dome, cone;
    for (const bool peak : {false, true}) {
        const double h2 = peak ? above * above : above * above - across * across / 2;
        if (h2 < 1 || (peak && above <= across / sqrt2)) continue;
        const double height = std::sqrt(h2);
        EstimatedObject o;
        o.model = ObjectModel::mound;
        o.center_x = object.x0 + (a + b + 1) / 2.0, o.center_y = fy;
        const std::size_t n = std::size_t(std::lround(height));
        o.radius.resize(n), o.across.resize(n);
        for (std::size_t z = 0; z < n; ++z) {
            const double t = (double(z) + 0.5) / height;
            o.radius[z] = o.across[z] = across * (peak ? 1 - t : std::sqrt(std::max(0.0, 1 - t * t)));
        }
        o.rect = Rect{object.x0 + a, int(std::floor(fy - across / sqrt2)), b - a + 1, int(std::ceil(2 * across / sqrt2)) + 1};
        (peak ? cone : dome) = std::move(o);
    }
    if (cone && (!dome || silhouette_fit({*cone}, object) > silhouette_fit({*dome}, object) + cone_fit_margin)) return cone;
    return dome;
}

std::vector<EstimatedObject> estimate_objects(const FootprintReport& report, const Mask& footprint,
                                              const FootprintSpec* correction) {
    const bool corrected =
        correction && (correction->object_foot || correction->object_height > 0 || correction->object_model);
    if (report.parts.empty() || corrected || report.trunks.size() >= 2)
        return estimate_objects(report.estimate, footprint, correction, &report.trunks, report.whole_base, &report.crowns);
    std::vector<EstimatedObject> out;
    for (const ObjectPart& part : report.parts)
        for (EstimatedObject& o : estimate_objects(part.object, part.footprint)) out.push_back(std::move(o));
    return out;
}

std::vector<EstimatedObject> sprite_objects(const Tileset& tileset, const Sprite& s, const Params& p) {
    FootprintReport report;
    const Mask footprint = tileset_footprint(tileset, s, p, &report);
    return estimate_objects(report, footprint, &s.footprint);
}

namespace {

// A prism's silhouette: the pixels whose view line meets its rectangle at
// a height in [0, its column's step). On the view line through (sx, sy) from the foot
// the point z high is (t + sx / 2, t - sx / 2) with t = sy + z (t is its
// ground point's screen row), so the pixel is drawn when the ranges of t
// (the rectangle's two sides, the heights and the column's front) meet, and
// the pixel is one of its hull's (every point on its view line shows there).
void draw_prism(const EstimatedObject& o, Mask& m) {
    const double reach = o.half_x + o.half_y;
    const int x0 = std::max(int(std::floor(o.center_x - reach)), 0), x1 = std::min(int(std::ceil(o.center_x + reach)), m.width - 1);
    const int y0 = std::max(int(std::floor(o.center_y - reach / 2 - o.height())), 0),
              y1 = std::min(int(std::ceil(o.center_y + reach / 2)), m.height - 1);
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
            const double sx = x + 0.5 - o.center_x, sy = y + 0.5 - o.center_y;
            const double lo = std::max({-o.half_x - sx / 2, -o.half_y + sx / 2, sy});
            const double hi = std::min({o.half_x - sx / 2, o.half_y + sx / 2, o.front_at(sx)});
            if (lo > hi || !o.hull_shows(x, y)) continue;
            // Some t in [lo, hi] below the top: top_at - (t - sy) is concave
            // along the view line (a step under a ridge's tent), so its
            // greatest is at an end or over the ridge.
            auto below_top = [&](double t) { return t - sy <= o.top_at(t + sx / 2, t - sx / 2); };
            const double over_ridge = o.ridge_axis == 0 ? sx / 2 : -sx / 2;
            if (below_top(lo) || below_top(hi) || (o.ridge_axis >= 0 && lo < over_ridge && over_ridge < hi && below_top(over_ridge)))
                m.set(x, y);
        }
}

}  // namespace

double silhouette_fit(const std::vector<EstimatedObject>& objects, const Mask& object) {
    const int w = object.x0 + object.width, h = object.y0 + object.height;
    if (w <= 0 || h <= 0) return 0;
    // Past the object's rectangle the silhouette only adds to |either|: drawn on a margin around it.
    double margin = 0;
    for (const EstimatedObject& o : objects) {
        double reach = o.half_x + o.half_y;
        for (std::size_t z = 0; z < o.radius.size(); ++z) reach = std::max(reach, o.across_at(z) * sqrt2);
        margin = std::max(margin, 2 * reach + 2);
    }
    const Mask drawn = solid_silhouette(objects, w + int(margin), h + int(margin));
    long both = 0, either = 0;
    for (int y = 0; y < drawn.height; ++y)
        for (int x = 0; x < drawn.width; ++x) {
            const bool a = drawn.get(x, y), b = object.get(x, y);
            both += a && b, either += a || b;
        }
    return either ? double(both) / double(either) : 0;
}

Mask solid_silhouette(const std::vector<EstimatedObject>& objects, int w, int h) {
    Mask m(Rect{0, 0, w, h});
    // An object's cross-sections share its axis, so on each row they show
    // as intervals about one centre: the row's widest is their union (one
    // pass over the rows a cross-section spans, not over its pixels).
    std::vector<double> widest(std::size_t(std::max(h, 0)));
    for (const EstimatedObject& o : objects) {
        if (o.model == ObjectModel::prism) {
            draw_prism(o, m);
            continue;
        }
        std::fill(widest.begin(), widest.end(), -1.0);
        for (std::size_t z = 0; z < o.radius.size(); ++z) {
            const double r = o.radius[z], a = o.across_at(z) * sqrt2, b = r / sqrt2, yc = o.center_y - (double(z) + 0.5);
            if (r <= 0) continue;
            const int y0 = std::max(int(std::floor(yc - b)), 0), y1 = std::min(int(std::ceil(yc + b)), h - 1);
            for (int y = y0; y <= y1; ++y) {
                const double v = (y + 0.5 - yc) / b;
                if (v * v > 1) continue;
                widest[std::size_t(y)] = std::max(widest[std::size_t(y)], a * std::sqrt(1 - v * v));
            }
        }
        for (int y = 0; y < h; ++y) {
            const double hw = widest[std::size_t(y)];
            if (hw < 0) continue;
            for (int x = std::max(int(std::ceil(o.center_x - hw - 0.5)), 0); x <= std::min(int(std::floor(o.center_x + hw - 0.5)), w - 1); ++x)
                m.set(x, y);
        }
    }
    return m;
}

double volume_overlap(const std::vector<EstimatedObject>& objects, int anchor_x, int anchor_y,
                      const std::vector<Solid>& shape) {
    // Each object's axis foot in the anchor's ground frame, and the bounds of both.
    std::vector<Vec3> feet;
    Vec3 lo{1e300}, hi{-1e300};
    for (const EstimatedObject& o : objects) {
        const Vec3 foot = ground_frame(o.center_x - anchor_x, o.center_y - anchor_y, 0);
        feet.push_back(foot);
        double r = 0;
        for (std::size_t z = 0; z < o.radius.size(); ++z) r = std::max(r, o.across_at(z));  // across >= radius
        lo = glm::min(lo, foot - Vec3{r, r, 0});
        hi = glm::max(hi, foot + Vec3{r, r, o.height()});
    }
    for (const Solid& s : shape) {
        const auto b = solid_bounds(s);
        lo = glm::min(lo, b[0]);
        hi = glm::max(hi, b[1]);
    }
    if (!(lo.x <= hi.x)) return 0;
    const Vec3 extent = hi - glm::floor(lo) + 1.0;
    const double step = std::max(1.0, std::cbrt(extent.x * extent.y * extent.z / volume_overlap_samples));
    long both = 0, either = 0;
    for (double z = std::floor(lo.z) + 0.5 * step; z < hi.z; z += step)
        for (double y = std::floor(lo.y) + 0.5 * step; y < hi.y; y += step)
            for (double x = std::floor(lo.x) + 0.5 * step; x < hi.x; x += step) {
                const Vec3 p{x, y, z};
                bool in_estimate = false, in_shape = false;
                for (std::size_t k = 0; k < objects.size() && !in_estimate; ++k)
                    in_estimate = objects[k].contains(p - feet[k]);
                for (std::size_t k = 0; k < shape.size() && !in_shape; ++k) in_shape = solid_contains(shape[k], p);
                both += in_estimate && in_shape;
                either += in_estimate || in_shape;
            }
    return either ? double(both) / double(either) : 0;
}

}  // namespace isolux
