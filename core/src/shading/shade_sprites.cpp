// Beyond the paper: the shading map over a frame's region, and each light's
// sprite pixels shaded by it (sprite_shading.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "base/cpu.hpp"
#include "base/cpu_dispatch.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/sprite_shading.hpp"
#include "shading/oracles.hpp"

namespace isolux {

const SpriteNormals& cached_normals(NormalsCache& cache, const World& world, std::size_t index, const Params& p,
                                    SolidsCache* solids) {
    if (cache.from != p.sprite_shading || cache.made.size() != world.tileset.sprites.size()) {
        cache.from = p.sprite_shading;
        cache.sprites.assign(world.tileset.sprites.size(), SpriteNormals{});
        cache.made.assign(world.tileset.sprites.size(), 0);
    }
    if (!cache.made[index]) {
        const bool estimated = p.sprite_shading == SpriteShading::solids || p.sprite_shading == SpriteShading::luminance;
        const SpriteSolids* estimate = solids && estimated ? &cached_solids(*solids, world.tileset, index, p) : nullptr;
        cache.sprites[index] = sprite_normals(world.tileset, world.tileset.sprites[index], p, p.sprite_shading, estimate);
        cache.made[index] = 1;
    }
    return cache.sprites[index];
}

ShadingMap build_shading_map(const World& world, const Params& p, Rect region, NormalsCache& cache, SolidsCache* solids) {
    ShadingMap m;
    m.rect = region;
    // Each overlay meeting the region gets its normals (and their heights) first.
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near);
    std::vector<std::vector<float>> heights(world.tileset.sprites.size());
    for (std::uint32_t k : near) {
        const std::size_t si = std::size_t(world.placed.instances[k].sprite);
        if (heights[si].empty()) heights[si] = cached_normals(cache, world, si, p, solids).heights;
    }
    const Surface surface = build_surface(world, region, p.opacity_threshold, &heights);
    m.height = surface.height;
    m.normal.assign(surface.instance.size(), {0, 0, 0});
    for (int y = 0; y < region.h; ++y)
        for (int x = 0; x < region.w; ++x) {
            const std::size_t i = std::size_t(y) * region.w + x;
            if (surface.instance[i] < 0) continue;
            const SpriteInstance& in = world.placed.instances[std::size_t(surface.instance[i])];
            const SpriteNormals& sn = cache.sprites[std::size_t(in.sprite)];
            const Vec3 n = sn.normal[std::size_t(region.y + y - in.y) * sn.width + std::size_t(region.x + x - in.x)];
            for (int c = 0; c < 3; ++c) m.normal[i][std::size_t(c)] = std::int8_t(std::lround(std::clamp(n[c], -1.0, 1.0) * 127));
            // A sprite pixel never holds (0, 0, 0): that is the ground's mark.
            if (m.normal[i] == std::array<std::int8_t, 3>{0, 0, 0}) m.normal[i] = {0, 0, 127};
        }
    return m;
}

namespace {

// One row of a light's mask, x from 0 to n: the pixels lit (v != 0) that
// show a sprite (a normal that is not (0, 0, 0)), multiplied by the blend
// of the flat light and Lambert's cosine; every lane computed, then kept or
// not (no branch, so the compiler's vectors take the row; the arithmetic is
// the same per pixel). ox0: the row's first pixel's column less the light's.
[[gnu::always_inline]] inline void shade_row(std::uint8_t* v, const std::array<std::int8_t, 3>* q, const float* h, int n,
                                             int ox0, float oy, float lz, float s, float flat) {
    for (int x = 0; x < n; ++x) {
        const int qx = q[x][0], qy = q[x][1], qz = q[x][2];
        const float half_ox = float(ox0 + x) * 0.5f, up = oy + h[x];
        const float dx = -(up + half_ox), dy = -(up - half_ox), dz = lz - h[x];
        const float len2 = dx * dx + dy * dy + dz * dz;
        const float along = float(qx) * dx + float(qy) * dy + float(qz) * dz;
        // (Divided in every lane, then chosen: a division the compiler may
        // not move out of a branch keeps the loop scalar.)
        const float facing = std::max(0.0f, along / (127.0f * std::sqrt(len2)));
        const float cosine = len2 > 1e-12f ? facing : 1.0f;
        const float here = float(v[x]);
        const float lit = std::min(here, std::floor(here * (flat + s * cosine) + 0.5f));
        const bool shaded = v[x] != 0 && (qx | qy | qz) != 0;  // lit, and not the ground
        v[x] = std::uint8_t(shaded ? lit : here);
    }
}

// The rows of r, in runs of 64 pixels: a run the light leaves dark (a
// shadow) is passed without reading its normals and heights.
[[gnu::always_inline]] inline void shade_runs(LightMask& mask, const ShadingMap& map, Rect r, float lz, float s, float flat) {
    constexpr int run = 64;
    for (int y = r.y; y < r.y + r.h; ++y) {
        const std::size_t row = std::size_t(y - map.rect.y) * map.rect.w + std::size_t(r.x - map.rect.x);
        std::uint8_t* v = &mask.value[std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(r.x - mask.clip.x)];
        const int ox0 = int(std::int64_t(r.x) - mask.cx);
        const float oy = float(std::int64_t(y) - mask.cy);
        for (int x = 0; x < r.w; x += run) {
            const int n = std::min(run, r.w - x);
            std::uint64_t any = 0;
            if (n == run) {
                std::uint64_t words[run / 8];
                std::memcpy(words, v + x, run);
                for (std::uint64_t w : words) any |= w;
            } else {
                any = 1;
            }
            if (any) shade_row(v + x, &map.normal[row + std::size_t(x)], &map.height[row + std::size_t(x)], n, ox0 + x, oy, lz, s, flat);
        }
    }
}
void shade_rows(LightMask& mask, const ShadingMap& map, Rect r, float lz, float s, float flat) {
    shade_runs(mask, map, r, lz, s, flat);
}
#if ISOLUX_X86_DISPATCH
ISOLUX_AVX2 void shade_rows_avx2(LightMask& mask, const ShadingMap& map, Rect r, float lz, float s, float flat) {
    shade_runs(mask, map, r, lz, s, flat);
}
#endif

}  // namespace

void shade_sprites_reference(LightMask& mask, const ShadingMap& map, double light_height, const Params& p) {
    if (!shades_sprites(p) || map.empty()) return;
    const Rect r = intersect(mask.clip, map.rect);
    const float s = float(p.shading_strength), flat = 1 - s, lz = float(light_height);
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x) {
            std::uint8_t& v = mask.value[std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(x - mask.clip.x)];
            const std::size_t i = std::size_t(y - map.rect.y) * map.rect.w + std::size_t(x - map.rect.x);
            const std::array<std::int8_t, 3> q = map.normal[i];
            if (v == 0 || q == std::array<std::int8_t, 3>{0, 0, 0}) continue;  // dark, or the ground
            const float h = map.height[i];
            const float half_ox = float(std::int64_t(x) - mask.cx) * 0.5f, up = float(std::int64_t(y) - mask.cy) + h;
            const float dx = -(up + half_ox), dy = -(up - half_ox), dz = lz - h;
            const float len2 = dx * dx + dy * dy + dz * dz;
            const float along = float(q[0]) * dx + float(q[1]) * dy + float(q[2]) * dz;
            const float cosine = len2 > 1e-12f ? std::max(0.0f, along / (127.0f * std::sqrt(len2))) : 1.0f;
            v = std::uint8_t(std::min(float(v), std::floor(float(v) * (flat + s * cosine) + 0.5f)));
        }
}

void shade_sprites(LightMask& mask, const ShadingMap& map, double light_height, const Params& p) {
    if (!shades_sprites(p) || map.empty()) return;
    const Rect r = intersect(mask.clip, map.rect);
    if (r.empty()) return;
    // Single precision, one square root a pixel: lambert() written out for
    // the map's stored normals (q / 127, unit within a rounding). The
    // direction to the light, from the point ground_frame(x + 0.5, y + 0.5,
    // h) to L = ground_frame(cx + 0.5, cy + 0.5, 0) + (0, 0, H), is by
    // ground_frame's linearity (-(oy + h + ox / 2), -(oy + h - ox / 2), H - h)
    // with (ox, oy) = (x - cx, y - cy): small numbers however far out the
    // light stands (an endless world's pixels pass 2^36). Floats round the
    // same on every machine (no contraction: core's -ffp-contract=off), in
    // the baseline build and the AVX2 one alike.
    const float s = float(p.shading_strength), flat = 1 - s, lz = float(light_height);
#if ISOLUX_X86_DISPATCH
    if (wide_kernels()) return shade_rows_avx2(mask, map, r, lz, s, flat);
#endif
    shade_rows(mask, map, r, lz, s, flat);
}

}  // namespace isolux
