// The references the 2.5D model is measured against: the true 3D shapes and
// the exact 2D line (core/src/truth/truth.cpp, core/src/solids/solid.cpp).
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "isolux/hash.hpp"
#include "isolux/height_rays.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/truth.hpp"
#include "isolux/sprite_shading.hpp"
#include "isolux/map.hpp"
#include "test_util.hpp"
#include "frame/trace_hooks.hpp"

using namespace isolux;

namespace {

// A surface of bare ground over `r`.
Surface ground(Rect r) {
    Surface s;
    s.rect = r;
    s.instance.assign(std::size_t(r.w) * r.h, -1);
    s.height.assign(s.instance.size(), 0.0f);
    return s;
}

WorldSolids one(const Solid& s) {
    WorldSolids w;
    w.solids = {s};
    w.bounds = {solid_bounds(s)};
    w.instance = {0};
    return w;
}

bool lit(const LightMask& m, int x, int y) {
    return m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] != 0;
}

Params wide() {
    Params p;
    p.falloff_scale = 1e6;  // no pixel of the area falls to 0 by distance
    return p;
}

}  // namespace

// The light stands 10 px above the ground point of screen pixel (0, 0):
// L = (0.75, 0.25, 10). Ground pixel (x, y) is P = (y + 0.5 + (x + 0.5) / 2,
// y + 0.5 - (x + 0.5) / 2, 0), so P = L + (dX, dY) is pixel
// (dX - dY, (dX + dY) / 2). A box stands at X in [10.75, 20.75], Y in
// [-4.75, 5.25]: 10 to 20 px from the light along X.
TEST(Truth, aLightBesideABoxCastsTheShadowWorkedOutByHand) {
    const Rect area{-100, -100, 201, 201};
    const Surface s = ground(area);
    const Params p = wide();
    const Solid tall{SolidKind::box, {10.75, -4.75, 0}, {20.75, 5.25, 1000}};
    const LightMask m = truth_light(s, one(tall), 0, 0, 10, 100, 100, p, area, false, 1.0);
    EXPECT_TRUE(lit(m, 0, 0));
    // P = L + (30, 0): straight behind the box: dark.
    EXPECT_FALSE(lit(m, 30, 15));
    // P = L + (30, 20): the line passes beside the box (dY from 6.7 to 13.3 across it): lit.
    EXPECT_TRUE(lit(m, 10, 25));
    // P = L + (-30, 0): the other way: lit.
    EXPECT_TRUE(lit(m, -30, -15));

    // A box 5 px high, lower than the light: its shadow ends. At L + (30, 0)
    // the line is at z 6.7 to 3.3 across the box: dark; at L + (60, 0), z 8.3
    // to 6.7: lit.
    const Solid low{SolidKind::box, {10.75, -4.75, 0}, {20.75, 5.25, 5}};
    const LightMask n = truth_light(s, one(low), 0, 0, 10, 100, 100, p, area, false, 1.0);
    EXPECT_FALSE(lit(n, 30, 15));
    EXPECT_TRUE(lit(n, 60, 30));
}

TEST(Truth, aLightAboveEverythingLightsAllTheGroundAroundASolid) {
    const Rect area{-60, -60, 121, 121};
    const Surface s = ground(area);
    const Solid low{SolidKind::box, {10.75, -4.75, 0}, {20.75, 5.25, 5}};
    const LightMask m = truth_light(s, one(low), 0, 0, 4000, 60, 60, wide(), area, false, 1.0);
    for (int y = area.y; y < area.y + area.h; ++y)
        for (int x = area.x; x < area.x + area.w; ++x) {
            const Vec3 p = ground_frame(x + 0.5, y + 0.5, 0);
            const bool under = p.x >= 10.75 - 2 && p.x <= 20.75 + 2 && p.y >= -4.75 - 2 && p.y <= 5.25 + 2;
            if (!under) {
                ASSERT_TRUE(lit(m, x, y)) << x << "," << y;
            }
        }
}

TEST(Truth, raisingALightNeverDarkensAGroundPixel) {
    // Solids standing on the ground, no wider above than below.
    WorldSolids w;
    for (const Solid& s : {Solid{SolidKind::box, {20, 0, 0}, {30, 12, 18}}, Solid{SolidKind::cylinder, {-20, 10, 0}, {6, 6, 30}},
                           Solid{SolidKind::cone, {5, -25, 0}, {9, 9, 25}}}) {
        w.solids.push_back(s);
        w.bounds.push_back(solid_bounds(s));
        w.instance.push_back(0);
    }
    const Rect area{-70, -70, 141, 141};
    const Surface s = ground(area);
    LightMask before = truth_light(s, w, 0, 0, 2, 70, 70, wide(), area, false, 1.0);
    for (double h : {6.0, 12.0, 24.0, 48.0, 96.0}) {
        const LightMask after = truth_light(s, w, 0, 0, h, 70, 70, wide(), area, false, 1.0);
        long darkened = 0, lit_before = 0;
        for (std::size_t i = 0; i < before.value.size(); ++i) {
            // Ground under a solid is hidden by it: not a ground pixel anyone sees.
            const int x = area.x + int(i % std::size_t(area.w)), y = area.y + int(i / std::size_t(area.w));
            const Vec3 p = ground_frame(x + 0.5, y + 0.5, 0);
            bool hidden = false;
            for (const auto& b : w.bounds)
                hidden = hidden || (p.x >= b[0].x - 2 && p.x <= b[1].x + 2 && p.y >= b[0].y - 2 && p.y <= b[1].y + 2);
            if (hidden) continue;
            darkened += before.value[i] && !after.value[i];
            lit_before += before.value[i] != 0;
        }
        EXPECT_EQ(darkened, 0) << "height " << h;
        EXPECT_GT(lit_before, 0);
        before = after;
    }
}

TEST(Truth, facingDarkensWhatTheLightSeesFromBehind) {
    // A ground pixel always faces a light above it; the facing reference adds
    // darkness only on sprites, never on bare ground.
    const Rect area{-30, -30, 61, 61};
    const Surface s = ground(area);
    const WorldSolids none;
    const LightMask a = truth_light(s, none, 0, 0, 20, 30, 30, wide(), area, false, 1.0);
    const LightMask b = truth_light(s, none, 0, 0, 20, 30, 30, wide(), area, true, 1.0);
    EXPECT_EQ(a.value, b.value);
    for (std::uint8_t v : a.value) ASSERT_NE(v, 0);
}

// 3d_shaded: the ground as 3d gives it; on sprites never brighter than 3d,
// dark wherever 3d_facing is (a surface turned away has a cosine of 0), and
// elsewhere 3d's light times the cosine between the true normal and the
// direction to the light, which the shapes' normals give (sprite_normals).
TEST(Truth, theShadedReferenceIsThe3dLightTimesLambertsCosineOnSprites) {
    test::CentredLight scene = test::centred_light(8, 48, 40);
    Scene& s = scene.scene;
    const World& w = scene.world;
    const Rect v = scene.view;
    const Light& l = s.lights[0];
    const LightTexture flat = reference_texture(w, s, v, Reference::three_d),
                       facing = reference_texture(w, s, v, Reference::three_d_facing),
                       shaded = reference_texture(w, s, v, Reference::three_d_shaded);
    const Surface surface = build_surface(w, v, s.params.opacity_threshold);
    Params shapes = s.params;
    shapes.sprite_shading = SpriteShading::shapes;
    NormalsCache cache;
    const ShadingMap normals = build_shading_map(w, shapes, v, cache);
    const Vec3 light = ground_frame(std::floor(l.x) + 0.5, std::floor(l.y) + 0.5, 0) + Vec3{0, 0, 48};
    long sprite = 0, lit = 0, dimmed = 0, near_cosine = 0, compared = 0;
    for (int y = v.y; y < v.y + v.h; ++y)
        for (int x = v.x; x < v.x + v.w; ++x) {
            const int f = flat.value(x, y, 0), sh = shaded.value(x, y, 0);
            const std::size_t i = std::size_t(y - v.y) * v.w + std::size_t(x - v.x);
            if (surface.instance[i] < 0) {
                ASSERT_EQ(sh, f) << "ground at " << x << "," << y;
                continue;
            }
            ++sprite;
            ASSERT_LE(sh, f) << x << "," << y;
            if (facing.value(x, y, 0) == 0) {
                ASSERT_EQ(sh, 0) << x << "," << y;
            }
            lit += f > 0;
            dimmed += sh < f;
            if (f < 40) continue;
            const auto& q = normals.normal[i];
            const double cosine = lambert(glm::normalize(Vec3{double(q[0]), double(q[1]), double(q[2])}),
                                          ground_frame(x + 0.5, y + 0.5, normals.height[i]), light);
            ++compared;
            near_cosine += std::abs(sh - f * cosine) <= 0.05 * f + 1;
        }
    EXPECT_GT(sprite, 1000);
    EXPECT_GT(dimmed, lit / 2) << dimmed << " of " << lit << " lit sprite pixels";
    ASSERT_GT(compared, 1000);
    EXPECT_GT(near_cosine, 0.95 * compared) << near_cosine << " of " << compared;
}

TEST(Truth, exactLineEqualsAlgorithm2TracedToEachPixel) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        const Rect area{-20, -14, 41, 29};
        Mask obstacles(area);
        Pcg32 rng(seed);
        for (auto& b : obstacles.bits) b = rng.below(100) < 12;
        obstacles.set(0, 0, false);
        Params p;
        const LightMask m = exact_line_light(obstacles, 0, 0, 20, 14, p, area, 1.0);
        for (int y = area.y; y < area.y + area.h; ++y)
            for (int x = area.x; x < area.x + area.w; ++x) {
                std::vector<std::uint8_t> tex(std::size_t(area.w) * area.h, 0);
                trace_light_ray_paper(obstacles, 0, 0, x, y, area, tex);
                const std::uint8_t own = tex[std::size_t(y - area.y) * area.w + (x - area.x)];
                ASSERT_EQ(lit(m, x, y), own != 0) << "seed " << seed << " pixel " << x << "," << y;
            }
    }
}

TEST(Truth, theGeneratorsShapesReproduceItsSpritesOpaquePixels) {
    const GeneratedTileset g = generate_default_tileset(1.0);
    for (const Sprite& s : g.tileset.sprites) {
        if (s.kind != SpriteKind::overlay) continue;
        ASSERT_FALSE(s.shape.empty()) << s.name;
        const int w = s.image.width, h = s.image.height;
        std::vector<char> covered(std::size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                covered[std::size_t(y) * w + x] = surface_height(s.shape, x + 0.5 - s.anchor_x, y + 0.5 - s.anchor_y) > -HUGE_VAL;
        long wrong = 0, opaque = 0;
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                // Away from the antialiased edge: the 3x3 neighbourhood agrees.
                const char c = covered[std::size_t(y) * w + x];
                bool edge = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) edge = edge || covered[std::size_t(y + dy) * w + x + dx] != c;
                if (edge) continue;
                const bool is_opaque = s.image.at(x, y)[3] >= 192;  // above any baked ground shadow
                opaque += is_opaque;
                wrong += is_opaque != bool(c);
            }
        EXPECT_EQ(wrong, 0) << s.name << " (" << opaque << " opaque pixels)";
        EXPECT_GT(opaque, 50) << s.name;
    }
}

// One intensity for every tracer: where nothing blocks, the paper's tracer
// (then shape_light, as render_frame does), the exact line, the 3D reference
// and rays over obstacles all give shaped_falloff, for each falloff shape and
// edge fade, on the screen and on the ground (dy_scale 2: a round light's
// pool is an ellipse; a round, faded light has no square edge in any of them).
TEST(Truth, everyTracerGivesTheOneIntensityFunctionForEveryShapeAndFade) {
    const Rect area{-30, -20, 61, 41};
    const Mask clear(area);
    const Surface s = ground(area);
    const WorldSolids nothing;
    for (FalloffShape shape : {FalloffShape::chebyshev, FalloffShape::euclidean})
        for (bool fade : {false, true})
        for (double dy_scale : {1.0, 2.0}) {
            Params p;
            p.falloff_space = dy_scale == 1.0 ? FalloffSpace::screen : FalloffSpace::ground;
            p.falloff_scale = 6;
            p.falloff_shape = shape;
            p.edge_fade = fade;
            LightMask paper = trace_light(clear, 0, 0, 30, 20, p, area, true);
            paper.dy_scale = dy_scale;  // as render_frame sets it from the tileset
            shape_light(paper, p);
            const LightMask line = exact_line_light(clear, 0, 0, 30, 20, p, area, dy_scale);
            const LightMask truth = truth_light(s, nothing, 0, 0, 32, 30, 20, p, area, false, dy_scale);
            ObstacleHeights flat;
            flat.rect = area;
            flat.height.assign(clear.bits.size(), 0);
            LightMask over = trace_light_over(clear, flat, 0, 0, 30, 20, 32, p, area);
            over.dy_scale = dy_scale;
            shape_light(over, p);
            long faded = 0;
            for (int y = area.y; y < area.y + area.h; ++y)
                for (int x = area.x; x < area.x + area.w; ++x) {
                    const std::uint8_t want = shaped_falloff(x, y, 30, 20, p, dy_scale);
                    const std::size_t i = std::size_t(y - area.y) * area.w + (x - area.x);
                    ASSERT_EQ(paper.value[i], want) << int(shape) << fade << dy_scale << " paper " << x << "," << y;
                    ASSERT_EQ(line.value[i], want) << int(shape) << fade << dy_scale << " exact_line " << x << "," << y;
                    ASSERT_EQ(truth.value[i], want) << int(shape) << fade << dy_scale << " 3d " << x << "," << y;
                    ASSERT_EQ(over.value[i], want) << int(shape) << fade << dy_scale << " over " << x << "," << y;
                    faded += fade && want == 0;
                }
            if (fade && shape == FalloffShape::euclidean) {
                EXPECT_GT(faded, 100);  // the round light's corners: nothing
            }
        }
}

// The 3D reference on a curved sprite surface whose heights are whole pixels
// (as a height map stores them): every pixel that faces the light clearly is
// lit, with no bands of self-shadow from a surface point rebuilt a fraction
// of a pixel inside its own solid. The ground around stays as it was.
TEST(Truth, aCurvedSurfaceFromWholePixelHeightsHasNoSelfShadowAcne) {
    const Solid canopy{SolidKind::ellipsoid, {0, 0, 45}, {28, 28, 24}};
    const Rect area{-120, -110, 241, 201};
    Surface s = ground(area);
    for (int y = area.y; y < area.y + area.h; ++y)
        for (int x = area.x; x < area.x + area.w; ++x) {
            const double h = surface_height({canopy}, x + 0.5, y + 0.5);
            if (!std::isfinite(h) || h < 0) continue;
            const std::size_t i = std::size_t(y - area.y) * area.w + (x - area.x);
            s.instance[i] = 0;
            s.height[i] = float(std::lround(h));
        }
    Params p = wide();
    for (const auto& [lx, ly, lh] : {std::array<double, 3>{-100, -20, 90}, {90, 30, 60}, {0, -100, 120}}) {
        const LightMask m = truth_light(s, one(canopy), std::int64_t(lx), std::int64_t(ly), lh, 120, 110, p, area, false, 1.0);
        // The light stands lh above the ground point its centre pixel shows.
        const Vec3 foot = ground_frame(std::floor(lx) + 0.5, std::floor(ly) + 0.5, 0);
        const Vec3 light{foot.x, foot.y, lh};
        long facing = 0, dark = 0;
        for (int y = area.y; y < area.y + area.h; ++y)
            for (int x = area.x; x < area.x + area.w; ++x) {
                const std::size_t i = std::size_t(y - area.y) * area.w + (x - area.x);
                if (s.instance[i] != 0) continue;
                const Vec3 q = ground_frame(x + 0.5, y + 0.5, s.height[i]);
                const Vec3 n = solid_normal(canopy, q);
                Vec3 l{light.x - q.x, light.y - q.y, light.z - q.z};
                const double len = std::sqrt(l.x * l.x + l.y * l.y + l.z * l.z);
                if ((n.x * l.x + n.y * l.y + n.z * l.z) / len < 0.3) continue;
                ++facing;
                dark += !lit(m, x, y);
            }
        EXPECT_GT(facing, 300);
        EXPECT_LE(dark, facing / 200) << "light at " << lx << "," << ly << " height " << lh << ": " << dark << " of "
                                      << facing << " facing pixels dark";
    }
}
