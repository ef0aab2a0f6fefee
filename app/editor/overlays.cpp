#include "editor/overlays.hpp"

#include <algorithm>
#include <cmath>

#include "isolux/light_texture.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/sprite_shading.hpp"
#include "isolux/truth.hpp"

namespace isolux::app {

namespace {
void blend(std::uint8_t* d, int r, int g, int b, float a) {
    // Premultiplied "over".
    const float keep = 1.0f - a;
    d[0] = std::uint8_t(r * a + d[0] * keep + 0.5f);
    d[1] = std::uint8_t(g * a + d[1] * keep + 0.5f);
    d[2] = std::uint8_t(b * a + d[2] * keep + 0.5f);
    d[3] = std::uint8_t(255 * a + d[3] * keep + 0.5f);
}
}  // namespace

OverlayImage build_overlays(const World& world, const FrameState& frame, const Scene& scene, const Overlays& o,
                            Rect region, const LightTexture* truth) {
    OverlayImage out;
    const bool difference = o.truth_difference && truth && !truth->rect.empty();
    const bool normals = o.normals && !frame.shading.empty();
    if (!o.obstacles && !o.opacity_maps && !o.delta_y_bands && !difference && !normals) return out;
    region = intersect(region, world.placed.bounds);
    if (region.empty()) return out;
    out.rect = region;
    out.image = Image(region.w, region.h);
    const Params& p = scene.params;
    const auto& inst = world.placed.instances;

    if (o.delta_y_bands) {
        std::vector<SpriteObstacleTrace> traces(world.tileset.sprites.size());
        std::vector<char> done(traces.size(), 0);
        std::vector<std::uint32_t> near;
        instances_in(world.placed, region, true, near);
        for (std::uint32_t k : near) {
            const SpriteInstance& in = inst[k];
            if (in.sprite >= int(frame.opacity.size())) continue;
            const Mask& op = frame.opacity[in.sprite];
            if (!done[in.sprite]) {
                sprite_obstacle(op, p.delta_y, &traces[in.sprite]);
                done[in.sprite] = 1;
            }
            const SpriteObstacleTrace& t = traces[in.sprite];
            for (int y = t.first_line; y <= t.last_line; ++y)
                for (int x = 0; x < op.width; ++x) {
                    const int wx = in.x + x, wy = in.y + y;
                    if (!op.get(x, y) || !region.contains(wx, wy)) continue;
                    const bool chosen = y == t.chosen_line && x >= t.run_start && x < t.run_start + t.run_length;
                    blend(out.image.at(wx - region.x, wy - region.y), chosen ? 0 : 60, chosen ? 255 : 120,
                          255, o.delta_y_opacity);
                }
        }
    }
    if (normals) {  // the shading's normals in the screen's tangent space, as a normal map draws them
        const ShadingMap& m = frame.shading;
        const Rect r = intersect(m.rect, region);
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x) {
                const auto& q = m.normal[std::size_t(y - m.rect.y) * m.rect.w + std::size_t(x - m.rect.x)];
                if (q[0] == 0 && q[1] == 0 && q[2] == 0) continue;
                const auto c = normal_map_colour(Vec3{double(q[0]), double(q[1]), double(q[2])} / 127.0);
                blend(out.image.at(x - region.x, y - region.y), c[0], c[1], c[2], o.normals_opacity);
            }
    }
    if (o.opacity_maps) {
        for (const Light& l : scene.lights) {
            const Rect area = intersect(light_area(l, p), region);
            if (area.empty()) continue;
            const auto cy = std::int64_t(std::floor(l.y));
            std::vector<std::uint32_t> near;
            instances_in(world.placed, area, true, near);
            for (std::uint32_t k : near) {
                const SpriteInstance& in = inst[k];
                if (in.sprite >= int(frame.opacity.size())) continue;
                const Mask& op = frame.opacity[in.sprite];
                const Rect r = intersect({in.x, in.y, op.width, op.height}, area);
                if (r.empty()) continue;
                const bool added = opacity_map_added(in, cy);
                for (int y = r.y; y < r.y + r.h; ++y)
                    for (int x = r.x; x < r.x + r.w; ++x)
                        if (op.get(x - in.x, y - in.y))
                            blend(out.image.at(x - region.x, y - region.y), added ? 40 : 255, added ? 230 : 50,
                                  added ? 80 : 50, o.opacity_maps_opacity);
            }
        }
    }
    if (difference) {
        // The model as traced and corrected (before the blur) against the 3D reference.
        const Rect r = intersect(truth->rect, region);
        const Image d = lit_difference(shift_light_texture(frame.traced, r), *truth);
        for (int y = 0; y < r.h; ++y)
            for (int x = 0; x < r.w; ++x) {
                const std::uint8_t* c = d.at(x, y);
                if (c[3]) blend(out.image.at(r.x + x - region.x, r.y + y - region.y), c[0], c[1], c[2], o.truth_difference_opacity);
            }
    }
    if (o.obstacles) {
        const Mask& m = frame.obstacles;
        const Rect r = intersect(m.rect(), region);
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x)
                if (m.get(x, y)) blend(out.image.at(x - region.x, y - region.y), 255, 255, 255, o.obstacles_opacity);
    }
    return out;
}

}  // namespace isolux::app
