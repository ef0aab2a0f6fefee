// Beyond the paper: each sprite pixel's normal and the height of the point
// it shows, from the estimated solids, the manifest's shapes or the
// picture's brightness (sprite_shading.hpp).
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "isolux/error.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/sprite_shading.hpp"

namespace isolux {

namespace {

// How much two one-sided rises along an axis may differ for the surface to
// count as bending through the pixel (their mean the slope), pixels.
constexpr double bend = 1.0;

// The ground's normal, for floors (which are ground) and for what no source
// can tell.
const Vec3 up{0, 0, 1};

// The height field's slope at (x, y) along (dx, dy), pixels of height a pixel.
double slope(const Mask& shown, const std::vector<float>& h, int x, int y, int dx, int dy) {
    const std::size_t w = std::size_t(shown.width);
    const double here = h[std::size_t(y) * w + x];
    const bool before = shown.get(x - dx, y - dy), after = shown.get(x + dx, y + dy);
    const double rise_before = before ? here - h[std::size_t(y - dy) * w + (x - dx)] : 0;
    const double rise_after = after ? h[std::size_t(y + dy) * w + (x + dx)] - here : 0;
    if (before && after)
        return std::abs(rise_after - rise_before) <= bend
                   ? (rise_before + rise_after) / 2
                   : (std::abs(rise_after) < std::abs(rise_before) ? rise_after : rise_before);
    return before ? rise_before : after ? rise_after : 0;
}

// Normals averaged over the shown pixels within `smooth_radius` whose
// points lie within `smooth_rise` of the pixel's height: the estimate's
// heights rise in steps of its cross-sections (and a height map's in whole
// pixels), which differenced alone draw stripes; the edge between two
// objects stays an edge.
constexpr int smooth_radius = 1;
constexpr double smooth_rise = 1.5;
std::vector<Vec3> smoothed(const Mask& shown, const std::vector<float>& h, const std::vector<Vec3>& n) {
    const int w = shown.width, hgt = shown.height;
    std::vector<Vec3> out(n.size(), Vec3{0.0});
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!shown.bits[i]) continue;
            Vec3 sum{0.0};
            for (int yy = std::max(0, y - smooth_radius); yy <= std::min(hgt - 1, y + smooth_radius); ++yy)
                for (int xx = std::max(0, x - smooth_radius); xx <= std::min(w - 1, x + smooth_radius); ++xx) {
                    const std::size_t j = std::size_t(yy) * w + xx;
                    if (shown.bits[j] && std::abs(double(h[j]) - double(h[i])) <= smooth_rise + std::abs(yy - y) + std::abs(xx - x))
                        sum += n[j];
                }
            const double len = glm::length(sum);
            out[i] = len > 0 ? sum / len : n[i];
        }
    return out;
}

// The sprite's pixels that show a surface (opaque at the preset's threshold).
Mask shown_pixels(const Sprite& s, const Params& p) { return opacity_map(s.image, sprite_threshold(s, p.opacity_threshold)); }

// The estimated solids' own normals (EstimatedObject::normal_at) at the
// points they show. A pixel no solid shows (the silhouette of the solids
// leaves out a fence's rail, a crown's ragged edge, a twig: its height is
// its row's above a foot, which tells no direction) takes the normal of the
// nearest pixel a solid shows, 4-neighbour steps through shown pixels,
// ties to the first reached in row order. Where a model's normal turns
// away from the viewer (rounding put the point past its silhouette), and
// where no shown pixel joins one a solid shows, the height field's,
// differenced.
std::vector<Vec3> solid_normals(const Sprite& s, const Mask& shown, const SpriteSolids& solids) {
    std::vector<Vec3> n = normals_from_heights(shown, solids.heights);
    const int w = s.image.width, hgt = s.image.height;
    std::vector<std::size_t> queue;
    std::vector<char> reached(n.size(), 0);
    if (solids.shown_by.size() != n.size()) return n;  // solids made without it: the heights' own
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!shown.bits[i] || solids.shown_by[i] < 0) continue;
            const EstimatedObject& o = solids.objects[std::size_t(solids.shown_by[i])];
            const Vec3 m = o.normal_at(ground_frame(x + 0.5 - o.center_x, y + 0.5 - o.center_y, solids.heights[i]));
            if (glm::dot(m, toward_viewer) > 0) n[i] = m;
            reached[i] = 1;
            queue.push_back(i);
        }
    for (std::size_t head = 0; head < queue.size(); ++head) {
        const std::size_t i = queue[head];
        const int x = int(i % std::size_t(w)), y = int(i / std::size_t(w));
        for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            if (!shown.get(x + dx, y + dy)) continue;
            const std::size_t j = std::size_t(y + dy) * w + std::size_t(x + dx);
            if (reached[j]) continue;
            reached[j] = 1;
            n[j] = n[i];
            queue.push_back(j);
        }
    }
    return n;
}

// Brightness read as relief, its slope by Sobel's 3 x 3 differences (a
// neighbour the sprite does not show counts as the pixel itself), the normal
// on the screen's plane.
std::vector<Vec3> luminance_normals(const Sprite& s, const Mask& shown) {
    const int w = s.image.width, hgt = s.image.height;
    std::vector<double> relief(std::size_t(w) * hgt, 0);
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint8_t* c = s.image.at(x, y);
            relief[std::size_t(y) * w + x] = (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) / 255.0 * luminance_relief;
        }
    std::vector<Vec3> n(relief.size(), Vec3{0.0});
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            if (!shown.get(x, y)) continue;
            const double here = relief[std::size_t(y) * w + x];
            auto at = [&](int dx, int dy) {
                return shown.get(x + dx, y + dy) ? relief[std::size_t(y + dy) * w + (x + dx)] : here;
            };
            const double gx = (at(1, -1) + 2 * at(1, 0) + at(1, 1) - at(-1, -1) - 2 * at(-1, 0) - at(-1, 1)) / 8;
            const double gy = (at(-1, 1) + 2 * at(0, 1) + at(1, 1) - at(-1, -1) - 2 * at(0, -1) - at(1, -1)) / 8;
            // Screen y grows downward, tangent +Y upward: the relief rises up the screen by -gy.
            n[std::size_t(y) * w + x] = from_screen_tangent(glm::normalize(Vec3{-gx, gy, 1}));
        }
    return n;
}

// The manifest's shapes: the nearest solid's normal at the point each pixel
// shows (as the 3D reference takes it).
std::vector<Vec3> shape_normals(const Sprite& s, const Mask& shown, const std::vector<float>& heights) {
    const int w = s.image.width, hgt = s.image.height;
    std::vector<Vec3> n(std::size_t(w) * hgt, Vec3{0.0});
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            if (!shown.get(x, y)) continue;
            const std::size_t i = std::size_t(y) * w + x;
            const Vec3 point = ground_frame(x + 0.5 - s.anchor_x, y + 0.5 - s.anchor_y, heights[i]);
            double best = 1e300;
            Vec3 nearest = up;
            for (const Solid& solid : s.shape) {
                if (!has_volume(solid)) continue;
                double d = 0;
                const Vec3 nk = solid_normal(solid, point, &d);
                if (d < best) best = d, nearest = nk;
            }
            n[i] = nearest;
        }
    return n;
}

// The heights of the points the manifest's shapes show: its height map, else
// its shapes cast along the view line (as build_surface reads them).
std::vector<float> shape_heights(const Sprite& s, const Mask& shown) {
    const int w = s.image.width, hgt = s.image.height;
    std::vector<float> h(std::size_t(w) * hgt, 0.f);
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            if (!shown.get(x, y)) continue;
            const std::size_t i = std::size_t(y) * w + x;
            h[i] = !s.height.empty() ? float(s.height[i])
                                     : float(std::max(0.0, surface_height(s.shape, x + 0.5 - s.anchor_x, y + 0.5 - s.anchor_y)));
        }
    return h;
}

}  // namespace

std::vector<Vec3> normals_from_heights(const Mask& shown, const std::vector<float>& heights) {
    const int w = shown.width, hgt = shown.height;
    std::vector<Vec3> n(std::size_t(w) * hgt, Vec3{0.0});
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            if (!shown.get(x, y)) continue;
            // The point a pixel shows is ground_frame(x, y, h): its change along
            // screen x and y with the height's slopes hx, hy.
            const double hx = slope(shown, heights, x, y, 1, 0), hy = slope(shown, heights, x, y, 0, 1);
            const Vec3 along_x{0.5 + hx, -0.5 + hx, hx}, along_y{1 + hy, 1 + hy, hy};
            Vec3 c = glm::cross(along_x, along_y);
            if (glm::dot(c, toward_viewer) < 0) c = -c;  // what a pixel shows faces the viewer
            const double len = glm::length(c);
            n[std::size_t(y) * w + x] = len > 0 ? c / len : toward_viewer;
        }
    return smoothed(shown, heights, n);
}

std::array<std::uint8_t, 3> normal_map_colour(Vec3 n, NormalConvention convention) {
    Vec3 t = glm::length(n) > 0 ? to_screen_tangent(n) : Vec3{0, 0, 1};
    if (convention == NormalConvention::directx) t.y = -t.y;
    auto byte = [](double c) { return std::uint8_t(std::lround((std::clamp(c, -1.0, 1.0) + 1) / 2 * 255)); };
    return {byte(t.x), byte(t.y), byte(t.z)};
}

std::vector<std::uint8_t> normal_map_rgb(const SpriteNormals& n, NormalConvention convention) {
    std::vector<std::uint8_t> rgb(n.normal.size() * 3);
    for (std::size_t i = 0; i < n.normal.size(); ++i) {
        const auto c = normal_map_colour(n.normal[i], convention);
        std::copy(c.begin(), c.end(), rgb.begin() + std::ptrdiff_t(i * 3));
    }
    return rgb;
}

std::vector<std::uint16_t> height_map_values(const SpriteNormals& n) {
    std::vector<std::uint16_t> h(n.heights.size());
    for (std::size_t i = 0; i < h.size(); ++i) h[i] = std::uint16_t(std::lround(std::clamp(double(n.heights[i]), 0.0, 65535.0)));
    return h;
}

double lambert(Vec3 n, Vec3 point, Vec3 light) {
    const Vec3 d = light - point;
    const double len = glm::length(d);
    if (!(len > 1e-9)) return 1;
    return std::max(0.0, glm::dot(n, d) / len);
}

SpriteNormals sprite_normals(const Tileset& ts, const Sprite& s, const Params& p, SpriteShading from,
                             const SpriteSolids* estimate) {
    SpriteNormals out;
    out.width = s.image.width;
    out.height = s.image.height;
    const Mask shown = shown_pixels(s, p);
    const std::size_t n = std::size_t(out.width) * out.height;
    if (s.kind != SpriteKind::overlay) {  // floors are the ground
        out.normal.assign(n, Vec3{0.0});
        out.heights.assign(n, 0.f);
        for (std::size_t i = 0; i < n; ++i)
            if (shown.bits[i]) out.normal[i] = up;
        return out;
    }
    switch (from) {
        case SpriteShading::none:
        case SpriteShading::solids:
        case SpriteShading::luminance: {
            SpriteSolids own;
            if (!estimate) own = sprite_solids(ts, s, p), estimate = &own;
            out.heights = estimate->heights;
            out.normal = from == SpriteShading::luminance ? luminance_normals(s, shown) : solid_normals(s, shown, *estimate);
            break;
        }
        case SpriteShading::shapes:
            if (s.shape.empty() && s.height.empty())
                throw Error(ts.source + ": sprite \"" + s.name +
                            "\" has no shape or height map: sprite_shading shapes needs one for every overlay (see "
                            "docs/guide.md)");
            out.heights = shape_heights(s, shown);
            out.normal = s.shape.empty() ? normals_from_heights(shown, out.heights) : shape_normals(s, shown, out.heights);
            break;
    }
    return out;
}

}  // namespace isolux
