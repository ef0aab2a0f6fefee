// Beyond the paper: the shading map over a frame's region, and each light's
// sprite pixels shaded by it (sprite_shading.hpp).
#include <algorithm>
#include <cmath>

#include "isolux/sprite_shading.hpp"

namespace isolux {

const SpriteNormals& cached_normals(NormalsCache& cache, const World& world, std::size_t index, const Params& p) {
    if (cache.from != p.sprite_shading || cache.made.size() != world.tileset.sprites.size()) {
        cache.from = p.sprite_shading;
        cache.sprites.assign(world.tileset.sprites.size(), SpriteNormals{});
        cache.made.assign(world.tileset.sprites.size(), 0);
    }
    if (!cache.made[index]) {
        cache.sprites[index] = sprite_normals(world.tileset, world.tileset.sprites[index], p, p.sprite_shading);
        cache.made[index] = 1;
    }
    return cache.sprites[index];
}

ShadingMap build_shading_map(const World& world, const Params& p, Rect region, NormalsCache& cache) {
    ShadingMap m;
    m.rect = region;
    // Each overlay meeting the region gets its normals (and their heights) first.
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near);
    std::vector<std::vector<float>> heights(world.tileset.sprites.size());
    for (std::uint32_t k : near) {
        const std::size_t si = std::size_t(world.placed.instances[k].sprite);
        if (heights[si].empty()) heights[si] = cached_normals(cache, world, si, p).heights;
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
    if (p.sprite_shading == SpriteShading::none || p.shading_strength <= 0 || map.empty()) return;
    const Rect r = intersect(mask.clip, map.rect);
    const double s = p.shading_strength;
    const Vec3 light = ground_frame(double(mask.cx) + 0.5, double(mask.cy) + 0.5, 0) + Vec3{0, 0, light_height};
    for (int y = r.y; y < r.y + r.h; ++y) {
        std::uint8_t* v = &mask.value[std::size_t(y - mask.clip.y) * mask.clip.w + std::size_t(r.x - mask.clip.x)];
        const std::size_t row = std::size_t(y - map.rect.y) * map.rect.w + std::size_t(r.x - map.rect.x);
        for (int x = 0; x < r.w; ++x) {
            if (v[x] == 0) continue;
            const std::array<std::int8_t, 3>& q = map.normal[row + std::size_t(x)];
            if (q[0] == 0 && q[1] == 0 && q[2] == 0) continue;  // the ground: not shaded
            const Vec3 n = glm::normalize(Vec3{double(q[0]), double(q[1]), double(q[2])});
            const Vec3 point = ground_frame(r.x + x + 0.5, y + 0.5, map.height[row + std::size_t(x)]);
            const double factor = (1 - s) + s * lambert(n, point, light);
            v[x] = std::uint8_t(std::min(double(v[x]), std::floor(v[x] * factor + 0.5)));
        }
    }
}

}  // namespace isolux
