// The blur (paper 3.2): box_blur held to box_blur_reference byte for byte,
// in both kernels' builds, at every radius, row width and edge.
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
#include "frame/oracles.hpp"
#include "frame/frame_cache.hpp"

using namespace isolux;
using isolux::test::both_widths;
using isolux::test::random_texture;

namespace {

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

namespace {

// Surfaces in blobs: rectangles of overlay ids over the ground (-1), some
// overlapping, so ids change along rows and columns at every distance.
SurfaceIds random_surfaces(Rect r, std::uint64_t seed) {
    SurfaceIds ids;
    ids.rect = r;
    ids.id.assign(std::size_t(r.w) * r.h, -1);
    Pcg32 rng(seed);
    const int blobs = 1 + int(rng.below(12));
    for (int b = 0; b < blobs; ++b) {
        const int w = 1 + int(rng.below(std::uint32_t(std::max(1, r.w / 2)))), h = 1 + int(rng.below(std::uint32_t(std::max(1, r.h / 2))));
        const int x = int(rng.below(std::uint32_t(r.w))), y = int(rng.below(std::uint32_t(r.h)));
        for (int yy = y; yy < std::min(r.h, y + h); ++yy)
            for (int xx = x; xx < std::min(r.w, x + w); ++xx) ids.id[std::size_t(yy) * r.w + xx] = b;
    }
    return ids;
}

}  // namespace

TEST(BlurWithinSurfaces, EqualsItsReferenceForEveryRadiusSizeAndLayout) {
    const Rect sizes[] = {{0, 0, 1, 1}, {-3, 5, 2, 7}, {10, -4, 17, 5}, {0, 0, 40, 30}};
    int checked = 0;
    for (const Rect& r : sizes)
        for (int radius : {0, 1, 2, 3, 5, 9, 40})
            for (int channels : {1, 3}) {
                LightTexture t = random_texture(r, std::uint64_t(r.w * 17 + radius));
                if (channels == 1) {
                    LightTexture g(r, 1);
                    for (std::size_t i = 0; i < g.texels.size(); ++i) g.texels[i] = t.texels[i * 3];
                    t = g;
                }
                // Ids over a rectangle that covers only part of the texture: outside, the ground.
                SurfaceIds ids = random_surfaces(Rect{r.x + 1, r.y, std::max(1, r.w - 1), r.h}, std::uint64_t(radius * 7 + r.h));
                EXPECT_EQ(box_blur_within(t, radius, ids).texels, box_blur_within_reference(t, radius, ids).texels)
                    << r.w << "x" << r.h << " r " << radius << " channels " << channels;
                ++checked;
            }
    EXPECT_EQ(checked, 56);
}

TEST(BlurWithinSurfaces, LightNeverBleedsOntoAnotherSurface) {
    // Lit ground (255) around a dark sprite (0): the plain blur lights the
    // sprite's edge, the blur within surfaces leaves every sprite texel dark
    // and the ground's lit.
    const Rect r{0, 0, 20, 20};
    LightTexture t(r);
    SurfaceIds ids{r, std::vector<std::int32_t>(400, -1)};
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            const bool sprite = x >= 6 && x < 14 && y >= 6 && y < 14;
            ids.id[std::size_t(y) * 20 + x] = sprite ? 3 : -1;
            for (int k = 0; k < 3; ++k) t.texels[(std::size_t(y) * 20 + x) * 3 + k] = sprite ? 0 : 255;
        }
    const LightTexture plain = box_blur(t, 2), within = box_blur_within(t, 2, ids);
    int plain_lit_sprite = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 20; ++x) {
            const bool sprite = ids.at(x, y) == 3;
            plain_lit_sprite += sprite && plain.at(x, y)[0] > 0;
            EXPECT_EQ(within.at(x, y)[0], sprite ? 0 : 255) << x << ", " << y;
        }
    EXPECT_GT(plain_lit_sprite, 0);  // what the plain blur does there
}

TEST(BlurWithinSurfaces, ARegionWritesTheWholeBlursTexels) {
    const Rect r{-7, 3, 61, 45};
    const LightTexture t = random_texture(r, 99);
    const SurfaceIds ids = random_surfaces(r, 5);
    const LightTexture whole = box_blur_within(t, 3, ids);
    LightTexture out(r);
    std::fill(out.texels.begin(), out.texels.end(), std::uint8_t(7));
    const Rect region{5, 10, 20, 9};
    box_blur_within_into(t, 3, ids, region, out);
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x)
            for (int k = 0; k < 3; ++k)
                EXPECT_EQ(out.at(x, y)[k], region.contains(x, y) ? whole.at(x, y)[k] : 7) << x << ", " << y;
}

TEST(BlurWithinSurfaces, TheFrameBlursWithinTheSurfacesWithSolidsOnly) {
    // With occluders solids the frame's blurred texture is box_blur_within of
    // its trace over the surfaces it shows; with footprints, box_blur's.
    Scene s;
    s.width = 8;
    s.height = 8;
    const World w = make_world(test::default_tileset(), s);
    s.params.falloff_scale = 8;
    s.params.blur_radius = 2;
    s.lights = {Light{500, 300}, Light{700, 420}};
    for (Occluders o : {Occluders::footprints, Occluders::solids}) {
        s.params.occluders = o;
        FrameState st;
        st.options.grey_when_lights_are = false;
        render_frame(st, w, s, Camera{100, 60, 700, 420}, 0);
        if (o == Occluders::footprints) {
            EXPECT_TRUE(st.surface_ids.id.empty());
            EXPECT_EQ(st.cache->blurred.texels, box_blur(st.traced, 2).texels);
            continue;
        }
        ASSERT_EQ(st.surface_ids.rect, st.occluders.surface.rect);
        ASSERT_EQ(st.surface_ids.reach.size(), st.surface_ids.id.size());
        const long sprites = std::count_if(st.surface_ids.id.begin(), st.surface_ids.id.end(), [](std::int32_t i) { return i >= 0; });
        EXPECT_GT(sprites, 1000);
        EXPECT_EQ(st.cache->blurred.texels, box_blur_within(st.traced, 2, st.surface_ids).texels);
        EXPECT_NE(st.cache->blurred.texels, box_blur(st.traced, 2).texels);
        // A light moved: the blur redone where it changed is the whole blur's.
        s.lights[0].x += 9;
        render_frame(st, w, s, Camera{100, 60, 700, 420}, 1);
        EXPECT_EQ(st.cache->blurred.texels, box_blur_within(st.traced, 2, st.surface_ids).texels);
        // The app's options (its GPU blurs): the same ids, and no reach made for them.
        FrameState gpu;
        gpu.options.grey_when_lights_are = false;
        gpu.options.cpu_sprites = false;
        gpu.options.cpu_blur_and_composite = false;
        render_frame(gpu, w, s, Camera{100, 60, 700, 420}, 1);
        EXPECT_EQ(gpu.surface_ids.id, st.surface_ids.id);
        EXPECT_NE(gpu.surface_ids_revision, 0u);
        EXPECT_TRUE(gpu.surface_ids.reach.empty());
    }
}

// The redo skips texels whose window holds one value (the dark between
// lights, a lit stretch of one level), sixteen at a time where all are 0,
// and texels at the texture's edge whose window is dark: on textures made
// of such stretches (0 and other values, touching the edges, wide enough
// for the sixteen-texel steps) the bytes stay the reference's.
TEST(BlurWithinSurfaces, darkAndEvenStretchesGiveTheReferencesBytes) {
    int checked = 0;
    for (std::uint64_t seed : {11, 12, 13, 14})
        for (int channels : {1, 3}) {
            const Rect r{-7, 3, 83, 47};
            LightTexture t(r, channels);
            Pcg32 rng(seed);
            for (int b = 0; b < 14; ++b) {  // stretches of one value over random noise
                const int x = int(rng.below(std::uint32_t(r.w))) - 5, y = int(rng.below(std::uint32_t(r.h))) - 5;
                const int w = 3 + int(rng.below(40)), h = 3 + int(rng.below(25));
                const std::uint8_t v = b % 2 ? std::uint8_t(rng.below(256)) : 0;
                for (int yy = std::max(0, y); yy < std::min(r.h, y + h); ++yy)
                    for (int xx = std::max(0, x); xx < std::min(r.w, x + w); ++xx)
                        for (int k = 0; k < channels; ++k)
                            t.texels[(std::size_t(yy) * r.w + xx) * channels + k] = b == 13 ? std::uint8_t(rng.below(256)) : v;
            }
            SurfaceIds ids = random_surfaces(r, seed);
            index_surfaces(ids);
            for (int radius = 1; radius <= 7; ++radius) {
                EXPECT_EQ(box_blur_within(t, radius, ids).texels, box_blur_within_reference(t, radius, ids).texels)
                    << "seed " << seed << " channels " << channels << " r " << radius;
                ++checked;
            }
        }
    EXPECT_EQ(checked, 56);
}

TEST(BlurWithinSurfaces, ItsSixteenWideStripsGiveTheReferencesBytesAtFullValueAndOnRaggedOutlines) {
    // The one-channel blur takes the texels near an outline sixteen at a
    // time, down bands of rows, with 16-bit sums and a float division: a
    // texture wider than several strips and taller than a band, at full
    // value (the largest sums: 225 x 255 at radius 7, each mean whole) and
    // at random values (means that are not whole), over surfaces whose
    // outlines are ragged pixel by pixel and over solid blocks.
    int checked = 0;
    for (std::uint64_t seed : {21, 22, 23}) {
        const Rect r{-9, 4, 150, 90};
        Pcg32 rng(seed);
        SurfaceIds ids = random_surfaces(r, seed);
        for (std::size_t i = 0; i < ids.id.size(); ++i)  // ragged: a third of the pixels another surface
            if (rng.below(3) == 0) ids.id[i] = std::int32_t(rng.below(4)) - 1;
        index_surfaces(ids);
        ASSERT_EQ(ids.joins.size(), ids.id.size());
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x) {
                const std::uint8_t j = ids.joins[std::size_t(y - r.y) * r.w + std::size_t(x - r.x)];
                EXPECT_EQ(bool(j & SurfaceIds::join_right), x + 1 < r.x + r.w && ids.at(x + 1, y) == ids.at(x, y));
                EXPECT_EQ(bool(j & SurfaceIds::join_down), y + 1 < r.y + r.h && ids.at(x, y + 1) == ids.at(x, y));
            }
        for (bool full : {true, false}) {
            LightTexture t(r, 1);
            for (std::uint8_t& v : t.texels) v = full ? 255 : std::uint8_t(rng.below(256));
            for (int radius = 1; radius <= 7; ++radius) {
                EXPECT_EQ(box_blur_within(t, radius, ids).texels, box_blur_within_reference(t, radius, ids).texels)
                    << "seed " << seed << (full ? " full" : " random") << " r " << radius;
                ++checked;
            }
        }
    }
    EXPECT_EQ(checked, 42);
}

TEST(BlurWithinSurfaces, ReachIsTheChebyshevDistanceToAnotherSurface) {
    // Every pixel's reach against a brute-force search, the outside counting
    // as the ground; and the blur gives the same bytes with ids over any
    // rectangle, indexed or not.
    for (std::uint64_t seed : {1, 2, 3, 4, 5, 6}) {
        const Rect sizes[] = {{-4, 7, 37, 23}, {3, 3, 1, 9}, {0, -2, 11, 1}, {5, 0, 64, 40}};
        SurfaceIds ids = random_surfaces(sizes[seed % 4], seed);
        index_surfaces(ids);
        const Rect r = ids.rect;
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x) {
                int best = 255;
                for (int d = 1; d < 255 && best == 255; ++d)
                    for (int dy = -d; dy <= d && best == 255; ++dy)
                        for (int dx = -d; dx <= d; ++dx)
                            if ((std::abs(dx) == d || std::abs(dy) == d) && ids.at(x + dx, y + dy) != ids.at(x, y)) {
                                best = d;
                                break;
                            }
                ASSERT_EQ(int(ids.reach[std::size_t(y - r.y) * r.w + (x - r.x)]), std::min(best, surface_reach_cap))
                    << x << ", " << y;
            }
        const LightTexture t = random_texture(Rect{-10, 0, 50, 40}, seed);
        SurfaceIds bare{ids.rect, ids.id, {}};
        for (int radius : {1, 2, 4, 7, 8})
            for (const SurfaceIds* s : {&ids, &bare})
                EXPECT_EQ(box_blur_within(t, radius, *s).texels, box_blur_within_reference(t, radius, *s).texels) << radius;
    }
}

TEST(Blur, isTheClampedBoxMean) {
    LightTexture t(Rect{0, 0, 3, 1});
    const std::uint8_t v[3] = {0, 90, 180};
    for (int x = 0; x < 3; ++x)
        for (int k = 0; k < 3; ++k) t.texels[x * 3 + k] = v[x];
    LightTexture b = box_blur(t, 1);
    // Clamped at the edges: x=0 sees 0,0,90; x=1 sees 0,90,180; x=2 sees 90,180,180.
    EXPECT_EQ(b.texels[0], 30);
    EXPECT_EQ(b.texels[3], 90);
    EXPECT_EQ(b.texels[6], 150);
    // A radius far larger than the texture: the clamp weights the edges.
    LightTexture big = box_blur(t, 50);
    // Window of 101 over x in [-50, 50+x]: 51 - x texels of 0 ... exact mean.
    const int n = 101;
    const int sum0 = 0 * 51 + 90 * 1 + 180 * 49;
    EXPECT_EQ(big.texels[0], (sum0 + n / 2) / n);
    EXPECT_EQ(box_blur(t, 0).texels, t.texels);
}
