// Sprite shading: normals from the estimated solids, the shapes and the
// picture's brightness, and each light's sprite pixels shaded by them
// (core/src/shading/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "isolux/frame.hpp"
#include "isolux/map.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/sprite_shading.hpp"
#include "isolux/tileset_file.hpp"
#include "base/cpu.hpp"
#include "isolux/occluder_map.hpp"
#include "shading/oracles.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

double angle_deg(Vec3 a, Vec3 b) { return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * 180 / 3.14159265358979; }

// The mean angle between two sources' normals over the pixels both show.
double mean_angle(const SpriteNormals& a, const SpriteNormals& b) {
    double sum = 0;
    long n = 0;
    for (std::size_t i = 0; i < a.normal.size(); ++i) {
        if (glm::length(a.normal[i]) == 0 || glm::length(b.normal[i]) == 0) continue;
        sum += angle_deg(a.normal[i], b.normal[i]);
        ++n;
    }
    return n ? sum / double(n) : 0;
}

// A shading map of one pixel at (0, 0) showing a point `h` high with normal `n`.
ShadingMap one_pixel(Vec3 n, float h) {
    ShadingMap m;
    m.rect = {0, 0, 1, 1};
    m.normal = {{std::int8_t(std::lround(n.x * 127)), std::int8_t(std::lround(n.y * 127)), std::int8_t(std::lround(n.z * 127))}};
    m.height = {h};
    return m;
}

// A white light's mask over (0, 0) alone, value v there, centred at (cx, cy).
LightMask mask_at(std::int64_t cx, std::int64_t cy, std::uint8_t v) {
    LightMask m;
    m.clip = {0, 0, 1, 1};
    m.cx = cx, m.cy = cy;
    m.value = {v};
    return m;
}

}  // namespace

// The screen's tangent space is orthonormal in the ground frame, its +Z
// along the view line toward the viewer, and the ground tilts up the screen.
TEST(SpriteShading, theScreensTangentSpaceIsTheViewsFrame) {
    EXPECT_NEAR(glm::dot(screen_right, screen_up), 0, 1e-12);
    EXPECT_NEAR(glm::dot(screen_right, toward_viewer), 0, 1e-12);
    EXPECT_NEAR(glm::dot(screen_up, toward_viewer), 0, 1e-12);
    for (Vec3 v : {screen_right, screen_up, toward_viewer}) EXPECT_NEAR(glm::length(v), 1, 1e-12);
    // A step along the view line keeps the screen position.
    const Vec3 a = ground_frame(3, 4, 5);
    const Vec3 b = a + toward_viewer * 7.0;
    EXPECT_NEAR(b.x - b.y, 3, 1e-9);
    EXPECT_NEAR((b.x + b.y) / 2 - b.z, 4, 1e-9);
    // Screen right raises screen x; screen up lowers screen y.
    EXPECT_GT(screen_right.x - screen_right.y, 0);
    EXPECT_LT((screen_up.x + screen_up.y) / 2 - screen_up.z, 0);
    const Vec3 t = to_screen_tangent({0, 0, 1});
    EXPECT_NEAR(t.x, 0, 1e-12);
    EXPECT_GT(t.y, 0.8);
    EXPECT_NEAR(glm::length(from_screen_tangent(t) - Vec3{0, 0, 1}), 0, 1e-12);
}

// Heights worked out by hand: flat ground faces up; the plane X = 20, a
// wall facing +X, shows at h = 20 - y - x/2; the plane Y = -20, facing +Y,
// at h = -20 - y + x/2 (ground_frame: X = y + h + x/2, Y = y + h - x/2).
TEST(SpriteShading, normalsFromHeightsAreThoseOfPlanesWorkedOutByHand) {
    const int w = 16, h = 12;
    Mask shown(Rect{0, 0, w, h});
    std::fill(shown.bits.begin(), shown.bits.end(), 1);
    std::vector<float> flat(std::size_t(w) * h, 0.f), wall_x(flat.size()), wall_y(flat.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            wall_x[std::size_t(y) * w + x] = float(20 - (y + 0.5) - (x + 0.5) / 2);
            wall_y[std::size_t(y) * w + x] = float(-20 - (y + 0.5) + (x + 0.5) / 2 + 40);  // any constant: Y = 20
        }
    const auto n_flat = normals_from_heights(shown, flat), n_x = normals_from_heights(shown, wall_x),
               n_y = normals_from_heights(shown, wall_y);
    for (std::size_t i = 0; i < flat.size(); ++i) {  // every pixel, the edges' one-sided ones included
        EXPECT_LT(angle_deg(n_flat[i], {0, 0, 1}), 1e-6);
        EXPECT_LT(angle_deg(n_x[i], {1, 0, 0}), 1e-6);
        EXPECT_LT(angle_deg(n_y[i], {0, 1, 0}), 1e-6);
    }
    // A pixel the sprite does not show has no normal; a lone pixel, no slope
    // either way, faces up.
    Mask lone(Rect{0, 0, 3, 3});
    lone.set(1, 1);
    const auto n_lone = normals_from_heights(lone, std::vector<float>(9, 5.f));
    EXPECT_EQ(glm::length(n_lone[0]), 0);
    EXPECT_LT(angle_deg(n_lone[4], {0, 0, 1}), 1e-6);
    // The edge between two objects is not a slope: a step of 30 px between
    // columns leaves both sides' normals those of their own planes.
    std::vector<float> step(flat.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) step[std::size_t(y) * w + x] = x < w / 2 ? 0.f : 30.f;
    const auto n_step = normals_from_heights(shown, step);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) EXPECT_LT(angle_deg(n_step[std::size_t(y) * w + x], {0, 0, 1}), 1e-6) << x << "," << y;
}

// Lambert's cosine, and the blend with the flat light.
TEST(SpriteShading, aLitPixelTakesLambertsCosineBlendedByTheStrength) {
    Params p;
    p.sprite_shading = SpriteShading::solids;
    // Pixel (0, 0) shows a point 10 px up; the light 10 px up over screen
    // pixel (cx, cy) far along +X of it faces a +X normal head on.
    const Vec3 point = ground_frame(0.5, 0.5, 10);
    const std::int64_t cx = 200, cy = 100;  // its foot (200.75, 0.25, 0): 190 px along +X of the point
    const Vec3 light = ground_frame(cx + 0.5, cy + 0.5, 0) + Vec3{0, 0, 10};
    const Vec3 to_light = glm::normalize(light - point);
    const double cos_x = glm::dot(to_light, Vec3{1, 0, 0});
    ASSERT_GT(cos_x, 0.5);
    for (double s : {1.0, 0.5, 0.0}) {
        p.shading_strength = s;
        LightMask facing = mask_at(cx, cy, 200), away = mask_at(cx, cy, 200);
        shade_sprites(facing, one_pixel({1, 0, 0}, 10), 10, p);
        shade_sprites(away, one_pixel({-1, 0, 0}, 10), 10, p);
        EXPECT_NEAR(facing.value[0], 200 * ((1 - s) + s * cos_x), 1.01) << s;
        EXPECT_NEAR(away.value[0], 200 * (1 - s), 0.51) << s;
    }
    // The same pixel and light 2^30 pixels out (the frame's rectangles are
    // ints, an endless world's windows far out): the same byte.
    p.shading_strength = 1;
    for (const Vec3 n : {Vec3{1, 0, 0}, glm::normalize(Vec3{1, 1, 1}), glm::normalize(Vec3{0.3, -0.5, 0.8})}) {
        LightMask near = mask_at(cx, cy, 200), far = mask_at(cx + (1 << 30), cy + (1 << 30), 200);
        ShadingMap far_map = one_pixel(n, 10);
        far_map.rect = {1 << 30, 1 << 30, 1, 1};
        far.clip = far_map.rect;
        shade_sprites(near, one_pixel(n, 10), 10, p);
        shade_sprites(far, far_map, 10, p);
        EXPECT_EQ(far.value[0], near.value[0]);
        EXPECT_GT(near.value[0], 0);
    }
    // The ground is never shaded; nor is anything with sprite_shading none.
    p.shading_strength = 1;
    ShadingMap ground = one_pixel({0, 0, 0}, 0);
    LightMask g = mask_at(cx, cy, 200);
    shade_sprites(g, ground, 10, p);
    EXPECT_EQ(g.value[0], 200);
    p.sprite_shading = SpriteShading::none;
    LightMask a = mask_at(cx, cy, 200);
    shade_sprites(a, one_pixel({-1, 0, 0}, 10), 10, p);
    EXPECT_EQ(a.value[0], 200);
}

// shade_sprites takes each row in vectors (the AVX2 build) or pixel by
// pixel (the baseline): both give its oracle's bytes, on a frame's own
// shading map and traced masks (ground, sprites, dark and lit, the map's
// edge), at several strengths and light heights.
TEST(SpriteShading, theShadingsBuildsGiveItsOraclesBytes) {
    test::CentredLight scene = test::centred_light(10, 40, 30);
    Scene s = scene.scene;
    s.params.sprite_shading = SpriteShading::solids;
    const Rect b = scene.world.placed.bounds;
    s.lights.push_back(Light{b.x + b.w / 4.0 + 0.5, b.y + b.h / 3.0 + 0.5});
    s.lights.push_back(Light{double(b.x + b.w - 3), double(b.y + 2)});  // its area past the map's corner
    FrameState st;
    render_frame(st, scene.world, s, Camera{}, 0);
    ASSERT_FALSE(st.shading.empty());
    int compared = 0;
    long shaded = 0;
    for (const Light& l : s.lights)
        for (double strength : {1.0, 0.6})
            for (double height : {6.0, 40.0, 300.0}) {
                Params p = s.params;
                p.shading_strength = strength;
                const std::int64_t cx = std::int64_t(std::floor(l.x)), cy = std::int64_t(std::floor(l.y));
                const LightMask traced = trace_light_solids(st.occluders, cx, cy, 90, 70, height, p,
                                                            Rect{int(cx) - 90, int(cy) - 70, 181, 141});
                LightMask want = traced;
                shade_sprites_reference(want, st.shading, height, p);
                for (std::size_t i = 0; i < want.value.size(); ++i) shaded += want.value[i] != traced.value[i];
                for (const bool wide : test::both_widths()) {
                    set_wide_kernels(wide);
                    LightMask got = traced;
                    shade_sprites(got, st.shading, height, p);
                    set_wide_kernels(true);
                    EXPECT_EQ(got.value, want.value) << (wide ? "AVX2" : "baseline") << " strength " << strength << " height " << height;
                    ++compared;
                }
            }
    EXPECT_GE(compared, 18);
    EXPECT_GT(shaded, 10000) << "the shading must change many pixels";
}

// On the default and town tilesets, whose sprites were drawn from the
// shapes their manifests give: the estimated solids' normals lie nearer the
// shapes' than the brightness gradient's do, on each tileset as a whole by
// a quarter at least. (Sprite by sprite too, but for the town's grove,
// where the estimate finds half the trees: docs/beyond.md.)
TEST(SpriteShading, theSolidsNormalsLieNearerTheShapesThanTheLuminancesOnEveryTilesetWithShapes) {
    const Params p;
    for (const char* name : {"default", "town"}) {
        const Tileset ts = load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/" + name + "/tileset.json");
        double sum_solids = 0, sum_luminance = 0;
        int sprites = 0;
        for (const Sprite& s : ts.sprites) {
            if (s.kind != SpriteKind::overlay) continue;
            const SpriteNormals truth = sprite_normals(ts, s, p, SpriteShading::shapes);
            const double solids = mean_angle(sprite_normals(ts, s, p, SpriteShading::solids), truth);
            const double luminance = mean_angle(sprite_normals(ts, s, p, SpriteShading::luminance), truth);
            std::printf("%-8s %-14s mean angle to the shapes' normals: solids %5.1f deg, luminance %5.1f deg\n", name,
                        s.name.c_str(), solids, luminance);
            if (s.name != "grove") {
                EXPECT_LT(solids, luminance) << name << " " << s.name;
            }
            sum_solids += solids, sum_luminance += luminance, ++sprites;
        }
        ASSERT_GT(sprites, 3) << name;
        std::printf("%-8s mean over %d overlays: solids %.1f deg, luminance %.1f deg\n", name, sprites,
                    sum_solids / sprites, sum_luminance / sprites);
        EXPECT_LT(sum_solids / sprites, 0.75 * sum_luminance / sprites) << name;
    }
}

// shapes needs a shape or a height map on every overlay, and says which lacks one.
TEST(SpriteShading, shapesShadingNamesTheSpriteWithoutAShape) {
    const Tileset ts = test::foreign_tileset();
    Params p;
    bool refused = false;
    for (const Sprite& s : ts.sprites) {
        if (s.kind != SpriteKind::overlay || !s.shape.empty() || !s.height.empty()) continue;
        const std::string e = test::error_of([&] { sprite_normals(ts, s, p, SpriteShading::shapes); });
        EXPECT_NE(e.find("\"" + s.name + "\""), std::string::npos) << e;
        EXPECT_NE(e.find("sprite_shading shapes"), std::string::npos) << e;
        refused = true;
    }
    EXPECT_TRUE(refused) << "the foreign tileset has an overlay with no shape";
}

// Whole frames of a seeded map: shading changes sprite pixels alone, never
// brightens one, darkens those turned from the light, and at strength 0 is
// the flat light's bytes; in shadow mode what a sprite pixel lacks becomes
// shadow; a state that switches the shading gives a fresh state's bytes.
TEST(SpriteShading, aFrameShadesItsSpritePixelsAloneAndStrengthZeroIsTheFlatLight) {
    test::CentredLight scene = test::centred_light(10, 40, 30);
    Scene& s = scene.scene;
    const World& w = scene.world;
    const Light& lamp = s.lights[0];
    auto traced = [&](const Params& p, FrameState* reuse = nullptr) {
        FrameState fresh;
        FrameState& st = reuse ? *reuse : fresh;
        Scene sc = s;
        sc.params = p;
        render_frame(st, w, sc, Camera{}, 0);
        return std::make_pair(st.traced, st.shading);
    };
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat}) {
        Params flat = s.params;
        flat.mode = mode;
        Params zero = flat, full = flat;
        zero.sprite_shading = full.sprite_shading = SpriteShading::solids;
        zero.shading_strength = 0;
        const auto [t_flat, no_map] = traced(flat);
        const auto [t_zero, map0] = traced(zero);
        const auto [t_full, map] = traced(full);
        EXPECT_TRUE(no_map.empty());
        ASSERT_FALSE(map.empty());
        EXPECT_EQ(t_zero.texels, t_flat.texels) << "strength 0, mode " << int(mode);
        ASSERT_EQ(t_full.rect, t_flat.rect);
        const Vec3 light = ground_frame(std::floor(lamp.x) + 0.5, std::floor(lamp.y) + 0.5, 0) + Vec3{0, 0, 40};
        long sprite = 0, darker = 0, away_dark = 0, away = 0, facing = 0, facing_kept = 0;
        for (int y = t_flat.rect.y; y < t_flat.rect.y + t_flat.rect.h; ++y)
            for (int x = t_flat.rect.x; x < t_flat.rect.x + t_flat.rect.w; ++x) {
                const int before = t_flat.value(x, y, 0), after = t_full.value(x, y, 0);
                // Beyond the map (the texture's margin past its edge) nothing is shaded.
                const bool inside = map.rect.contains(x, y);
                const std::size_t i = inside ? std::size_t(y - map.rect.y) * map.rect.w + std::size_t(x - map.rect.x) : 0;
                const std::array<std::int8_t, 3> q = inside ? map.normal[i] : std::array<std::int8_t, 3>{0, 0, 0};
                if (q[0] == 0 && q[1] == 0 && q[2] == 0) {
                    ASSERT_EQ(after, before) << "a ground pixel at " << x << "," << y;
                    continue;
                }
                ++sprite;
                if (mode == Mode::shadow) {  // the shadow grows where the surface turns away
                    ASSERT_GE(after, before) << x << "," << y;
                    darker += after > before;
                    continue;
                }
                ASSERT_LE(after, before) << x << "," << y;
                darker += after < before;
                if (before < 40) continue;
                const double cosine = lambert(glm::normalize(Vec3{double(q[0]), double(q[1]), double(q[2])}),
                                              ground_frame(x + 0.5, y + 0.5, map.height[i]), light);
                if (cosine == 0) ++away, away_dark += after == 0;
                if (cosine > 0.7) ++facing, facing_kept += after >= 0.7 * before - 1;
            }
        std::printf("mode %d: %ld sprite pixels, %ld darker; turned away %ld (dark %ld), facing %ld (kept %ld)\n",
                    int(mode), sprite, darker, away, away_dark, facing, facing_kept);
        EXPECT_GT(sprite, 1000);
        EXPECT_GT(darker, sprite / 10) << "pixels changed";
        if (mode == Mode::shadow) continue;
        EXPECT_GT(away, 100);
        EXPECT_EQ(away_dark, away);
        EXPECT_GT(facing, 100);
        EXPECT_EQ(facing_kept, facing);
    }
    // One state through none, solids, luminance and back: each frame a fresh state's bytes.
    FrameState st;
    for (SpriteShading from : {SpriteShading::none, SpriteShading::solids, SpriteShading::luminance, SpriteShading::none}) {
        Params p = s.params;
        p.sprite_shading = from;
        EXPECT_EQ(traced(p, &st).first.texels, traced(p).first.texels) << int(from);
    }
}

// The accuracy page's targets (docs/accuracy.md): with occluders solids,
// at light heights 16, 32 and 64 px, solids shading leaves at most
// max(half of what no shading leaves, 1.2 times what the true shapes'
// normals leave over the true shapes' visibility) of the sprite pixels'
// RMSE against 3d_shaded, and at most three quarters of what the brightness
// gradient's normals leave; on the default, forest and town scenes (the
// page's 8 frames) and a drawn seed (2 frames).
TEST(SpriteShading, solidsShadingHalvesTheSpritesErrorAgainstTheShadedTruth) {
    struct Case {
        std::string name;
        Tileset tileset;
        Scene scene;
        int frames;
    };
    std::vector<Case> cases;
    for (const char* name : {"default", "forest"})
        cases.push_back({name, test::default_tileset(),
                         load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/" + name + ".json"), 8});
    cases.push_back({"town", load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/town/tileset.json"),
                     load_scene(std::string(ISOLUX_ASSETS_DIR) + "/scenes/town.json"), 8});
    Scene drawn;
    drawn.seed = "drawn-shading-7";
    drawn.width = drawn.height = 10;
    drawn.params.area_a = drawn.params.area_b = 160;
    drawn.params.falloff_scale = 8;
    {
        const World w = make_world(test::default_tileset(), drawn);
        const Rect b = w.placed.bounds;
        Pcg32 rng(7);
        for (int i = 0; i < 2; ++i)
            drawn.lights.push_back(Light{double(b.x + 150 + int(rng.below(std::uint32_t(b.w - 300)))) + 0.5,
                                         double(b.y + 100 + int(rng.below(std::uint32_t(b.h - 200)))) + 0.5});
        drawn.camera = {double(b.x), double(b.y), b.w, b.h};
    }
    cases.push_back({drawn.seed, test::default_tileset(), drawn, 2});
    const std::vector<std::string> heights{"16", "32", "64"};
    for (Case& c : cases) {
        const World w = make_world(c.tileset, c.scene);
        SweepOptions o;
        o.frames = c.frames;
        o.repeats = 1;
        o.references = {Reference::three_d_shaded};
        // Solids' visibility under each shading, and the true shapes' own.
        const auto points = run_sweep(w, c.scene,
                                      {{"occluders", {"solids"}},
                                       {"sprite_shading", {"none", "solids", "luminance"}},
                                       {"light_height", heights}},
                                      o);
        const auto floors = run_sweep(w, c.scene,
                                      {{"occluders", {"shapes"}}, {"sprite_shading", {"shapes"}}, {"light_height", heights}}, o);
        for (const std::string& h : heights) {
            auto rmse = [&](const std::vector<SweepPoint>& from, const char* occluders, const char* shading) {
                for (const SweepPoint& pt : from)
                    if (pt.values[0] == occluders && pt.values[1] == shading && pt.values[2] == h) return pt.sprite.rmse;
                ADD_FAILURE() << "no point " << occluders << " " << shading << " " << h;
                return 0.0;
            };
            const double none = rmse(points, "solids", "none"), solids = rmse(points, "solids", "solids"),
                         luminance = rmse(points, "solids", "luminance"), floor = rmse(floors, "shapes", "shapes");
            std::printf("%s at %s px: sprites' RMSE against 3d_shaded: none %.2f, solids %.2f, luminance %.2f, "
                        "shapes over shapes %.2f\n",
                        c.name.c_str(), h.c_str(), none, solids, luminance, floor);
            EXPECT_LE(solids, std::max(none / 2, 1.2 * floor)) << c.name << " at " << h;
            EXPECT_LE(solids, 0.75 * luminance) << c.name << " at " << h;
        }
    }
}

// The frame keeps its shading map as it keeps the obstacle map: after pans
// (only the strips that came in remade) and tile edits (only the rebuilt
// part) it holds the bytes of the map built whole over its region.
TEST(SpriteShading, aPannedAndEditedFramesShadingMapIsTheMapBuiltWhole) {
    Scene s;
    s.width = s.height = 12;
    s.params.sprite_shading = SpriteShading::solids;
    World w = make_world(test::default_tileset(), s);
    const Rect b = w.placed.bounds;
    s.lights = {Light{b.x + b.w / 2.0 + 0.5, b.y + b.h / 2.0 + 0.5}};
    s.params.area_a = s.params.area_b = 120;
    FrameState st;
    auto matches_whole = [&](const std::string& what) {
        ASSERT_FALSE(st.shading.empty()) << what;
        NormalsCache fresh;
        const ShadingMap whole = build_shading_map(w, s.params, st.shading.rect, fresh);
        EXPECT_EQ(st.shading.normal, whole.normal) << what;
        EXPECT_EQ(st.shading.height, whole.height) << what;
    };
    Camera cam{double(b.x + 60), double(b.y + 40), 500, 300};
    render_frame(st, w, s, cam, 0);
    matches_whole("first frame");
    for (int f = 1; f <= 4; ++f) {
        cam.x += 170, cam.y += f % 2 ? 90 : -40;  // beyond the region's margin: strips come in
        render_frame(st, w, s, cam, f);
        matches_whole("pan " + std::to_string(f));
    }
    const int floor = test::sprite_index(w.tileset, "grass"), oak = test::sprite_index(w.tileset, "oak"),
              rock = test::sprite_index(w.tileset, "rock");
    ASSERT_GE(floor, 0);
    ASSERT_GE(oak, 0);
    ASSERT_GE(rock, 0);
    for (int k = 0; k < 6; ++k) {
        set_tile(w, 2 + k, 3 + k, floor, k % 2 ? std::vector<int>{oak} : std::vector<int>{rock, oak});
        s.edits = w.edits;
        render_frame(st, w, s, cam, 10 + k);
        matches_whole("edit " + std::to_string(k));
    }
}
