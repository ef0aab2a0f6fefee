// The fast CPU stages (issue: the whole frame near its memory floor) held to
// the plainest statements of their rules, byte for byte: box_blur against
// box_blur_reference, composite against composite_reference, the ground-line
// opacity correction against the per-sprite one, and a frame that redoes only
// what changed against one built from nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <chrono>
#include <string>
#include <thread>

#include "isolux/accuracy.hpp"
#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/cpu.hpp"
#include "isolux/frame.hpp"
#include "isolux/hash.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/opacity_correction.hpp"
#include "test_util.hpp"

using namespace isolux;

namespace {

// Texels mostly dark with bright patches and full-white runs: the sums reach
// their maximum and every rounding case appears.
LightTexture random_texture(Rect r, std::uint64_t seed) {
    LightTexture t(r);
    Pcg32 rng(seed);
    for (std::size_t i = 0; i < t.texels.size(); ++i) {
        const std::uint32_t k = rng.below(10);
        t.texels[i] = k < 4 ? 0 : k < 6 ? 255 : std::uint8_t(rng.below(256));
    }
    return t;
}

// The kernels' builds to hold to the same bytes (isolux/cpu.hpp): the
// baseline, and AVX2 when this CPU has it (said once, so a run without it
// is seen).
std::vector<bool> both_widths() {
    static const bool has_avx2 = [] {
        set_wide_kernels(true);
        const bool on = wide_kernels();
        if (!on) std::printf("note: this CPU has no AVX2: only the baseline kernels are tested\n");
        return on;
    }();
    return has_avx2 ? std::vector<bool>{false, true} : std::vector<bool>{false};
}

// box_blur of t in both kernels' builds must equal the oracle's bytes
// (returned); `what` names the case in a failure.
LightTexture expect_blur_is_reference(const LightTexture& t, int radius, const std::string& what) {
    LightTexture want = box_blur_reference(t, radius);
    for (bool wide : both_widths()) {
        set_wide_kernels(wide);
        EXPECT_EQ(box_blur(t, radius).texels, want.texels) << what << " r " << radius << " wide " << wide;
    }
    set_wide_kernels(true);
    return want;
}

}  // namespace

TEST(FastBlur, EqualsTheReferenceForEveryRadiusAndSize) {
    const Rect sizes[] = {{0, 0, 1, 1}, {-3, 5, 2, 7}, {10, -4, 17, 5}, {0, 0, 64, 40}, {-100, -50, 33, 29}};
    int checked = 0;
    for (const Rect& r : sizes)
        for (int radius : {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 20, 62, 63, 100}) {
            if (radius > 20 && r.w * r.h > 1200) continue;  // the reference is O(r^2) per texel
            const LightTexture t = random_texture(r, std::uint64_t(r.w * 131 + radius));
            expect_blur_is_reference(t, radius, std::to_string(r.w) + "x" + std::to_string(r.h));
            ++checked;
        }
    EXPECT_GE(checked, 50);
}

TEST(FastBlur, WideRowsOfExtremeTexelsEqualTheReference) {
    // Rows wide enough for the AVX2 interior's 32-value steps and a tail,
    // of 0s and 255s in runs (the largest window sums, and every quotient
    // from 0 to 255 at the runs' edges).
    for (const Rect r : {Rect{3, -2, 300, 24}, Rect{0, 0, 97, 20}}) {
        LightTexture t(r);
        for (int y = 0; y < r.h; ++y)
            for (int x = 0; x < r.w; ++x)
                for (int c = 0; c < 3; ++c)
                    t.texels[(std::size_t(y) * r.w + x) * 3 + c] = (x / 16 + y / 8 + c) % 3 ? 255 : 0;
        for (int radius = 1; radius <= 8; ++radius) {
            const LightTexture want = expect_blur_is_reference(t, radius, "width " + std::to_string(r.w));
            int top = 0;
            for (std::uint8_t v : want.texels) top += v == 255;
            EXPECT_GT(top, 0) << "some windows must be all 255";
        }
    }
}

TEST(FastBlur, ARegionWritesOnlyItsTexelsAndTheirFullValues) {
    const Rect r{-20, 7, 61, 45};
    const LightTexture t = random_texture(r, 9);
    for (int radius : {1, 2, 5, 9}) {
        const LightTexture whole = box_blur_reference(t, radius);
        Pcg32 rng{std::uint64_t(radius)};
        for (int k = 0; k < 12; ++k) {
            const Rect region{r.x - 5 + int(rng.below(50)), r.y - 5 + int(rng.below(40)), 1 + int(rng.below(40)),
                              1 + int(rng.below(30))};
            for (bool wide : both_widths()) {
                set_wide_kernels(wide);
                LightTexture out(r);
                std::fill(out.texels.begin(), out.texels.end(), std::uint8_t(77));
                box_blur_into(t, radius, region, out);
                for (int y = r.y; y < r.y + r.h; ++y)
                    for (int x = r.x; x < r.x + r.w; ++x)
                        for (int c = 0; c < 3; ++c) {
                            const std::uint8_t want = region.contains(x, y) ? whole.at(x, y)[c] : 77;
                            ASSERT_EQ(out.at(x, y)[c], want) << x << "," << y << " r " << radius << " wide " << wide;
                        }
            }
            set_wide_kernels(true);
        }
    }
}

TEST(FastBlur, EveryRowWidthAndEdgeEqualsTheReference) {
    // The AVX2 rows at every radius of the fused pass: the first values
    // (16, or 32 where an RGB window reaches past 16 bytes), the 32-value
    // steps, the 16-value tail whose last step overlaps values done (every
    // width mod 32), the clamped bytes at either texture edge or neither, in
    // both layouts, over dark rows (2R + 4 of them, longer than the window)
    // and lit patches, into output holding other values.
    int checked = 0;
    for (int channels : {1, 3})
        for (int tex_w = 40; tex_w <= 120; tex_w += channels == 1 ? 1 : 7)
            for (int radius = 1; radius <= 7; ++radius) {
                const Rect r{-3, 2, tex_w, 40};
                LightTexture t(r, channels);
                Pcg32 rng(std::uint64_t(tex_w * 3 + channels));
                for (std::size_t i = 0; i < t.texels.size(); ++i) {
                    const std::size_t x = (i / std::size_t(channels)) % std::size_t(tex_w);
                    const std::size_t y = i / std::size_t(channels * tex_w);
                    t.texels[i] = (x / 11) % 3 || (y / std::size_t(radius + 2)) % 3 ? 0 : std::uint8_t(1 + rng.below(255));
                }
                const LightTexture want = box_blur_reference(t, radius);
                for (const Rect z : {r, Rect{r.x + 4, r.y + 1, tex_w - 4, 37}, Rect{r.x, r.y, tex_w - 5, 40},
                                     Rect{r.x + 5, r.y + 3, tex_w - 9, 29}})
                    for (bool wide : both_widths()) {
                        set_wide_kernels(wide);
                        LightTexture out(r, channels);
                        std::fill(out.texels.begin(), out.texels.end(), std::uint8_t(77));
                        box_blur_into(t, radius, z, out);
                        for (int y = r.y; y < r.y + r.h; ++y)
                            for (int x = r.x; x < r.x + r.w; ++x)
                                for (int c = 0; c < channels; ++c)
                                    ASSERT_EQ(out.value(x, y, c), z.contains(x, y) ? want.value(x, y, c) : 77)
                                        << x << "," << y << " c " << c << " of " << channels << ", width " << tex_w
                                        << " region " << z.x << "," << z.w << " r " << radius << " wide " << wide;
                    }
                set_wide_kernels(true);
                ++checked;
            }
    EXPECT_EQ(checked, 7 * (81 + 12));
}

TEST(FastBlur, DarkStretchesLongerThanItsCountEqualTheReference) {
    // The AVX2 rows count dark rows per step in a byte, which starts again
    // at 0 after 255: 300 dark rows between lit ones, at the smallest and
    // largest radius of the fused pass, in both layouts.
    for (int channels : {1, 3}) {
        const Rect r{0, 0, 90, 340};
        LightTexture t(r, channels);
        Pcg32 rng{std::uint64_t(channels)};
        for (int y = 0; y < r.h; ++y)
            if (y < 8 || (y >= 308 && y < 316) || y >= 330)
                for (int i = 0; i < r.w * channels; ++i)
                    t.texels[std::size_t(y) * std::size_t(r.w * channels) + std::size_t(i)] = std::uint8_t(rng.below(256));
        for (int radius : {1, 7}) expect_blur_is_reference(t, radius, std::to_string(channels) + " channels");
    }
}

TEST(FastBlur, SparseLitBytesEqualTheReference) {
    // Single lit bytes scattered over dark rows: a dark step (or a run of
    // them) must see a lit byte anywhere in its window, including the middle
    // of an RGB window wider than two 32-byte loads.
    for (int channels : {1, 3})
        for (int radius = 1; radius <= 8; ++radius) {
            // Sparse enough that most steps go dark (a step's window holds
            // up to 74 x 15 bytes), dense enough for lit bytes in every part.
            const Rect r{-7, 4, 230, 200};
            LightTexture t(r, channels);
            Pcg32 rng{std::uint64_t(radius * 7 + channels)};
            for (std::uint8_t& v : t.texels) v = rng.below(2000) == 0 ? std::uint8_t(1 + rng.below(255)) : 0;
            expect_blur_is_reference(t, radius, std::to_string(channels) + " channels");
        }
}

TEST(FastComposite, EqualsTheReferenceInEveryModeAndClarity) {
    const Rect view{-7, 3, 97, 61};
    Image colour(view.w, view.h);
    Pcg32 rng(4);
    for (std::uint8_t& v : colour.rgba) v = std::uint8_t(rng.below(256));
    for (int i = 0; i < view.w * view.h; i += 5) colour.rgba[std::size_t(i) * 4 + 3] = 0;  // some transparent
    // A light texture covering part of the view only: the rest reads unlit.
    const LightTexture light = random_texture({view.x + 20, view.y - 10, 60, 50}, 5);
    int configs = 0;
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (LightMix mix : {LightMix::luminance, LightMix::surface})
            for (bool dark : {false, true})
                for (double ac : {0.0, 0.16, 0.4, 0.5, 0.77, 1.0}) {
                    Params p;
                    p.mode = mode;
                    p.light_mix = mix;
                    p.dark_unlit = dark;
                    p.ambient_clarity = ac;
                    const Image want = composite_reference(colour, view, light, p);
                    for (bool wide : both_widths()) {
                        set_wide_kernels(wide);
                        EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba)
                            << to_string(mode) << " mix " << int(mix) << " dark " << dark << " ac " << ac << " wide " << wide;
                    }
                    set_wide_kernels(true);
                    ++configs;
                }
    EXPECT_EQ(configs, 72);
}

TEST(FastComposite, EveryColourAndLightPairAtTheDefaults) {
    // All 256 x 256 (colour, light) values in each channel, with the other
    // channels varied: every rounding boundary of the default settings.
    const Rect view{0, 0, 256, 256};
    Image colour(256, 256);
    LightTexture light(view);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            std::uint8_t* c = colour.at(x, y);
            c[0] = std::uint8_t(x), c[1] = std::uint8_t(255 - x), c[2] = std::uint8_t((x * 7 + y) & 255), c[3] = 255;
            std::uint8_t* l = &light.texels[(std::size_t(y) * 256 + x) * 3];
            l[0] = std::uint8_t(y), l[1] = std::uint8_t((y * 3) & 255), l[2] = std::uint8_t(255 - y);
        }
    for (double ac : {0.4, 0.25, 0.9}) {
        Params p;
        p.ambient_clarity = ac;
        const Image want = composite_reference(colour, view, light, p);
        for (bool wide : both_widths()) {
            set_wide_kernels(wide);
            EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba) << ac << " wide " << wide;
        }
        set_wide_kernels(true);
    }
    // And every mode, light mix and dark-unlit at the extreme clarities (0:
    // the light term ten times the colour's) and one between.
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (LightMix mix : {LightMix::luminance, LightMix::surface})
            for (bool dark : {false, true})
                for (double ac : {0.0, 0.6, 1.0}) {
                    Params p;
                    p.mode = mode;
                    p.light_mix = mix;
                    p.dark_unlit = dark;
                    p.ambient_clarity = ac;
                    const Image want = composite_reference(colour, view, light, p);
                    for (bool wide : both_widths()) {
                        set_wide_kernels(wide);
                        EXPECT_EQ(composite(colour, view, light, p).rgba, want.rgba)
                            << to_string(mode) << " mix " << int(mix) << " dark " << dark << " ac " << ac << " wide " << wide;
                    }
                    set_wide_kernels(true);
                }
}

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

namespace {

Scene moving_scene(const World& w, int lights) {
    Scene s;
    s.params.area_a = s.params.area_b = 90;
    s.params.blur_radius = 2;
    Pcg32 rng(21);
    const Rect b = w.placed.bounds;
    for (int i = 0; i < lights; ++i)
        s.lights.push_back(Light{b.x + double(rng.below(std::uint32_t(b.w))) + 0.5, b.y + double(rng.below(std::uint32_t(b.h))) + 0.5});
    return s;
}

}  // namespace

TEST(OnlyWhatChanged, OneMovedLightRedoesItsAreasAndEqualsAFreshFrame) {
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    for (int threads : {1, 2}) {
        Scene s = moving_scene(w, 12);
        const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
        for (int i = 0; i < 3; ++i) s.lights[std::size_t(i)] = Light{cam.x + 150 + 200.0 * i, cam.y + 100 + 90.0 * i};
        FrameState st;
        st.options.threads = threads;
        render_frame(st, w, s, cam, 0);
        for (long f = 1; f <= 6; ++f) {
            s.lights[std::size_t(f % 3)].x += 7;  // one light moves
            const FrameReport r = render_frame(st, w, s, cam, f);
            FrameState fresh;
            render_frame(fresh, w, s, cam, 0);
            ASSERT_EQ(st.traced.texels, fresh.traced.texels) << "frame " << f;
            ASSERT_EQ(st.light.texels, fresh.light.texels) << "frame " << f;
            ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f << ", " << threads << " threads";
            EXPECT_EQ(r.lights_traced, 1);
            // The blur and composite touched a part, not the whole texture or view.
            const Rect blurred = r.touched[int(Stage::blur)], composited = r.touched[int(Stage::composite)];
            EXPECT_FALSE(blurred.empty());
            EXPECT_LT(double(blurred.w) * blurred.h, 0.8 * st.traced.rect.w * st.traced.rect.h);
            EXPECT_LT(double(composited.w) * composited.h, 0.8 * cam.width * cam.height);
            EXPECT_EQ(intersect(composited, r.touched[int(Stage::blur)]), composited);
        }
        // Nothing moved: nothing redone.
        const FrameReport still = render_frame(st, w, s, cam, 7);
        EXPECT_TRUE(still.touched[int(Stage::blur)].empty());
        EXPECT_TRUE(still.touched[int(Stage::composite)].empty());
    }
}

TEST(OnlyWhatChanged, TheLightsOrderByCostChangesNoByteNorRectangle) {
    // Lights are traced costliest first by what each took the frame before
    // (timings: they differ from run to run). Two states whose recorded
    // costs order the lights opposite ways draw the same frames and report
    // the same rectangles, and every traced light has its cost recorded.
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 10);
    const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
    for (std::size_t i = 0; i < s.lights.size(); ++i) s.lights[i] = Light{cam.x + 40 + 65.0 * double(i), cam.y + 40 + 33.0 * double(i)};
    FrameState a, b;
    a.options.threads = b.options.threads = 2;
    render_frame(a, w, s, cam, 0);
    render_frame(b, w, s, cam, 0);
    for (long f = 1; f <= 4; ++f) {
        ASSERT_EQ(a.cache.lights.size(), b.cache.lights.size());
        for (std::size_t i = 0; i < a.cache.lights.size(); ++i) {
            EXPECT_GT(a.cache.lights[i].cost_ms, 0) << "light " << i << " traced without its cost";
            a.cache.lights[i].cost_ms = 1.0 + double(i);
            b.cache.lights[i].cost_ms = 100.0 - double(i);
        }
        for (std::size_t i = 0; i < s.lights.size(); i += 2) s.lights[i].x += 3;  // half the lights move
        const FrameReport ra = render_frame(a, w, s, cam, f), rb = render_frame(b, w, s, cam, f);
        ASSERT_EQ(ra.lights_traced, rb.lights_traced);
        EXPECT_EQ(ra.lights_traced, 5);
        ASSERT_EQ(a.final.rgba, b.final.rgba) << "frame " << f;
        EXPECT_EQ(ra.dirty_parts, rb.dirty_parts) << "frame " << f;
        for (Stage stage : {Stage::trace, Stage::opacity_correction, Stage::blur, Stage::composite})
            EXPECT_EQ(ra.touched_parts[int(stage)], rb.touched_parts[int(stage)]) << "frame " << f << " stage " << int(stage);
    }
}

TEST(OnlyWhatChanged, TheDisjointUnionCoversEachPixelOfThePartsOnce) {
    Pcg32 rng(5);
    for (int round = 0; round < 300; ++round) {
        const int field = 40;
        std::vector<Rect> parts(rng.below(12));
        for (Rect& r : parts)  // some empty, some touching, some nested
            r = {int(rng.below(field)) - 5, int(rng.below(field)) - 5, int(rng.below(20)), int(rng.below(20))};
        std::vector<int> wanted(field * field * 9, 0), got(field * field * 9, 0);  // -field..2 field squared
        auto mark = [&](std::vector<int>& grid, Rect r) {
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) grid.at(std::size_t(y + field) * field * 3 + std::size_t(x + field)) += 1;
        };
        for (const Rect& r : parts) mark(wanted, r);
        for (int& v : wanted) v = v > 0;
        const std::vector<Rect> out = disjoint_union(parts);
        for (const Rect& r : out) {
            ASSERT_FALSE(r.empty());
            mark(got, r);
        }
        ASSERT_EQ(got, wanted) << "round " << round;  // every pixel of the union once, nothing else
        for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LE(out[i - 1].y, out[i].y) << "top to bottom";
    }
    // Runs that stay the same join downward: two stacked equal parts are one.
    EXPECT_EQ(disjoint_union({{0, 0, 10, 5}, {0, 5, 10, 5}}), (std::vector<Rect>{{0, 0, 10, 10}}));
}

TEST(OnlyWhatChanged, AGapJoinsCloseRunsOfABandAndNothingElse) {
    // Runs 6 apart join with a gap of 6 (the pixels between included), not
    // with 5; runs in other bands, and parts farther apart, stay apart.
    const std::vector<Rect> parts = {{0, 0, 10, 4}, {16, 0, 10, 4}, {100, 0, 5, 4}, {0, 10, 5, 2}};
    EXPECT_EQ(disjoint_union(parts, 5), disjoint_union(parts));
    EXPECT_EQ(disjoint_union(parts, 6), (std::vector<Rect>{{0, 0, 26, 4}, {100, 0, 5, 4}, {0, 10, 5, 2}}));
    // Random parts: disjoint, covering the union, and every pixel added lies
    // between two runs of its row at most `gap` apart.
    Pcg32 rng(6);
    for (int round = 0; round < 300; ++round) {
        std::vector<Rect> random(rng.below(10));
        for (Rect& r : random) r = {int(rng.below(60)), int(rng.below(30)), int(rng.below(15)), int(rng.below(15))};
        const int gap = int(rng.below(12));
        std::vector<int> in(100 * 50, 0), got(100 * 50, 0);
        for (const Rect& r : random)
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) in[std::size_t(y) * 100 + std::size_t(x)] = 1;
        for (const Rect& r : disjoint_union(random, gap))
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x) got[std::size_t(y) * 100 + std::size_t(x)] += 1;
        for (int y = 0; y < 50; ++y)
            for (int x = 0; x < 100; ++x) {
                const std::size_t i = std::size_t(y) * 100 + std::size_t(x);
                ASSERT_LE(got[i], 1) << "round " << round << ": pixel twice";
                if (in[i]) {
                    ASSERT_EQ(got[i], 1) << "round " << round << ": pixel of the union left out";
                }
                if (got[i] && !in[i]) {  // added: the union's nearest pixels left and right are at most gap + 1 apart
                    int l = x, r = x;
                    while (l >= 0 && !in[std::size_t(y) * 100 + std::size_t(l)]) --l;
                    while (r < 100 && !in[std::size_t(y) * 100 + std::size_t(r)]) ++r;
                    ASSERT_TRUE(l >= 0 && r < 100 && r - l - 1 <= gap) << "round " << round << " at " << x << "," << y;
                }
            }
    }
}

TEST(OnlyWhatChanged, LightsFarApartAreRedoneApart) {
    // Two lights at opposite corners of the view move: the blur and the
    // composite redo their two areas, not the box spanning the view.
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    for (int threads : {1, 2}) {
        Scene s = moving_scene(w, 2);
        const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 900, 500};
        s.lights[0] = Light{cam.x + 120, cam.y + 110};
        s.lights[1] = Light{cam.x + 780, cam.y + 390};
        FrameState st;
        st.options.threads = threads;
        render_frame(st, w, s, cam, 0);
        for (long f = 1; f <= 4; ++f) {
            for (Light& l : s.lights) l.x += (f % 2) ? 3 : -2;
            const FrameReport r = render_frame(st, w, s, cam, f);
            FrameState fresh;
            fresh.options.threads = threads;
            render_frame(fresh, w, s, cam, 0);
            ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f << ", " << threads << " threads";
            for (Stage stage : {Stage::trace, Stage::blur, Stage::composite}) {
                const std::vector<Rect>& parts = r.touched_parts[int(stage)];
                const Rect box = r.touched[int(stage)];
                double pixels = 0;
                for (const Rect& z : parts) pixels += double(z.w) * z.h;
                ASSERT_FALSE(parts.empty()) << to_string(stage);
                EXPECT_LT(pixels, 0.5 * box.w * box.h) << to_string(stage) << ": the parts, not their box";
                EXPECT_EQ(disjoint_union(parts).size(), parts.size()) << to_string(stage);
                for (const Rect& z : parts) EXPECT_EQ(intersect(z, box), z);
            }
            // The blur reaches its radius past what was traced; the composite stays in the blur's parts.
            for (const Rect& z : r.touched_parts[int(Stage::composite)]) {
                bool inside = false;
                for (const Rect& b : r.touched_parts[int(Stage::blur)]) inside = inside || intersect(z, b) == z;
                EXPECT_TRUE(inside);
            }
            EXPECT_EQ(r.dirty, r.touched[int(Stage::trace)]);
        }
    }
}

TEST(OnlyWhatChanged, LightsSharingAPlaceEachKeepTheirMask) {
    // Reused masks move out of the cache, one per cached light: two lights
    // at the same place must each find their own (the second one must not
    // get the first one's moved-from, empty mask).
    Scene base;
    base.width = base.height = 16;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 3);
    const Camera cam{double(w.placed.bounds.x + 100), double(w.placed.bounds.y + 50), 700, 400};
    const Light twin{cam.x + 300, cam.y + 200};
    s.lights = {twin, twin, Light{cam.x + 350, cam.y + 230}};  // its areas meet the twins': they are redrawn
    FrameState st;
    render_frame(st, w, s, cam, 0);
    for (long f = 1; f <= 4; ++f) {
        // Another light moves, and the list's order changes: the second twin
        // is looked for away from its old place.
        Light other = s.lights[f % 2 ? 2 : 1];
        other.y += 5;
        s.lights = f % 2 ? std::vector<Light>{twin, other, twin} : std::vector<Light>{twin, twin, other};
        const FrameReport r = render_frame(st, w, s, cam, f);
        EXPECT_EQ(r.lights_traced, 1);
        EXPECT_EQ(r.lights_reused, 2);
        FrameState fresh;
        render_frame(fresh, w, s, cam, 0);
        ASSERT_EQ(st.traced.texels, fresh.traced.texels) << "frame " << f;
        ASSERT_EQ(st.final.rgba, fresh.final.rgba) << "frame " << f;
    }
}

TEST(OnlyWhatChanged, RadiusAndModeChangesRedoEverything) {
    Scene base;
    base.width = base.height = 10;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 5);
    FrameState st;
    render_frame(st, w, s, Camera{}, 0);
    for (int radius : {0, 3, 0, 1}) {
        s.params.blur_radius = radius;
        s.lights[0].y += 3;
        render_frame(st, w, s, Camera{}, 1);
        FrameState fresh;
        render_frame(fresh, w, s, Camera{}, 0);
        EXPECT_EQ(st.final.rgba, fresh.final.rgba) << "radius " << radius;
        EXPECT_EQ(st.light.texels, fresh.light.texels) << "radius " << radius;
    }
}

TEST(FastTrace, AClippedLightEqualsTheGeneralPath) {
    // The same obstacles twice: in a map covering every light's area (the
    // fast path, traced whole and cropped) and in a map of just their own
    // rectangle (which covers no area: the general path, ray by ray).
    const Rect own{-30, -25, 61, 51};
    Mask small(own), big(Rect{-200, -200, 401, 401});
    Pcg32 rng(31);
    for (int i = 0; i < 300; ++i) {
        const int x = own.x + int(rng.below(std::uint32_t(own.w))), y = own.y + int(rng.below(std::uint32_t(own.h)));
        if (std::abs(x) + std::abs(y) < 3) continue;  // keep the centres clear
        small.set(x, y), big.set(x, y);
    }
    int compared = 0;
    for (Mode mode : {Mode::light, Mode::shadow, Mode::flat})
        for (Rays rays : {Rays::border, Rays::every_pixel})
            for (int k : {1, 3})
                for (int t = 0; t < 6; ++t) {
                    if (rays == Rays::every_pixel && k != 1) continue;
                    Params p;
                    p.mode = mode;
                    p.rays = rays;
                    p.ray_skip = k;
                    const int a = 20 + int(rng.below(60)), b = 20 + int(rng.below(60));
                    const std::int64_t cx = int(rng.below(9)) - 4, cy = int(rng.below(9)) - 4;
                    const Rect area{int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
                    const Rect clip = intersect(area, Rect{area.x + int(rng.below(std::uint32_t(a))), area.y - 5,
                                                           a + int(rng.below(std::uint32_t(a))), b + 10});
                    const LightMask fast = trace_light(big, cx, cy, a, b, p, clip);
                    const LightMask general = trace_light(small, cx, cy, a, b, p, clip);
                    ASSERT_EQ(fast.value, general.value) << to_string(mode) << " k " << k << " t " << t;
                    ASSERT_EQ(fast.reached, general.reached) << to_string(mode) << " k " << k << " t " << t;
                    ++compared;
                }
    EXPECT_EQ(compared, 54);
}

TEST(FastTrace, PrunedAndWalkedTreesEqualTheGeneralPath) {
    // From one obstacle to a dense field, so that the tree is both pruned
    // (few obstacles) and walked (many), against the general path, ray by
    // ray, on the same obstacles in a map that covers no area.
    const TreeTraces before = tree_traces();
    Pcg32 rng(77);
    int compared = 0;
    for (int obstacles : {0, 1, 4, 20, 120, 900, 4000})
        for (Mode mode : {Mode::light, Mode::shadow})
            for (int k : {1, 2, 5}) {
                const int a = 15 + int(rng.below(60)), b = 15 + int(rng.below(60));
                const Rect area{-a, -b, 2 * a + 1, 2 * b + 1};
                // `small` lacks the area's left column: it covers no area, so its light takes the general path.
                Mask small(Rect{area.x + 1, area.y, area.w - 1, area.h}), big(Rect{-100, -100, 201, 201});
                for (int i = 0; i < obstacles; ++i) {
                    const int x = area.x + 1 + int(rng.below(std::uint32_t(area.w - 1)));
                    const int y = area.y + int(rng.below(std::uint32_t(area.h)));
                    if (x == 0 && y == 0 && obstacles > 1) continue;  // the centre blocked only in the one-obstacle case below
                    small.set(x, y), big.set(x, y);
                }
                if (obstacles == 1) small.set(0, 0), big.set(0, 0);
                Params p;
                p.mode = mode;
                p.ray_skip = k;
                const LightMask fast = trace_light(big, 0, 0, a, b, p, area);
                const LightMask general = trace_light(small, 0, 0, a, b, p, area);
                ASSERT_EQ(fast.value, general.value) << obstacles << " obstacles, " << to_string(mode) << " k " << k;
                ASSERT_EQ(fast.reached, general.reached) << obstacles << " obstacles, " << to_string(mode) << " k " << k;
                ++compared;
            }
    EXPECT_EQ(compared, 42);
    // Both ways ran (a blocked centre, a dense field: walked; a few obstacles: pruned).
    EXPECT_GE(tree_traces().walked - before.walked, 6u);
    EXPECT_GE(tree_traces().pruned - before.pruned, 12u);
}

TEST(Accumulate, WhiteLightsAddTheirValueToEveryChannelSaturating) {
    LightMask m;
    m.clip = {0, 0, 4, 1};
    m.value = {0, 100, 200, 255};
    LightTexture tex({0, 0, 4, 1});
    Params p;
    const Light white{0, 0};
    accumulate_light(tex, m, white, p);
    accumulate_light(tex, m, white, p);
    const std::vector<std::uint8_t> want = {0, 0, 0, 200, 200, 200, 255, 255, 255, 255, 255, 255};
    EXPECT_EQ(tex.texels, want);
}

TEST(Accumulate, WhiteRowsWiderThanAVectorSaturateInBothBuilds) {
    // Rows of every kind of width (under, at and over 16 and 32 texels, a
    // light's 257), over a texture with values already in it.
    for (int width : {1, 15, 16, 17, 31, 32, 33, 37, 63, 64, 65, 100, 257}) {
        SCOPED_TRACE(width);
        const Rect area{-3, 2, width, 5};
        LightMask m;
        m.clip = area;
        Pcg32 rng(std::uint64_t(12 + width));
        m.value.resize(std::size_t(area.w) * area.h);
        for (std::uint8_t& v : m.value) v = std::uint8_t(rng.below(256));
        const LightTexture before = random_texture({area.x - 2, area.y - 1, area.w + 5, area.h + 2}, 13);
        for (bool wide : both_widths()) {
            set_wide_kernels(wide);
            LightTexture tex = before;
            accumulate_light(tex, m, Light{0, 0}, Params{});
            for (int y = tex.rect.y; y < tex.rect.y + tex.rect.h; ++y)
                for (int x = tex.rect.x; x < tex.rect.x + tex.rect.w; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const int add = area.contains(x, y) ? m.value[std::size_t(y - area.y) * area.w + (x - area.x)] : 0;
                        ASSERT_EQ(tex.at(x, y)[c], std::min(255, before.at(x, y)[c] + add)) << x << "," << y << " wide " << wide;
                    }
        }
        set_wide_kernels(true);
    }
}

// Long work (TraceControl): progress in trace_work's steps, the same bytes
// with a control as without, and a cancel that stops within moments and
// leaves nothing half-traced behind.
TEST(LongWork, AControlChangesNoByteAndCountsEachLightsEstimate) {
    // Obstacles over every area below (the fast paths) and a few near the centre.
    Mask ob(Rect{-601, -521, 1203, 1043});
    for (auto [x, y] : {std::pair{2, 1}, {3, 1}, {-4, -2}, {1, -3}, {-2, 2}}) ob.set(x, y);
    const Mask clear_map(Rect{-601, -521, 1203, 1043});
    struct Case {
        Rays rays;
        int skip, a, b;
        Rect clip;  // empty: the whole area
    };
    const Case cases[] = {{Rays::every_pixel, 1, 6, 4, {}},  {Rays::border, 1, 7, 3, {}},
                          {Rays::border, 3, 600, 520, {}},   {Rays::border, 2, 5, 5, Rect{-2, -1, 4, 3}},
                          {Rays::every_pixel, 1, 3, 3, Rect{0, 0, 2, 2}}};
    for (const Case& c : cases)
        for (bool clear : {false, true}) {
            Params p;
            p.rays = c.rays;
            p.ray_skip = c.skip;
            const Rect area{-c.a, -c.b, 2 * c.a + 1, 2 * c.b + 1};
            const Rect clip = c.clip.empty() ? area : c.clip;
            const Mask& obstacles = clear ? clear_map : ob;
            std::atomic<bool> cancel{false};
            std::atomic<std::int64_t> done{0};
            const TraceControl control{&cancel, &done};
            const LightMask with = trace_light(obstacles, 0, 0, c.a, c.b, p, clip, clear, &control);
            const LightMask without = trace_light(obstacles, 0, 0, c.a, c.b, p, clip, clear);
            EXPECT_EQ(with.value, without.value) << c.a << "x" << c.b;
            EXPECT_EQ(done.load(), std::int64_t(light_trace_work(c.a, c.b, p))) << c.a << "x" << c.b << " clear " << clear;
        }
}

TEST(LongWork, ACancelledFrameThrowsKeepsNothingAndTheNextFrameIsAFreshOne) {
    Scene base;
    base.width = base.height = 24;
    const World w = make_world(test::default_tileset(), base);
    Scene s = moving_scene(w, 3);
    s.params.area_a = s.params.area_b = 700;
    s.params.rays = Rays::every_pixel;  // about 3e9 steps: far beyond a test's time unless cancelled
    const Camera cam{};
    for (int threads : {1, 2}) {
        FrameState st;
        st.options.threads = threads;
        std::atomic<bool> cancel{false};
        std::atomic<std::int64_t> done{0};
        st.options.control = TraceControl{&cancel, &done};
        const double total = trace_work(s, camera_view(cam, w));
        // Cancel once the trace is under way, from another thread, as the app's Cancel button does.
        std::jthread user([&] {
            while (done.load() == 0) std::this_thread::yield();
            cancel = true;
        });
        const auto t0 = std::chrono::steady_clock::now();
        EXPECT_THROW(render_frame(st, w, s, cam, 0), Cancelled);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        user.join();
        EXPECT_GT(done.load(), 0);
        EXPECT_LT(double(done.load()), 0.5 * total) << "stopped late (" << seconds << " s)";
        EXPECT_FALSE(st.cache.has_trace);
        EXPECT_TRUE(st.cache.lights.empty());
        EXPECT_TRUE(st.traced.texels.empty());
        EXPECT_EQ(st.options.threads, threads);  // the options are kept
        // The same state, not cancelled, on a scene small enough to finish: a fresh frame's bytes.
        cancel = false;
        Scene small = s;
        small.params.area_a = small.params.area_b = 60;
        render_frame(st, w, small, cam, 1);
        FrameState fresh;
        fresh.options.threads = threads;
        render_frame(fresh, w, small, cam, 0);
        EXPECT_EQ(st.final.rgba, fresh.final.rgba);
        EXPECT_EQ(st.traced.texels, fresh.traced.texels);
    }
}

TEST(LongWork, ASweepCancelledMidFrameReturnsWhatItFinished) {
    Scene s;
    s.width = s.height = 12;
    const World w = make_world(test::default_tileset(), s);
    s.lights = {Light{double(w.placed.bounds.x + 200), double(w.placed.bounds.y + 150)}};
    s.params.mode = Mode::flat;  // rays never stop: the one combination traces about 1e10 steps a frame (the area is far larger than the view, so ray by ray)
    s.params.rays = Rays::every_pixel;
    s.camera = Camera{double(w.placed.bounds.x), double(w.placed.bounds.y), 400, 300};
    SweepOptions opt;
    opt.frames = 2;
    opt.repeats = 1;
    std::atomic<bool> cancel{false};
    std::jthread user([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        cancel = true;
    });
    const std::vector<SweepPoint> points =
        run_sweep(w, s, {parse_sweep_axis("area_a=1500", s.params, "test"), parse_sweep_axis("area_b=1500", s.params, "test")},
                  opt, {}, &cancel);
    EXPECT_TRUE(cancel.load());
    EXPECT_TRUE(points.empty());  // cancelled inside the first combination's frames
}
