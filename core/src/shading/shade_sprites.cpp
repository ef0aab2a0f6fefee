// Beyond the paper: the shading map over a frame's region, and each light's
// sprite pixels shaded by it (sprite_shading.hpp).
#include <algorithm>
#include <cmath>

#include "isolux/occluder_map.hpp"
#include "isolux/sprite_shading.hpp"

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

void shade_sprites(LightMask& mask, const ShadingMap& map, double light_height, const Params& p) {
    if (!shades_sprites(p) || map.empty()) return;
    const Rect r = intersect(mask.clip, map.rect);
    // Single precision, one square root a pixel: lambert() written out for
    // the map's stored normals (q / 127, unit within a rounding). The
    // direction to the light, from the point ground_frame(x + 0.5, y + 0.5,
    // h) to L = ground_frame(cx + 0.5, cy + 0.5, 0) + (0, 0, H), is by
    // ground_frame's linearity (-(oy + h + ox / 2), -(oy + h - ox / 2), H - h)
    // with (ox, oy) = (x - cx, y - cy): small numbers however far out the
    // light stands (an endless world's pixels pass 2^36). Floats round the
    // same on every machine (no contraction: core's -ffp-contract=off).
    const float s = float(p.shading_strength), flat = 1 - s;
    const float lz = float(light_height);
    for (int y = r.y; y < r.y + r.h; ++y) {
        std::uint8_t* v = &mask.value[std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(r.x - mask.clip.x)];
        const std::size_t row = std::size_t(y - map.rect.y) * map.rect.w + std::size_t(r.x - map.rect.x);
        const std::array<std::int8_t, 3>* q = &map.normal[row];
        const float* h = &map.height[row];
        const float oy = float(std::int64_t(y) - mask.cy);
        for (int x = 0; x < r.w; ++x) {
            if (v[x] == 0) continue;
            const int qx = q[x][0], qy = q[x][1], qz = q[x][2];
            if ((qx | qy | qz) == 0) continue;  // the ground: not shaded
            const float half_ox = float(std::int64_t(r.x + x) - mask.cx) * 0.5f, up = oy + h[x];
            const float dx = -(up + half_ox), dy = -(up - half_ox), dz = lz - h[x];
            const float len2 = dx * dx + dy * dy + dz * dz;
            const float along = float(qx) * dx + float(qy) * dy + float(qz) * dz;
            const float cosine = len2 > 1e-12f ? std::max(0.0f, along / (127.0f * std::sqrt(len2))) : 1.0f;
            const float lit = float(v[x]) * (flat + s * cosine);
            v[x] = std::uint8_t(std::min(float(v[x]), std::floor(lit + 0.5f)));
        }
    }
}

}  // namespace isolux
