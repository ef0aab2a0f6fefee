// The opacity correction: the ground lines held to the per-sprite rule
// (correct_with_opacity_maps), in both kernels' builds.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "base/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"
#include "isolux/opacity_map.hpp"

using namespace isolux;
using isolux::test::both_widths;
using isolux::test::random_texture;

TEST(FastCorrection, GroundLinesEqualThePerSpriteCorrection) {
    const Tileset ts = test::default_tileset();
    for (const char* kind : {"default", "forest"}) {
        Scene s;
        s.width = s.height = 12;
        World w = make_world(ts, s);
        if (std::string(kind) == "forest") {
            const std::vector<int> trees = w.tileset.find(SpriteKind::overlay, "tree");
            for (std::size_t i = 0; i < w.map.tiles.size(); ++i) {
                Tile& t = w.map.tiles[i];
                t.overlay_count = 2;
                t.overlays[0] = {trees[i % trees.size()], -20, 0};
                t.overlays[1] = {trees[(i + 1) % trees.size()], 20, 4};
            }
            w.placed = place_sprites(w.map, w.tileset);
        }
        // The opacity maps the frame uses, and its obstacle map.
        FrameState st;
        s.lights = {Light{double(w.placed.bounds.x + w.placed.bounds.w / 2), double(w.placed.bounds.y + w.placed.bounds.h / 2)}};
        render_frame(st, w, s, Camera{}, 0);
        ASSERT_FALSE(st.opacity.empty());
        const GroundLines lines = ground_lines(w.placed, st.opacity, w.placed.bounds);
        ASSERT_TRUE(lines.exact);
        Pcg32 rng(8);
        int compared = 0, changed = 0;
        for (Mode mode : {Mode::light, Mode::shadow})
            for (int k = 0; k < 40; ++k) {
                Params p;
                p.mode = mode;
                const int a = 20 + int(rng.below(120)), b = 20 + int(rng.below(120));
                const std::int64_t cx = w.placed.bounds.x + std::int64_t(rng.below(std::uint32_t(w.placed.bounds.w)));
                const std::int64_t cy = w.placed.bounds.y + std::int64_t(rng.below(std::uint32_t(w.placed.bounds.h)));
                Rect clip{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
                if (k % 5 == 0) clip = intersect(clip, {int(cx) - a / 2, int(cy) - b, a, b});  // clipped by a view
                const LightMask traced = trace_light(st.obstacles, cx, cy, a, b, p, clip);
                LightMask want = traced, got = traced;
                correct_with_opacity_maps(want, w.placed, st.opacity);
                for (bool wide : both_widths()) {
                    set_wide_kernels(wide);
                    got = traced;
                    correct_with_ground_lines(got, lines);
                    EXPECT_EQ(got.value, want.value) << kind << " light " << cx << "," << cy << " wide " << wide;
                    EXPECT_EQ(got.reached, want.reached) << kind << " light " << cx << "," << cy << " wide " << wide;
                    // Idempotent (the benchmark corrects the same masks again and again).
                    LightMask again = got;
                    correct_with_ground_lines(again, lines);
                    EXPECT_EQ(again.value, got.value);
                    EXPECT_EQ(again.reached, got.reached);
                }
                set_wide_kernels(true);
                changed += want.value != traced.value;
                ++compared;
            }
        EXPECT_EQ(compared, 80);
        EXPECT_GT(changed, 20) << "the corrections must have done something to compare";
    }
}

namespace {

// A light's mask of random values (and random reached flags in shadow mode):
// a traced mask's values often equal what the correction writes.
LightMask random_mask(Pcg32& rng, std::int64_t cx, std::int64_t cy, int a, int b, double scale, bool shadow) {
    LightMask m;
    m.cx = cx, m.cy = cy, m.a = a, m.b = b;
    m.falloff_scale = scale;
    m.clip = Rect{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
    m.value.resize(std::size_t(m.clip.w) * m.clip.h);
    for (std::uint8_t& v : m.value) v = std::uint8_t(rng.below(256));
    if (shadow) {
        m.reached.resize(m.value.size());
        for (std::uint8_t& v : m.reached) v = std::uint8_t(rng.below(2));
    }
    return m;
}

// The correction of `m` by the ground lines, in both builds, against the
// rule's; returns the rule's.
LightMask both_builds_equal_the_rule(const LightMask& m, const GroundLines& lines, const PlacedMap& placed,
                                     const std::vector<Mask>& opacity) {
    LightMask want = m;
    correct_with_opacity_maps(want, placed, opacity);
    for (bool wide : both_widths()) {
        set_wide_kernels(wide);
        LightMask got = m;
        correct_with_ground_lines(got, lines);
        EXPECT_EQ(got.value, want.value) << "light " << m.cx << "," << m.cy << " width " << m.clip.w << " wide " << wide;
        EXPECT_EQ(got.reached, want.reached) << "light " << m.cx << "," << m.cy << " width " << m.clip.w << " wide " << wide;
    }
    set_wide_kernels(true);
    return want;
}

// Overlays placed by hand (no tileset): sprite 0 a 40x300 column standing
// on its bottom row (its top 299 rows above its ground: too far for the
// byte lines), sprite 1 a 30x60 block whose ground is 50 rows above its
// bottom (pixels below the ground line), both with holes.
struct HandPlaced {
    PlacedMap placed;
    std::vector<Mask> opacity;
    HandPlaced() {
        opacity = {Mask(Rect{0, 0, 40, 300}), Mask(Rect{0, 0, 30, 60})};
        for (Mask& m : opacity)
            for (int y = 0; y < m.height; ++y)
                for (int x = 0; x < m.width; ++x) m.bits[std::size_t(y) * m.width + x] = (x * 7 + y * 3) % 11 != 0;
        Pcg32 rng(5);
        for (int i = 0; i < 24; ++i) {
            SpriteInstance in;
            in.sprite = i % 2;
            in.w = opacity[std::size_t(in.sprite)].width, in.h = opacity[std::size_t(in.sprite)].height;
            in.x = int(rng.below(400)), in.y = int(rng.below(400));
            in.ground_x = in.x + in.w / 2;
            in.ground_y = in.sprite == 0 ? in.y + in.h - 1 : in.y + 9;
            in.layer = 1;
            placed.instances.push_back(in);
        }
        // Draw order: overlays by their ground point, as place_sprites orders them.
        std::stable_sort(placed.instances.begin(), placed.instances.end(),
                         [](const SpriteInstance& a, const SpriteInstance& b) { return a.ground_y < b.ground_y; });
        placed.first_overlay = 0;
        finish_placed(placed);
    }
};

}  // namespace

TEST(FastCorrection, RowsTooTallForAByteReadTheWideLinesAndEqualTheRule) {
    const HandPlaced h;
    const GroundLines lines = ground_lines(h.placed, h.opacity, h.placed.bounds);
    ASSERT_TRUE(lines.exact);
    int wide_rows = 0, byte_rows = 0;
    for (std::uint32_t n : lines.wide) ++(n ? wide_rows : byte_rows);
    EXPECT_GT(wide_rows, 50) << "the test must reach the 16-bit rows";
    EXPECT_GT(byte_rows, 50) << "and the byte rows";
    Pcg32 rng(6);
    int changed = 0;
    for (int k = 0; k < 60; ++k) {
        const std::int64_t cx = h.placed.bounds.x + std::int64_t(rng.below(std::uint32_t(h.placed.bounds.w)));
        const std::int64_t cy = h.placed.bounds.y + std::int64_t(rng.below(std::uint32_t(h.placed.bounds.h)));
        const int a = 20 + int(rng.below(150)), b = 20 + int(rng.below(150));
        const LightMask m = random_mask(rng, cx, cy, a, b, k % 3 ? 1.0 : 2.5, k % 2);
        const LightMask want = both_builds_equal_the_rule(m, lines, h.placed, h.opacity);
        changed += want.value != m.value;
    }
    EXPECT_GT(changed, 30);
}

TEST(FastCorrection, EveryRowWidthEqualsTheRule) {
    // Rows narrower than a vector, a vector and a pixel, several vectors and
    // a tail: each width's own path through the byte rows.
    const Tileset ts = test::default_tileset();
    Scene s;
    s.width = s.height = 8;
    const World w = make_world(ts, s);
    FrameState st;
    render_frame(st, w, s, Camera{}, 0);
    const GroundLines lines = ground_lines(w.placed, st.opacity, w.placed.bounds);
    ASSERT_TRUE(lines.exact);
    Pcg32 rng(12);
    int changed = 0, byte_rows = 0;
    for (int a = 0; a <= 40; ++a) {
        const std::int64_t cx = w.placed.bounds.x + w.placed.bounds.w / 4 + std::int64_t(rng.below(std::uint32_t(w.placed.bounds.w / 2)));
        const std::int64_t cy = w.placed.bounds.y + w.placed.bounds.h / 4 + std::int64_t(rng.below(std::uint32_t(w.placed.bounds.h / 2)));
        const LightMask m = random_mask(rng, cx, cy, a, 40, 1.0, a % 2);
        for (int y = m.clip.y; y < m.clip.y + m.clip.h; ++y) byte_rows += lines.wide[std::size_t(y - lines.rect.y)] == 0;
        const LightMask want = both_builds_equal_the_rule(m, lines, w.placed, st.opacity);
        changed += want.value != m.value;
    }
    EXPECT_GT(byte_rows, 41 * 81 / 2) << "the byte rows are what this test is for";
    EXPECT_GT(changed, 30);
}

TEST(FastCorrection, MasksClippedAwayFromTheirCentreEqualTheRule) {
    // The falloff by column is the distance table read outwards from the
    // centre's column: here the mask's clip (a view's edge) leaves that
    // column to its left, to its right, or the centre's row above or below,
    // in a forest where every column of the clip has sprites.
    const Tileset ts = test::default_tileset();
    Scene s;
    s.width = s.height = 10;
    World w = make_world(ts, s);
    const std::vector<int> trees = w.tileset.find(SpriteKind::overlay, "tree");
    for (std::size_t i = 0; i < w.map.tiles.size(); ++i) {
        w.map.tiles[i].overlay_count = 1;
        w.map.tiles[i].overlays[0] = {trees[i % trees.size()], 0, 0};
    }
    w.placed = place_sprites(w.map, w.tileset);
    FrameState st;
    render_frame(st, w, s, Camera{}, 0);
    const GroundLines lines = ground_lines(w.placed, st.opacity, w.placed.bounds);
    ASSERT_TRUE(lines.exact);
    const Rect b = w.placed.bounds;
    Pcg32 rng(21);
    int changed = 0;
    for (int k = 0; k < 32; ++k) {
        const int a = 30 + int(rng.below(60)), h = 30 + int(rng.below(60));
        const std::int64_t cx = b.x + b.w / 3 + std::int64_t(rng.below(std::uint32_t(b.w / 3)));
        const std::int64_t cy = b.y + b.h / 3 + std::int64_t(rng.below(std::uint32_t(b.h / 3)));
        LightMask m = random_mask(rng, cx, cy, a, h, k % 3 ? 1.0 : 2.5, k % 2);
        // The clip starts or ends 1 to a/2 pixels past the centre.
        const int d = 1 + int(rng.below(std::uint32_t(std::min(a, h) / 2)));
        const Rect area = m.clip;
        Rect keep = area;
        switch (k % 4) {
            case 0: keep = {int(cx) + d, area.y, area.w, area.h}; break;            // centre left of the clip
            case 1: keep = {area.x, area.y, int(cx) - d - area.x + 1, area.h}; break;  // right of it
            case 2: keep = {area.x, int(cy) + d, area.w, area.h}; break;            // above it
            case 3: keep = {area.x, area.y, area.w, int(cy) - d - area.y + 1}; break;  // below it
        }
        m.clip = intersect(area, keep);
        ASSERT_FALSE(m.clip.contains(int(cx), int(cy)));
        std::vector<std::uint8_t> value, reached;
        for (int y = m.clip.y; y < m.clip.y + m.clip.h; ++y)
            for (int x = m.clip.x; x < m.clip.x + m.clip.w; ++x) {
                const std::size_t at = std::size_t(y - area.y) * area.w + std::size_t(x - area.x);
                value.push_back(m.value[at]);
                if (!m.reached.empty()) reached.push_back(m.reached[at]);
            }
        m.value = value, m.reached = reached;
        const LightMask want = both_builds_equal_the_rule(m, lines, w.placed, st.opacity);
        changed += want.value != m.value;
    }
    EXPECT_EQ(changed, 32) << "every clip has sprite pixels to correct";
}

TEST(FastCorrection, ARepaintEqualsFreshLines) {
    HandPlaced h;
    const Rect region{h.placed.bounds.x - 20, h.placed.bounds.y - 20, h.placed.bounds.w + 40, h.placed.bounds.h + 40};
    GroundLines lines = ground_lines(h.placed, h.opacity, region);
    Pcg32 rng(9);
    for (int k = 0; k < 12; ++k) {
        // Move one sprite (a tall one on even steps: its rows change between byte and wide).
        SpriteInstance& in = h.placed.instances[std::size_t(2 * (k % 12) + (k % 2))];
        const Rect before{in.x, in.y, in.w, in.h};
        const int dx = int(rng.below(61)) - 30, dy = int(rng.below(61)) - 30;
        in.x += dx, in.y += dy, in.ground_x += dx, in.ground_y += dy;
        finish_placed(h.placed);  // the grid again (draw order may differ now: both are painted the same way)
        repaint_ground_lines(lines, h.placed, h.opacity, bounding(before, Rect{in.x, in.y, in.w, in.h}));
        const GroundLines fresh = ground_lines(h.placed, h.opacity, region);
        ASSERT_EQ(lines.below, fresh.below) << "step " << k;
        ASSERT_EQ(lines.below8, fresh.below8) << "step " << k;
        ASSERT_EQ(lines.wide, fresh.wide) << "step " << k;
    }
}

TEST(OpacityCorrection, addsSpritesAboveTheCentreAndSubtractsThoseBelow) {
    // Two 3x3 opaque sprites: one standing above the light's centre (its
    // ground y < the centre's), one below it.
    Tileset ts;
    Sprite s;
    s.kind = SpriteKind::overlay;
    s.image = test::sprite_from({"###", "###", "###"});
    s.anchor_x = 1;
    s.anchor_y = 2;
    ts.sprites.push_back(s);
    PlacedMap placed;
    placed.first_overlay = 0;
    placed.instances.push_back({0, -6, -6, -5, -4, 0, 3, 3});  // ground y -4 < 0: above
    placed.instances.push_back({0, 2, 1, 3, 3, 1, 3, 3});      // ground y 3 >= 0: below
    std::vector<Mask> opacity = {opacity_map(ts.sprites[0].image, 0.5)};
    const Rect area{-8, -8, 17, 17};  // a light of half-extents 8 at the origin
    Mask wall(area);
    for (int x = -8; x <= 8; ++x) wall.set(x, -2);  // shadows everything above row -2
    LightMask m = trace_light(wall, 0, 0, 8, 8, Params{}, area);
    auto lit = [&](int x, int y) { return m.value[(y + 8) * 17 + (x + 8)] > 0 ? 1 : 0; };
    ASSERT_EQ(lit(-5, -5), 0);
    ASSERT_EQ(lit(3, 2), 1);
    EXPECT_EQ(correct_with_opacity_maps(m, placed, opacity), 2);
    for (int y = -6; y <= -4; ++y)
        for (int x = -6; x <= -4; ++x) EXPECT_EQ(lit(x, y), 1) << "added " << x << "," << y;
    for (int y = 1; y <= 3; ++y)
        for (int x = 2; x <= 4; ++x) EXPECT_EQ(lit(x, y), 0) << "subtracted " << x << "," << y;
    EXPECT_EQ(lit(0, 1), 1);    // untouched floor stays lit
    EXPECT_EQ(lit(0, -5), 0);   // untouched shadow stays dark
    // The added pixels get the light's intensity at their distance.
    LightTexture tex(area);
    accumulate_light(tex, m, Light{}, Params{});
    EXPECT_EQ(tex.at(-5, -5)[0], 255 / 6);
}
