// The default tileset: game-art sprites ray-cast from boxes, cylinders, cones
// and ellipsoids in 2:1 isometric projection, with baked Lambert shading, a
// soft ground shadow and 2x2 supersampled (soft) alpha edges. Each sprite's
// true height map is kept: the geometry the paper's Algorithm 1 estimates.
//
// Projection (world units = pixels): screen x = X - Y, screen y = (X + Y)/2 - Z.
// A 64x64 ground square maps to the 128x64 floor diamond. Only +, -, *, / and
// sqrt are used, so the output is bit-exact on every machine.
#include "isolux/tileset_generator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "isolux/hash.hpp"

namespace isolux {

namespace {

// GLM's dot and length are (x*x + y*y) + z*z and its square root: the same
// operations in the same order as written out, so the bytes stay the same.
using V3 = glm::dvec3;
// A zero vector points up (glm::normalize would give NaNs).
V3 unit(V3 a) {
    const double l = glm::length(a);
    return l > 0 ? a * (1.0 / l) : V3{0, 0, 1};
}

struct Material {
    V3 albedo{0.0};             // 0..1
    double grain = 0.15;   // noise amplitude
    double freq = 0.25;    // noise frequency, per pixel
    int pattern = 0;       // 0 plain, 1 bricks, 2 cobbles, 3 waves, 4 leaves
};

enum class Shape { box, ellipsoid, cylinder, cone };

struct Prim {
    Shape shape;
    V3 c{0.0};  // box: min corner; others: centre of base (cylinder, cone) or centre (ellipsoid)
    V3 r{0.0};  // box: max corner; ellipsoid: radii; cylinder/cone: (radius, unused, height)
    int material;
};

struct Hit {
    double t = std::numeric_limits<double>::infinity();
    V3 n{0.0};
    int material = -1;
};

// Ray P + tD with D = (-1,-1,-1): away from the viewer.
const V3 D{-1, -1, -1};

void hit_box(const Prim& p, V3 o, Hit& h) {
    double t0 = -1e30, t1 = 1e30;
    V3 n0{0.0};
    const double lo[3] = {p.c.x, p.c.y, p.c.z}, hi[3] = {p.r.x, p.r.y, p.r.z}, oo[3] = {o.x, o.y, o.z};
    for (int a = 0; a < 3; ++a) {
        // D is -1 on every axis: entering through the high face.
        double ta = (oo[a] - hi[a]), tb = (oo[a] - lo[a]);
        if (ta > t0) {
            t0 = ta;
            n0 = {a == 0 ? 1.0 : 0.0, a == 1 ? 1.0 : 0.0, a == 2 ? 1.0 : 0.0};
        }
        t1 = std::min(t1, tb);
    }
    if (t0 <= t1 && t0 >= 0 && t0 < h.t) h = {t0, n0, p.material};
}

void hit_ellipsoid(const Prim& p, V3 o, Hit& h) {
    V3 q = o - p.c;
    V3 qs{q.x / p.r.x, q.y / p.r.y, q.z / p.r.z}, ds{D.x / p.r.x, D.y / p.r.y, D.z / p.r.z};
    double a = dot(ds, ds), b = 2 * dot(qs, ds), c = dot(qs, qs) - 1;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return;
    double t = (-b - std::sqrt(disc)) / (2 * a);
    if (t < 0 || t >= h.t) return;
    V3 x = q + D * t;
    h = {t, unit({x.x / (p.r.x * p.r.x), x.y / (p.r.y * p.r.y), x.z / (p.r.z * p.r.z)}), p.material};
}

void hit_cylinder(const Prim& p, V3 o, Hit& h) {
    const double r = p.r.x, z0 = p.c.z, z1 = p.c.z + p.r.z;
    // Top cap first (seen from above).
    double tc = o.z - z1;
    if (tc >= 0 && tc < h.t) {
        V3 x = o + D * tc;
        double dx = x.x - p.c.x, dy = x.y - p.c.y;
        if (dx * dx + dy * dy <= r * r) {
            h = {tc, {0, 0, 1}, p.material};
            return;
        }
    }
    double qx = o.x - p.c.x, qy = o.y - p.c.y;
    double a = 2, b = -2 * (qx + qy), c = qx * qx + qy * qy - r * r;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return;
    double t = (-b - std::sqrt(disc)) / (2 * a);
    V3 x = o + D * t;
    if (t < 0 || t >= h.t || x.z < z0 || x.z > z1) return;
    h = {t, unit({x.x - p.c.x, x.y - p.c.y, 0}), p.material};
}

void hit_cone(const Prim& p, V3 o, Hit& h) {
    // Radius shrinks linearly from r at z0 to 0 at z0 + height. Solved by
    // bisection-free quadratic on (x^2 + y^2) = (k (zt - z))^2.
    const double r = p.r.x, z0 = p.c.z, ht = p.r.z, zt = z0 + ht, k = r / ht;
    double qx = o.x - p.c.x, qy = o.y - p.c.y, qz = zt - o.z;  // qz: depth below apex at t = 0
    // point: (qx - t, qy - t), depth below apex: qz + t
    double a = 2 - k * k, b = -2 * (qx + qy) - 2 * k * k * qz, c = qx * qx + qy * qy - k * k * qz * qz;
    double disc = b * b - 4 * a * c;
    if (disc < 0) return;
    double s = std::sqrt(disc);
    double ts[2] = {(-b - s) / (2 * a), (-b + s) / (2 * a)};
    if (ts[0] > ts[1]) std::swap(ts[0], ts[1]);
    for (double t : ts) {
        V3 x = o + D * t;
        if (t < 0 || t >= h.t || x.z < z0 || x.z > zt) continue;
        double dx = x.x - p.c.x, dy = x.y - p.c.y, rr = std::sqrt(dx * dx + dy * dy);
        V3 n = rr > 0 ? V3{dx / rr, dy / rr, k} : V3{0, 0, 1};
        h = {t, unit(n), p.material};
        return;
    }
}

struct Model {
    std::vector<Material> materials;
    std::vector<Prim> prims;
    double shadow_rx = 0, shadow_ry = 0;  // soft ground shadow ellipse (screen pixels), 0: none
    double shadow_dx = 0;                 // the shadow's centre, screen pixels right of the anchor
    bool floor = false;
};

// How a tileset is lit and inked: the sun its shading bakes in, and whether
// its overlays carry dark outlines (at their silhouette and where the
// surface jumps in depth), as much hand-drawn game art does.
struct Look {
    V3 sun;
    double ambient = 0.38;   // the light a face turned from the sun keeps
    bool outlines = false;
    // Whether the ground hides what lies below it (a rock's buried half):
    // the view ray only descends, so a hit below z = 0 is behind the ground.
    bool ground_hides = false;
};

Hit cast(const Model& m, V3 o) {
    Hit h;
    for (const Prim& p : m.prims) {
        switch (p.shape) {
            case Shape::box: hit_box(p, o, h); break;
            case Shape::ellipsoid: hit_ellipsoid(p, o, h); break;
            case Shape::cylinder: hit_cylinder(p, o, h); break;
            case Shape::cone: hit_cone(p, o, h); break;
        }
    }
    return h;
}

double pattern_value(const Material& mat, V3 x, std::uint64_t seed) {
    double n = value_noise(seed, (x.x + x.z * 0.7) * mat.freq, (x.y - x.z * 0.4) * mat.freq);
    switch (mat.pattern) {
        case 1: {  // bricks: mortar lines every 8 px vertically, staggered every 16 px
            double row = std::floor(x.z / 8.0);
            double u = x.x + x.y + (std::fmod(row, 2.0) == 0 ? 0 : 8);
            double fu = u / 16.0 - std::floor(u / 16.0), fz = x.z / 8.0 - row;
            if (fu < 0.1 || fz < 0.15) return -0.9;
            return n - 0.5;
        }
        case 2: {  // cobbles: cells with dark gaps
            double cx = x.x / 12.0, cy = x.y / 12.0;
            double fx = cx - std::floor(cx), fy = cy - std::floor(cy);
            if (fx < 0.12 || fy < 0.12) return -0.8;
            return value_noise(seed + 7, std::floor(cx), std::floor(cy)) - 0.5 + (n - 0.5) * 0.5;
        }
        case 3:  // waves: stretched noise
            return value_noise(seed, x.x * mat.freq * 0.4, x.y * mat.freq * 2.0) - 0.5;
        case 4:  // leaves: two octaves, strong
            return (n - 0.5) + 0.6 * (value_noise(seed + 3, x.x * 0.5, (x.y + x.z) * 0.5) - 0.5);
        default:
            return n - 0.5;
    }
}

const Look kDefaultLook{unit({0.35, 0.6, 1.0}), 0.38, false, false};  // the sun from the upper left of the screen
// The town's sun from the upper right, lower, with more contrast; dark outlines.
const Look kTownLook{unit({0.8, -0.25, 0.7}), 0.3, true, true};
// Outlines: an opaque pixel beside a transparent one, or beside one whose
// visible height differs by more than this many pixels (a roof's step, a
// crown before a trunk), is inked.
constexpr int outline_depth = 8;
constexpr double outline_shade = 0.3;

struct Rendered {
    Image image;
    std::vector<std::uint16_t> height;
};

// Darkens the pixels of an object's outline (Look::outlines): opaque (alpha
// at least half) with a 4-neighbour that is not, or whose height differs
// by more than outline_depth. Decided before any pixel is inked, so the ink
// does not spread.
void ink_outlines(Rendered& r, int w, int h) {
    auto solid = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && r.image.at(x, y)[3] >= 128; };
    auto height = [&](int x, int y) { return int(r.height[std::size_t(y) * w + x]); };
    std::vector<std::uint8_t> ink(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!solid(x, y)) continue;
            const int n[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
            for (const auto& q : n)
                if (!solid(q[0], q[1]) || std::abs(height(q[0], q[1]) - height(x, y)) > outline_depth)
                    ink[std::size_t(y) * w + x] = 1;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (ink[std::size_t(y) * w + x])
                for (int k = 0; k < 3; ++k) r.image.at(x, y)[k] = std::uint8_t(r.image.at(x, y)[k] * outline_shade + 0.5);
}

Rendered render_model(const Model& m, const Look& look, int w, int h, double ax, double ay, double scale,
                      std::uint64_t seed) {
    Rendered out{Image(w, h), std::vector<std::uint16_t>(std::size_t(w) * h, 0)};
    const double zstart = 1000;
    for (int py = 0; py < h; ++py) {
        for (int px = 0; px < w; ++px) {
            double acc[3] = {0, 0, 0}, cover = 0, zsum = 0, shadow = 0;
            int hits = 0;
            for (int s = 0; s < 4; ++s) {
                // Screen offset from the anchor, in unscaled world pixels.
                double sx = (px + 0.25 + 0.5 * (s & 1) - ax) / scale;
                double sy = (py + 0.25 + 0.5 * (s >> 1) - ay) / scale;
                V3 o{(2 * (sy + zstart) + sx) / 2, (2 * (sy + zstart) - sx) / 2, zstart};
                Hit hit = cast(m, o);
                if (look.ground_hides && !m.floor && hit.material >= 0 && (o + D * hit.t).z < 0) hit = Hit{};
                if (hit.material < 0) {
                    if (m.shadow_rx > 0) {
                        double ex = (sx - m.shadow_dx) / m.shadow_rx, ey = sy / m.shadow_ry, d = ex * ex + ey * ey;
                        if (d < 1) shadow += (1 - d) * 0.45;
                    }
                    continue;
                }
                V3 x = o + D * hit.t;
                const Material& mat = m.materials[hit.material];
                double lambert = std::max(0.0, dot(hit.n, look.sun));
                double light = look.ambient + (1 - look.ambient) * lambert;
                if (!m.floor) light *= 0.72 + 0.28 * std::min(1.0, std::max(0.0, x.z) / 18.0);  // grounding
                double var = 1 + mat.grain * 2 * pattern_value(mat, x, seed + std::uint64_t(hit.material));
                const double c[3] = {mat.albedo.x, mat.albedo.y, mat.albedo.z};
                for (int k = 0; k < 3; ++k) acc[k] += std::min(1.0, std::max(0.0, c[k] * var * light));
                cover += 1;
                zsum += std::max(0.0, x.z) * scale;
                ++hits;
            }
            std::uint8_t* d = out.image.at(px, py);
            if (hits > 0) {
                for (int k = 0; k < 3; ++k) d[k] = std::uint8_t(acc[k] / hits * 255 + 0.5);
                double a = cover / 4 + (shadow / 4) * (1 - cover / 4);
                d[3] = std::uint8_t(std::min(1.0, a) * 255 + 0.5);
                out.height[std::size_t(py) * w + px] = std::uint16_t(zsum / hits + 0.5);
            } else if (shadow > 0) {
                d[0] = 12, d[1] = 20, d[2] = 16;
                d[3] = std::uint8_t(std::min(1.0, shadow / 4) * 255 + 0.5);
            }
        }
    }
    if (look.outlines && !m.floor) ink_outlines(out, w, h);
    return out;
}

Prim box(V3 lo, V3 hi, int mat) { return {Shape::box, lo, hi, mat}; }
Prim ellipsoid(V3 c, V3 r, int mat) { return {Shape::ellipsoid, c, r, mat}; }
Prim cylinder(V3 base, double radius, double height, int mat) { return {Shape::cylinder, base, {radius, 0, height}, mat}; }
Prim cone(V3 base, double radius, double height, int mat) { return {Shape::cone, base, {radius, 0, height}, mat}; }

Model floor_block(Material top, Material side, double top_z = 0) {
    Model m;
    m.floor = true;
    m.materials = {top, side};
    // The top face (material 0) is a thin slab over the block's body (material 1).
    m.prims = {box({-32, -32, top_z - 3}, {32, 32, top_z}, 0), box({-32, -32, -24}, {32, 32, top_z - 3}, 1)};
    return m;
}

struct Def {
    std::string name;
    SpriteKind kind;
    std::string tag;
    Model model;
    // The sprite's size and anchor row at scale 1 (0: the tile's 128 x 128,
    // anchored 108 rows down for an overlay); wider than a tile for a mountain.
    int width = 0, height = 0, anchor_y = 0;
};

std::vector<Def> default_definitions() {
    const Material bark{{0.42, 0.29, 0.18}, 0.18, 0.5};
    const Material earth{{0.45, 0.32, 0.2}, 0.12, 0.3};
    std::vector<Def> d;
    d.push_back({"grass", SpriteKind::floor, "grass", floor_block({{0.36, 0.62, 0.26}, 0.16, 0.3, 4}, earth)});
    d.push_back({"dirt", SpriteKind::floor, "dirt", floor_block({{0.55, 0.40, 0.25}, 0.14, 0.35}, {{0.43, 0.3, 0.19}, 0.1, 0.3})});
    d.push_back({"sand", SpriteKind::floor, "sand", floor_block({{0.86, 0.78, 0.55}, 0.07, 0.5}, {{0.72, 0.62, 0.42}, 0.08, 0.4})});
    d.push_back({"stone", SpriteKind::floor, "stone", floor_block({{0.6, 0.6, 0.62}, 0.25, 0.3, 2}, {{0.45, 0.45, 0.48}, 0.15, 0.3})});
    d.push_back({"water", SpriteKind::floor, "water", floor_block({{0.22, 0.45, 0.75}, 0.18, 0.12, 3}, {{0.16, 0.3, 0.55}, 0.1, 0.2}, -4)});
    {
        Model m;
        m.materials = {bark, {{0.28, 0.55, 0.2}, 0.3, 0.35, 4}};
        m.prims = {cylinder({0, 0, 0}, 5, 44, 0), ellipsoid({0, 0, 62}, {26, 26, 22}, 1),
                   ellipsoid({10, -8, 50}, {16, 16, 14}, 1), ellipsoid({-9, 9, 54}, {15, 15, 13}, 1)};
        m.shadow_rx = 34, m.shadow_ry = 14;
        d.push_back({"oak", SpriteKind::overlay, "tree", m});
    }
    {
        Model m;
        m.materials = {bark, {{0.16, 0.42, 0.24}, 0.25, 0.45, 4}};
        m.prims = {cylinder({0, 0, 0}, 4, 16, 0), cone({0, 0, 10}, 22, 46, 1), cone({0, 0, 36}, 17, 42, 1),
                   cone({0, 0, 60}, 12, 40, 1)};
        m.shadow_rx = 28, m.shadow_ry = 12;
        d.push_back({"pine", SpriteKind::overlay, "tree", m});
    }
    {
        Model m;
        m.materials = {{{0.86, 0.84, 0.78}, 0.2, 0.6}, {{0.5, 0.68, 0.24}, 0.3, 0.4, 4}};
        m.prims = {cylinder({0, 0, 0}, 4, 56, 0), ellipsoid({0, 0, 74}, {18, 18, 26}, 1),
                   ellipsoid({6, 6, 58}, {12, 12, 12}, 1)};
        m.shadow_rx = 24, m.shadow_ry = 10;
        d.push_back({"birch", SpriteKind::overlay, "tree", m});
    }
    {
        Model m;
        m.materials = {{{0.3, 0.55, 0.22}, 0.3, 0.4, 4}};
        m.prims = {ellipsoid({0, 0, 10}, {17, 17, 13}, 0), ellipsoid({9, -6, 8}, {11, 11, 9}, 0),
                   ellipsoid({-7, 8, 9}, {11, 11, 10}, 0)};
        m.shadow_rx = 24, m.shadow_ry = 10;
        d.push_back({"bush", SpriteKind::overlay, "bush", m});
    }
    {
        Model m;
        m.materials = {{{0.22, 0.42, 0.2}, 0.3, 0.4, 4}, {{0.75, 0.15, 0.2}, 0.1, 0.5}};
        m.prims = {ellipsoid({0, 0, 9}, {14, 14, 11}, 0), ellipsoid({5, 8, 14}, {2.5, 2.5, 2.5}, 1),
                   ellipsoid({9, -2, 12}, {2.5, 2.5, 2.5}, 1), ellipsoid({-3, 11, 8}, {2.5, 2.5, 2.5}, 1)};
        m.shadow_rx = 18, m.shadow_ry = 8;
        d.push_back({"berry_bush", SpriteKind::overlay, "bush", m});
    }
    {
        Model m;
        m.materials = {{{0.55, 0.54, 0.52}, 0.22, 0.3}};
        m.prims = {ellipsoid({0, 0, 4}, {16, 12, 11}, 0), ellipsoid({8, 6, 2}, {8, 7, 6}, 0)};
        m.shadow_rx = 20, m.shadow_ry = 8;
        d.push_back({"rock", SpriteKind::overlay, "rock", m});
    }
    {
        Model m;
        m.materials = {{{0.5, 0.48, 0.45}, 0.22, 0.25}};
        m.prims = {ellipsoid({0, 0, 8}, {22, 20, 20}, 0), ellipsoid({-14, 10, 3}, {9, 9, 7}, 0)};
        m.shadow_rx = 28, m.shadow_ry = 11;
        d.push_back({"boulder", SpriteKind::overlay, "rock", m});
    }
    {
        Model m;
        m.materials = {{{0.62, 0.56, 0.5}, 0.22, 0.4, 1}, {{0.5, 0.47, 0.44}, 0.1, 0.3}};
        m.prims = {box({-30, -6, 0}, {30, 6, 36}, 0), box({-31, -7, 36}, {31, 7, 40}, 1)};
        m.shadow_rx = 0;
        d.push_back({"wall", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {{{0.55, 0.38, 0.22}, 0.15, 0.5}};
        for (int i = -1; i <= 1; ++i) m.prims.push_back(box({-2, i * 26.0 - 2, 0}, {2, i * 26.0 + 2, 26}, 0));
        m.prims.push_back(box({-1.5, -30, 17}, {1.5, 30, 21}, 0));
        m.prims.push_back(box({-1.5, -30, 7}, {1.5, 30, 11}, 0));
        d.push_back({"fence", SpriteKind::overlay, "wall", m});
    }
    return d;
}

// The town: what real games draw beside trees (walls, houses, a town in one
// tile, rocks, a mountain wider than a tile, a tower, a fence, a grove whose
// crowns merge, a tall thin tree), in another palette under kTownLook.
std::vector<Def> town_definitions() {
    const Material plaster{{0.88, 0.83, 0.72}, 0.08, 0.4};
    const Material stone{{0.58, 0.52, 0.46}, 0.2, 0.4, 1};
    const Material tiles{{0.74, 0.31, 0.2}, 0.18, 0.3, 3};
    const Material slate{{0.33, 0.37, 0.47}, 0.15, 0.35, 3};
    const Material bark{{0.3, 0.2, 0.16}, 0.18, 0.5};
    const Material granite{{0.55, 0.52, 0.58}, 0.25, 0.3};
    const Material wood{{0.5, 0.33, 0.18}, 0.15, 0.5};
    const std::vector<Material> crowns = {{{0.85, 0.47, 0.14}, 0.3, 0.35, 4},
                                          {{0.72, 0.24, 0.12}, 0.3, 0.35, 4},
                                          {{0.86, 0.7, 0.2}, 0.3, 0.35, 4}};
    const Material earth{{0.5, 0.34, 0.26}, 0.12, 0.3};
    std::vector<Def> d;
    d.push_back({"grass", SpriteKind::floor, "grass", floor_block({{0.55, 0.58, 0.3}, 0.16, 0.3, 4}, earth)});
    d.push_back({"dirt", SpriteKind::floor, "dirt", floor_block({{0.6, 0.38, 0.28}, 0.14, 0.35}, earth)});
    d.push_back({"sand", SpriteKind::floor, "sand", floor_block({{0.9, 0.84, 0.68}, 0.07, 0.5}, earth)});
    d.push_back({"paving", SpriteKind::floor, "stone", floor_block({{0.7, 0.64, 0.56}, 0.2, 0.3, 2}, earth)});
    d.push_back({"water", SpriteKind::floor, "water",
                 floor_block({{0.2, 0.52, 0.58}, 0.18, 0.12, 3}, {{0.14, 0.34, 0.4}, 0.1, 0.2}, -4)});
    {
        Model m;
        m.materials = {stone};
        m.prims = {box({-31, -5, 0}, {31, 5, 30}, 0)};
        for (int i = 0; i < 6; ++i) m.prims.push_back(box({-31 + 11.0 * i, -6, 30}, {-25 + 11.0 * i, 6, 36}, 0));
        d.push_back({"long_wall", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {plaster, tiles};
        m.prims = {box({-20, -14, 0}, {20, 14, 24}, 0), box({-22, -16, 24}, {22, 16, 29}, 1),
                   box({-22, -10, 29}, {22, 10, 34}, 1), box({-22, -4, 34}, {22, 4, 39}, 1)};
        m.shadow_rx = 34, m.shadow_ry = 13, m.shadow_dx = -12;
        d.push_back({"house", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {plaster, slate};
        m.prims = {cylinder({0, 0, 0}, 14, 20, 0), cone({0, 0, 20}, 18, 18, 1)};
        m.shadow_rx = 26, m.shadow_ry = 10, m.shadow_dx = -10;
        d.push_back({"round_hut", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {stone, slate};
        m.prims = {cylinder({0, 0, 0}, 11, 64, 0), cone({0, 0, 64}, 14, 22, 1)};
        m.shadow_rx = 20, m.shadow_ry = 8, m.shadow_dx = -10;
        d.push_back({"tower", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {wood};
        for (int i = -1; i <= 1; ++i) m.prims.push_back(box({i * 26.0 - 2, -2, 0}, {i * 26.0 + 2, 2, 22}, 0));
        m.prims.push_back(box({-30, -1.5, 14}, {30, 1.5, 17}, 0));
        m.prims.push_back(box({-30, -1.5, 5}, {30, 1.5, 8}, 0));
        d.push_back({"fence", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {crowns[2]};
        m.prims = {box({-24, -6, 0}, {24, 6, 12}, 0)};
        m.shadow_rx = 30, m.shadow_ry = 10, m.shadow_dx = -8;
        d.push_back({"hedge", SpriteKind::overlay, "bush", m});
    }
    {
        Model m;
        m.materials = {granite};
        m.prims = {ellipsoid({-12, 6, 0}, {9, 8, 6}, 0), ellipsoid({8, -4, 0}, {11, 9, 8}, 0),
                   ellipsoid({2, 14, 0}, {6, 6, 4}, 0)};
        m.shadow_rx = 24, m.shadow_ry = 9, m.shadow_dx = -6;
        d.push_back({"low_rocks", SpriteKind::overlay, "rock", m});
    }
    {
        Model m;
        m.materials = {granite};
        m.prims = {ellipsoid({-8, 4, 8}, {14, 13, 12}, 0), ellipsoid({10, -6, 7}, {12, 11, 10}, 0),
                   ellipsoid({2, 2, 22}, {10, 10, 9}, 0), ellipsoid({-14, -12, 4}, {7, 7, 6}, 0)};
        m.shadow_rx = 30, m.shadow_ry = 11, m.shadow_dx = -8;
        d.push_back({"boulder_pile", SpriteKind::overlay, "rock", m});
    }
    {
        Model m;
        m.materials = {bark, crowns[0], crowns[1], crowns[2]};
        const double trees[6][3] = {{-16, -14, 36}, {6, -20, 40}, {20, 2, 34}, {-4, 4, 42}, {-20, 12, 38}, {10, 18, 35}};
        for (const auto& t : trees) m.prims.push_back(cylinder({t[0], t[1], 0}, 2.5, t[2] - 6, 0));
        for (int i = 0; i < 6; ++i)
            m.prims.push_back(ellipsoid({trees[i][0], trees[i][1], trees[i][2]}, {12, 12, 11}, 1 + i % 3));
        m.shadow_rx = 40, m.shadow_ry = 16, m.shadow_dx = -10;
        d.push_back({"grove", SpriteKind::overlay, "tree", m});
    }
    {
        Model m;
        m.materials = {bark, crowns[2]};
        m.prims = {cylinder({0, 0, 0}, 2.5, 74, 0), ellipsoid({0, 0, 86}, {11, 11, 16}, 1),
                   ellipsoid({4, -3, 73}, {7, 7, 6}, 1)};
        m.shadow_rx = 14, m.shadow_ry = 6, m.shadow_dx = -8;
        d.push_back({"tall_tree", SpriteKind::overlay, "tree", m});
    }
    {
        Model m;
        m.materials = {plaster, tiles, slate, stone};
        m.prims = {box({-28, -28, 0}, {-8, -10, 18}, 0), box({-29, -29, 18}, {-7, -9, 22}, 1),
                   box({4, -28, 0}, {28, -8, 14}, 3),   box({3, -29, 14}, {29, -7, 18}, 2),
                   box({-26, 4, 0}, {-6, 26, 22}, 0),   box({-27, 3, 22}, {-5, 27, 26}, 1),
                   box({-27, 9, 26}, {-5, 21, 30}, 1),  box({2, 2, 0}, {10, 10, 10}, 0),
                   box({1, 1, 10}, {11, 11, 13}, 2),    cylinder({16, 16, 0}, 7, 30, 3),
                   cone({16, 16, 30}, 9, 12, 2)};
        d.push_back({"town", SpriteKind::overlay, "wall", m});
    }
    {
        Model m;
        m.materials = {{{0.5, 0.44, 0.4}, 0.22, 0.3}, {{0.93, 0.94, 0.97}, 0.05, 0.3}};
        m.prims = {cone({0, 0, 0}, 58, 72, 0), ellipsoid({-30, 20, 0}, {30, 26, 30}, 0),
                   ellipsoid({28, -18, 0}, {28, 24, 26}, 0), cone({0, 0, 49.5}, 18.5, 23, 1)};
        m.shadow_rx = 90, m.shadow_ry = 34, m.shadow_dx = -14;
        d.push_back({"mountain", SpriteKind::overlay, "rock", m, 256, 160, 112});
    }
    return d;
}

// The primitive as the manifest's solid, in sprite pixels (the scale applied).
Solid to_solid(const Prim& p, double scale) {
    auto v = [&](V3 a) { return Vec3{a.x * scale, a.y * scale, a.z * scale}; };
    switch (p.shape) {
        case Shape::box: return {SolidKind::box, v(p.c), v(p.r)};
        case Shape::ellipsoid: return {SolidKind::ellipsoid, v(p.c), v(p.r)};
        case Shape::cylinder: return {SolidKind::cylinder, v(p.c), {p.r.x * scale, p.r.x * scale, p.r.z * scale}};
        case Shape::cone: return {SolidKind::cone, v(p.c), {p.r.x * scale, p.r.x * scale, p.r.z * scale}};
    }
    return {};
}

GeneratedTileset generate_tileset(const std::vector<Def>& defs, const Look& look, std::string_view seed_text,
                                  double scale) {
    GeneratedTileset g;
    const int size = int(128 * scale + 0.5);
    g.tileset.tile_width = size;
    g.tileset.tile_height = size / 2;
    const std::uint64_t seed = hash_seed(seed_text);
    std::uint64_t i = 0;
    for (const Def& def : defs) {
        Sprite s;
        s.name = def.name;
        s.kind = def.kind;
        s.tags = {def.tag};
        const int w = def.width ? int(def.width * scale + 0.5) : size, h = def.height ? int(def.height * scale + 0.5) : size;
        s.anchor_x = w / 2;
        // Floors: the diamond's centre with the diamond at the top of the
        // sprite, the block's sides below. Overlays: the ground point low in
        // the sprite, leaving 108/128 of it for height.
        s.anchor_y = def.kind == SpriteKind::floor ? size / 4 : int((def.anchor_y ? def.anchor_y : 108) * scale + 0.5);
        Rendered r = render_model(def.model, look, w, h, s.anchor_x, s.anchor_y, scale, mix64(seed + ++i));
        s.image = std::move(r.image);
        for (const Prim& p : def.model.prims) s.shape.push_back(to_solid(p, scale));
        g.tileset.sprites.push_back(std::move(s));
        g.heights.push_back(std::move(r.height));
        g.image_files.push_back(def.name + ".png");
    }
    return g;
}

}  // namespace

GeneratedTileset generate_default_tileset(double scale) {
    return generate_tileset(default_definitions(), kDefaultLook, "isolux default tileset", scale);
}

GeneratedTileset generate_town_tileset(double scale) {
    return generate_tileset(town_definitions(), kTownLook, "isolux town tileset", scale);
}

Sprite generate_character_sprite(double scale) {
    Model m;
    m.materials = {{{0.25, 0.22, 0.35}, 0.08, 0.3},   // trousers
                   {{0.72, 0.2, 0.18}, 0.1, 0.3},     // coat
                   {{0.93, 0.76, 0.6}, 0.05, 0.3},    // face
                   {{0.98, 0.86, 0.42}, 0.02, 0.3}};  // lantern
    m.prims = {cylinder({-3, 3, 0}, 3, 16, 0),       cylinder({3, -3, 0}, 3, 16, 0),
               cylinder({0, 0, 15}, 7, 18, 1),       ellipsoid({0, 0, 39}, {6, 6, 7}, 2),
               cylinder({8, 6, 20}, 2, 10, 1),       ellipsoid({10, 8, 16}, {3, 3, 4}, 3)};
    m.shadow_rx = 12, m.shadow_ry = 5;
    Sprite s;
    s.name = "character";
    s.kind = SpriteKind::overlay;
    const int w = int(48 * scale + 0.5), h = int(80 * scale + 0.5);
    s.anchor_x = w / 2;
    s.anchor_y = int(72 * scale + 0.5);
    s.image = render_model(m, kDefaultLook, w, h, s.anchor_x, s.anchor_y, scale, hash_seed("isolux character")).image;
    return s;
}

}  // namespace isolux
