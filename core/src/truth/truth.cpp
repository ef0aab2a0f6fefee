// The references of truth.hpp: the true 3D shapes, the exact 2D line, and the
// model's own every-pixel rays.
#include "isolux/truth.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "isolux/error.hpp"
#include "isolux/frame.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"

namespace isolux {

namespace {

// How far from the surface point the segment to the light starts counting
// as blocked: the height map is rounded to whole pixels and averaged over the
// pixel, so the point lies up to about a pixel inside or outside its solid.
constexpr double surface_epsilon = 1.5;
// How far past its own solid's surface a sprite pixel's point is moved, pixels.
constexpr double surface_lift = 0.25;

Rect area_of(std::int64_t cx, std::int64_t cy, int a, int b) {
    return {int(cx) - a, int(cy) - b, 2 * a + 1, 2 * b + 1};
}

// A light's mask over the part of its area inside `clip`, nothing lit yet.
LightMask unlit_mask(std::int64_t cx, std::int64_t cy, int a, int b, const Params& p, Rect clip, double dy_scale) {
    LightMask m;
    start_mask(m, cx, cy, a, b, p, intersect(clip, area_of(cx, cy, a, b)));
    m.dy_scale = dy_scale;
    return m;
}

bool boxes_meet(const std::array<Vec3, 2>& p, const std::array<Vec3, 2>& q) {
    return p[0].x <= q[1].x && q[0].x <= p[1].x && p[0].y <= q[1].y && q[0].y <= p[1].y && p[0].z <= q[1].z &&
           q[0].z <= p[1].z;
}

}  // namespace

std::string_view to_string(Reference r) {
    switch (r) {
        case Reference::every_pixel: return "every_pixel";
        case Reference::exact_line: return "exact_line";
        case Reference::three_d: return "3d";
        case Reference::three_d_facing: return "3d_facing";
        case Reference::three_d_shaded: return "3d_shaded";
    }
    return "3d";
}

Reference parse_reference(std::string_view s, std::string_view source) {
    for (Reference r : {Reference::every_pixel, Reference::exact_line, Reference::three_d, Reference::three_d_facing,
                        Reference::three_d_shaded})
        if (s == to_string(r)) return r;
    throw Error(std::string(source) + ": reference \"" + std::string(s) +
                "\" is not one of every_pixel, exact_line, 3d, 3d_facing, 3d_shaded");
}

double light_height(const Light& l, const Params& p) { return l.height.value_or(p.light_height); }

Surface build_surface(const World& world, Rect rect, double opacity_threshold,
                      const std::vector<std::vector<float>>* heights) {
    Surface s;
    build_surface_into(s, world, rect, opacity_threshold, heights);
    return s;
}

void build_surface_into(Surface& s, const World& world, Rect rect, double opacity_threshold,
                        const std::vector<std::vector<float>>* heights) {
    s.rect = rect;
    s.instance.assign(std::size_t(std::max(0, rect.w)) * std::max(0, rect.h), -1);
    s.height.assign(s.instance.size(), 0.0f);
    if (rect.empty()) return;
    std::vector<Mask> opacity(world.tileset.sprites.size());
    std::vector<char> made(opacity.size(), 0);
    std::vector<std::uint32_t> near;
    instances_in(world.placed, rect, true, near);
    for (std::uint32_t k : near) {  // back to front: the last opaque one is on top
        const SpriteInstance& in = world.placed.instances[k];
        const Sprite& sp = world.tileset.sprites[std::size_t(in.sprite)];
        if (!made[std::size_t(in.sprite)]) {
            opacity[std::size_t(in.sprite)] = opacity_map(sp.image, sprite_threshold(sp, opacity_threshold));
            made[std::size_t(in.sprite)] = 1;
        }
        const Mask& op = opacity[std::size_t(in.sprite)];
        const Rect r = intersect({in.x, in.y, op.width, op.height}, rect);
        for (int y = r.y; y < r.y + r.h; ++y)
            for (int x = r.x; x < r.x + r.w; ++x) {
                const int sx = x - in.x, sy = y - in.y;
                if (!op.get(sx, sy)) continue;
                const std::size_t i = std::size_t(y - rect.y) * rect.w + (x - rect.x);
                s.instance[i] = std::int32_t(k);
                if (heights && !(*heights)[std::size_t(in.sprite)].empty()) {
                    s.height[i] = (*heights)[std::size_t(in.sprite)][std::size_t(sy) * sp.image.width + sx];
                } else if (!sp.height.empty()) {
                    s.height[i] = float(sp.height[std::size_t(sy) * sp.image.width + sx]);
                } else {
                    // No height map: the shape's surface seen at the pixel's centre.
                    const double h = surface_height(sp.shape, sx + 0.5 - (in.ground_x - in.x),
                                                    sy + 0.5 - (in.ground_y - in.y));
                    s.height[i] = float(std::max(0.0, h));
                }
            }
    }
}

namespace {

Error no_shape(const World& world, const Sprite& sp) {
    return Error(world.tileset.source + ": sprite \"" + sp.name +
                 "\" has no shape: the 3D reference and occluders shapes need every overlay's solids (see docs/guide.md)");
}

}  // namespace

void require_shapes(const World& world, Rect region) {
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near);
    for (std::uint32_t k : near) {
        const Sprite& sp = world.tileset.sprites[std::size_t(world.placed.instances[k].sprite)];
        if (sp.shape.empty()) throw no_shape(world, sp);
    }
}

WorldSolids world_solids(const World& world, Rect region) {
    WorldSolids w;
    std::vector<std::uint32_t> near;
    instances_in(world.placed, region, true, near);
    for (std::uint32_t k : near) {
        const SpriteInstance& in = world.placed.instances[k];
        const Sprite& sp = world.tileset.sprites[std::size_t(in.sprite)];
        if (sp.shape.empty()) throw no_shape(world, sp);
        const Vec3 origin = ground_frame(in.ground_x, in.ground_y, 0);
        for (const Solid& s : sp.shape) {
            if (!has_volume(s)) continue;
            w.solids.push_back(translated(s, origin));
            w.bounds.push_back(solid_bounds(w.solids.back()));
            w.instance.push_back(std::int32_t(k));
        }
    }
    return w;
}

LightMask truth_light(const Surface& surface, const WorldSolids& solids, std::int64_t cx, std::int64_t cy,
                      double height, int a, int b, const Params& p, Rect clip, bool facing, double dy_scale,
                      bool shaded) {
    LightMask m = unlit_mask(cx, cy, a, b, p, clip, dy_scale);
    if (m.clip.empty()) return m;
    // The light stands `height` above the ground point shown at its centre pixel.
    const Vec3 ground_point = ground_frame(double(cx) + 0.5, double(cy) + 0.5, 0);
    const Vec3 light{ground_point.x, ground_point.y, height};
    std::vector<std::size_t> candidates;
    for (int y = m.clip.y; y < m.clip.y + m.clip.h; ++y)
        for (int x = m.clip.x; x < m.clip.x + m.clip.w; ++x) {
            std::uint8_t v = shaped_falloff(x - cx, y - cy, a, b, p, dy_scale);  // the model's intensity, shape and fade
            if (v == 0) continue;
            std::size_t si = 0;
            std::int32_t owner = -1;
            float h = 0;
            if (surface.rect.contains(x, y)) {
                si = std::size_t(y - surface.rect.y) * surface.rect.w + (x - surface.rect.x);
                owner = surface.instance[si];
                h = surface.height[si];
            }
            Vec3 point = ground_frame(x + 0.5, y + 0.5, h);
            Vec3 n{0, 0, 1};  // the ground
            if (owner >= 0) {
                // The sprite's own surface nearest the point. Its height is whole
                // pixels (a height map), so the point may sit a fraction of a
                // pixel inside its solid, where a grazing segment would run
                // inside it for pixels and shade it (bands of "acne" on curved
                // surfaces): it is moved out along the normal, just past the
                // surface. A point truly facing away still shades itself.
                double best = 1e300;
                const Solid* nearest = nullptr;
                for (std::size_t k = 0; k < solids.solids.size(); ++k) {
                    if (solids.instance[k] != owner) continue;
                    double d = 0;
                    const Vec3 nk = solid_normal(solids.solids[k], point, &d);
                    if (d < best) best = d, n = nk, nearest = &solids.solids[k];
                }
                if (nearest) {
                    const double out = (solid_contains(*nearest, point) ? best : 0) + surface_lift;
                    point += n * out;
                }
            }
            const Vec3 to_light = light - point;
            if (facing && glm::dot(n, to_light) <= 0) continue;
            const double len = glm::length(to_light);
            if (shaded && owner >= 0) {
                v = std::uint8_t(std::floor(v * lambert(n, point, light) + 0.5));
                if (v == 0) continue;
            }
            if (len <= surface_epsilon) {
                m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] = v;
                continue;
            }
            // From the light down to just short of the surface point.
            const double t_end = 1 - surface_epsilon / len;
            const std::array<Vec3, 2> seg{glm::min(light, point), glm::max(light, point)};
            bool blocked = false;
            for (std::size_t k = 0; k < solids.solids.size() && !blocked; ++k)
                blocked = boxes_meet(seg, solids.bounds[k]) && segment_hits(solids.solids[k], light, point, t_end);
            if (!blocked) m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] = v;
        }
    return m;
}

LightMask exact_line_light(const Mask& obstacles, std::int64_t cx, std::int64_t cy, int a, int b, const Params& p,
                           Rect clip, double dy_scale) {
    LightMask m = unlit_mask(cx, cy, a, b, p, clip, dy_scale);
    for (int y = m.clip.y; y < m.clip.y + m.clip.h; ++y)
        for (int x = m.clip.x; x < m.clip.x + m.clip.w; ++x) {
            bool clear = true;
            for (BresenhamRay r(cx, cy, x, y); clear && !r.done(); r.step())
                clear = !obstacles.get(int(r.x), int(r.y));
            if (clear)
                m.value[std::size_t(y - m.clip.y) * m.clip.w + (x - m.clip.x)] =
                    shaped_falloff(x - cx, y - cy, a, b, p, dy_scale);
        }
    return m;
}

Image lit_difference(const LightTexture& model, const LightTexture& reference) {
    const Rect r = model.rect;
    Image out(r.w, r.h);
    for (int y = 0; y < r.h; ++y)
        for (int x = 0; x < r.w; ++x) {
            auto lit = [&](const LightTexture& t) {
                return t.value(r.x + x, r.y + y, 0) || t.value(r.x + x, r.y + y, 1) || t.value(r.x + x, r.y + y, 2);
            };
            const bool lit_model = lit(model);
            const bool lit_ref = reference.rect.contains(r.x + x, r.y + y) && lit(reference);
            if (lit_model != lit_ref) std::copy_n(lit_model ? lit_only_in_model : lit_only_in_reference, 4, out.at(x, y));
        }
    return out;
}

double reference_work(const World& world, const Scene& scene, Rect rect, Reference ref) {
    const Params& p = scene.params;
    if (ref == Reference::every_pixel) {
        Scene s = scene;
        s.params.rays = Rays::every_pixel;
        s.params.ray_skip = 1;
        return trace_work(s, rect);
    }
    // The lit pixels, and the region the lights' rays cross (as reference_texture).
    double lit_pixels = 0, line_steps = 0;
    Rect region = rect;
    for (const Light& l : scene.lights) {
        const Rect area = light_area(l, p);
        const Rect lit = intersect(area, rect);
        if (l.hidden || lit.empty()) continue;
        lit_pixels += double(lit.w) * double(lit.h);
        line_steps += double(lit.w) * double(lit.h) * (std::max(area.w, area.h) / 4.0);  // the mean line's steps
        region = bounding(region, area);
    }
    if (ref == Reference::exact_line) return line_steps;
    // Each lit pixel's segment is tested against every overlay's solid near the region.
    int tallest = 0;
    for (const Sprite& s : world.tileset.sprites) tallest = std::max(tallest, std::max(s.image.width, s.image.height));
    const Rect reach{region.x - tallest, region.y - tallest, region.w + 2 * tallest, region.h + 2 * tallest};
    double overlays = 0;
    for (std::size_t i = world.placed.first_overlay; i < world.placed.instances.size(); ++i) {
        const SpriteInstance& in = world.placed.instances[i];
        overlays += !intersect(Rect{in.x, in.y, in.w, in.h}, reach).empty();
    }
    return lit_pixels * (1 + overlays);
}

LightTexture reference_texture(const World& world, const Scene& scene, Rect rect, Reference ref,
                               bool opacity_correction) {
    Params p = scene.params;
    p.mode = p.mode == Mode::flat ? Mode::flat : Mode::light;
    if (ref == Reference::every_pixel) {
        FrameState st;
        st.options.margin = 0;
        st.options.opacity_correction = opacity_correction;
        st.options.cpu_sprites = false;
        st.options.cpu_blur_and_composite = false;
        st.options.grey_when_lights_are = false;  // r, g, b, as the other references
        Scene s = scene;
        s.params = p;
        s.params.rays = Rays::every_pixel;
        s.params.ray_skip = 1;
        s.params.trace_every = 1;
        render_frame(st, world, s, Camera{double(rect.x), double(rect.y), rect.w, rect.h}, 0);
        return st.traced;
    }
    LightTexture tex(rect);
    // The lights that meet the rectangle, and the region their rays cross.
    std::vector<const Light*> lights;
    Rect region = rect;
    for (const Light& l : scene.lights) {
        const Rect area = light_area(l, p);
        if (l.hidden || intersect(area, rect).empty()) continue;
        lights.push_back(&l);
        const Rect u = region;
        const int x0 = std::min(u.x, area.x), y0 = std::min(u.y, area.y);
        region = {x0, y0, std::max(u.x + u.w, area.x + area.w) - x0, std::max(u.y + u.h, area.y + area.h) - y0};
    }
    if (lights.empty()) return tex;
    Mask obstacles;
    Surface surface;
    WorldSolids solids;
    if (ref == Reference::exact_line) {
        if (p.mode != Mode::flat) obstacles = build_obstacle_map(world.tileset, world.placed, p, region);
    } else {
        surface = build_surface(world, rect, p.opacity_threshold);
        // Solids as tall as a sprite can cast into the rectangle from beyond it.
        int tallest = 0;
        for (const Sprite& s : world.tileset.sprites) tallest = std::max(tallest, std::max(s.image.width, s.image.height));
        solids = world_solids(world, Rect{region.x - tallest, region.y - tallest, region.w + 2 * tallest,
                                          region.h + 2 * tallest});
    }
    const double dy_scale = falloff_dy_scale(p, world.tileset.tile_width, world.tileset.tile_height);
    for (const Light* l : lights) {
        const std::int64_t cx = std::int64_t(std::floor(l->x)), cy = std::int64_t(std::floor(l->y));
        const int a = light_a(*l, p), b = light_b(*l, p);
        LightMask m = ref == Reference::exact_line
                          ? exact_line_light(obstacles, cx, cy, a, b, p, rect, dy_scale)
                          : truth_light(surface, solids, cx, cy, light_height(*l, p), a, b, p, rect,
                                        ref == Reference::three_d_facing, dy_scale, ref == Reference::three_d_shaded);
        accumulate_light(tex, m, *l, p);
    }
    return tex;
}

}  // namespace isolux
