// The parameter table (params.hpp) and everything that only reads it.
#include "isolux/params.hpp"

#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "isolux/error.hpp"

namespace isolux {

namespace {

constexpr StageSet obstacle_map = stages_from(Stage::obstacle_map);
constexpr StageSet trace = stages_from(Stage::trace);
constexpr StageSet blur = stages_from(Stage::blur);
constexpr StageSet composite = stages_from(Stage::composite);
constexpr StageSet nothing = {};

constexpr const char* obstacle_group = "obstacle map (paper 3.1)";
constexpr const char* trace_group = "tracing (paper 3.2)";
constexpr const char* shade_group = "shading (paper 3.2, Algorithm 3)";

#define ISOLUX_FIELD(f) [](const Params& p) { return double(p.f); }, [](Params& p, double v) { p.f = decltype(p.f)(v); }

// name, flag, old flag, label, symbol, group, type, min, max, min open,
// slider min, slider max, logarithmic, choices, help, re-runs, field.
// In the order the app's Parameters panel shows them: the look a user tunes
// first (Algorithm 3's shading, what stops the rays and how light falls),
// then the tracer's speed knobs, then the obstacle map.
const ParamInfo table[] = {
    {"ambient_clarity", "--ambient-clarity", "--ambient", "ambient clarity", "", shade_group, ParamType::real, 0, 1,
     false, 0, 1, false, {}, "Algorithm 3's ambientClarity: texture x sqrt(c) + luminance x light / (c^2 + 0.1) "
     "(paper 4: 0.4).", composite, ISOLUX_FIELD(ambient_clarity)},
    {"exposure", "--exposure", nullptr, "exposure", "", shade_group, ParamType::real, 0, 16, true, 1.0 / 16, 16,
     true, {}, "Multiplies Algorithm 3's light term (in shadow mode, the shadow subtracted), so how dark the night "
     "is (ambient clarity) and how bright the lamps are are set apart. 1 is the paper's.", composite,
     ISOLUX_FIELD(exposure)},
    {"tone_map", "--tone-map", nullptr, "tone map", "", shade_group, ParamType::choice, 0, 1, false, 0, 1, false,
     {"none", "reinhard_knee"}, "How the composite reaches the screen. none: each channel clamped (the paper). "
     "reinhard_knee: the light's added luminance rolls off into the headroom the texture leaves, so a bright pool "
     "keeps its hue and fades toward white instead of clipping channel by channel; unlit pixels are unchanged.",
     composite, ISOLUX_FIELD(tone_map)},
    {"light_mix", "--light-mix", nullptr, "light mix", "", shade_group, ParamType::choice, 0, 1, false, 0, 1, false,
     {"luminance", "surface"}, "luminance: Algorithm 3 as written, the sprite's luminance times the light (a coloured "
     "light paints its hue). surface: the sprite's colour times the light, so lit sprites keep their hue; shadows "
     "darken instead of blacking out.", composite, ISOLUX_FIELD(light_mix)},
    {"dark_unlit", "--dark-unlit", nullptr, "dark unlit", "", shade_group, ParamType::boolean, 0, 1, false, 0, 1,
     false, {}, "Algorithm 3 variant (paper 4): the texture factor is multiplied by the light, so what no ray "
     "reaches is black.", composite, ISOLUX_FIELD(dark_unlit)},
    {"blur_radius", "--blur-radius", "--blur", "blur radius", "", shade_group, ParamType::integer, 0, 255, false, 0,
     16, false, {}, "Box blur of the light texture, in pixels (paper 3.2).", blur, ISOLUX_FIELD(blur_radius)},
    {"occluders", "--occluders", nullptr, "occluders", "", trace_group, ParamType::choice, 0, 2, false, 0, 2,
     false, {"footprints", "solids", "shapes"}, "What stops the rays. footprints: the paper's obstacle map and "
     "opacity correction; solids: beyond the paper, a solid estimated from each sprite's alpha, the light at its "
     "height, so canopies cast shadows and a higher light casts shorter ones; shapes: the manifest's own shapes the "
     "same way (every overlay needs one). Light and shadow modes.", obstacle_map, ISOLUX_FIELD(occluders)},
    {"occluder_scale", "--occluder-scale", nullptr, "occluder scale", "", trace_group, ParamType::integer, 1, 4,
     false, 1, 4, false, {}, "Beyond the paper, with occluders solids or shapes: both passes traced over an "
     "occluder map this many times coarser (1: full resolution), each pixel lit where its block is; faster, a "
     "little less exact at shadows' edges (docs/accuracy.md measures both).", trace, ISOLUX_FIELD(occluder_scale)},
    {"sprite_shading", "--sprite-shading", nullptr, "sprite shading", "", trace_group, ParamType::choice, 0, 3, false,
     0, 3, false, {"none", "solids", "shapes", "luminance"}, "Beyond the paper: a sprite pixel's light from each light "
     "times the Lambert term between its surface's normal and the direction to the light (at its height). none: flat "
     "(the paper); solids: the normals of the solids estimated from the sprites; shapes: the manifest's shapes or "
     "height maps (every overlay needs one); luminance: from the picture's brightness, as normal-map generators do.",
     trace, ISOLUX_FIELD(sprite_shading)},
    {"shading_strength", "--shading-strength", nullptr, "shading strength", "", trace_group, ParamType::real, 0, 1,
     false, 0, 1, false, {}, "How much of the sprite shading applies: 0 the flat light, 1 the whole Lambert term, "
     "between them a blend. With sprite_shading.", trace, ISOLUX_FIELD(shading_strength)},
    {"mode", "--mode", nullptr, "mode", "", trace_group, ParamType::choice, 0, 2, false, 0, 2, false,
     {"light", "shadow", "flat"}, "light: rays stop at obstacles (the paper). shadow: paint what lies beyond the "
     "first obstacle (paper 4). flat: no obstacles, falloff only (Figure 10b).", trace, ISOLUX_FIELD(mode)},
    {"area_a", "--area-a", nullptr, "area a", "a", trace_group, ParamType::integer, 0, max_area, false, 0, 512, false,
     {}, "A light's half-width in pixels; its area is (2a+1) x (2b+1) (paper 3.2).", trace, ISOLUX_FIELD(area_a)},
    {"area_b", "--area-b", nullptr, "area b", "b", trace_group, ParamType::integer, 0, max_area, false, 0, 512, false,
     {}, "A light's half-height in pixels (paper 3.2).", trace, ISOLUX_FIELD(area_b)},
    {"falloff_scale", "--falloff-scale", nullptr, "falloff scale", "", trace_group, ParamType::real, 0, 1e6, true,
     0.25, 64, true, {}, "i = 255 / (1 + max(|dx|,|dy|) / falloff scale). 1 is the paper's function; larger spreads "
     "the light.", trace, ISOLUX_FIELD(falloff_scale)},
    {"falloff_shape", "--falloff-shape", nullptr, "falloff shape", "", trace_group, ParamType::choice, 0, 1, false, 0,
     1, false, {"chebyshev", "euclidean"}, "How the intensity falls with distance d: chebyshev, d = max(|dx|,|dy|), the "
     "paper's (square lights); euclidean, d = sqrt(dx^2 + dy^2) (round lights).", trace, ISOLUX_FIELD(falloff_shape)},
    {"falloff_space", "--falloff-space", nullptr, "falloff space", "", trace_group, ParamType::choice, 0, 1, false, 0,
     1, false, {"screen", "ground"}, "Where d is measured: screen, from the screen offset (the paper); ground, on the "
     "ground, dy scaled by the tile width over its height r (a round light is an ellipse r times as wide as tall).",
     trace, ISOLUX_FIELD(falloff_space)},
    {"edge_fade", "--edge-fade", nullptr, "edge fade", "", trace_group, ParamType::boolean, 0, 1, false, 0, 1, false,
     {}, "The intensity falls to 0 at the area's border instead of being cut there (no straight edge).", trace,
     ISOLUX_FIELD(edge_fade)},
    {"fade_curve", "--fade-curve", nullptr, "fade curve", "", trace_group, ParamType::choice, 0, 1, false, 0, 1, false,
     {"linear", "smooth"}, "The edge fade along a ray, t the share of the way to the border: linear, 1 - t (its "
     "slope jumps at the border: a ring); smooth, 1 - 3t^2 + 2t^3 (its slope 0 at the border). With edge_fade.",
     trace, ISOLUX_FIELD(fade_curve)},
    {"light_height", "--light-height", nullptr, "light height", "", trace_group, ParamType::real, 0, 4096, false, 0,
     256, false, {}, "A light's height above the ground in pixels, for lights that give none. The paper's model "
     "ignores it; the 3D reference and the height options use it.", trace, ISOLUX_FIELD(light_height)},
    {"ray_skip", "--ray-skip", nullptr, "ray skip", "k", trace_group, ParamType::integer, 1, 1 << 20, false, 1, 32,
     true, {}, "Trace every k-th border ray; the gaps of skipped rays are blurred (paper 3.2).", trace,
     ISOLUX_FIELD(ray_skip)},
    {"trace_every", "--trace-every", nullptr, "l frames", "l", trace_group, ParamType::integer, 1, 10000, false, 1, 30,
     false, {}, "Rays are traced once every l frames; in between the light texture is shifted with the camera "
     "(paper 3.2). Walk the character (WASD) to see it.", nothing, ISOLUX_FIELD(trace_every)},
    {"rays", "--rays", nullptr, "rays", "", trace_group, ParamType::choice, 0, 1, false, 0, 1, false,
     {"border", "every_pixel"}, "border: a ray to each border pixel (Algorithm 2). every_pixel: a ray to every pixel "
     "of the area, the paper's 4ab rays; the accuracy reference, slow.", trace, ISOLUX_FIELD(rays)},
    {"rays_over_obstacles", "--rays-over-obstacles", nullptr, "rays over obstacles", "", trace_group,
     ParamType::boolean, 0, 1, false, 0, 1, false, {}, "Beyond the paper: a ray passes over an obstacle lower than "
     "the ray at that point (heights estimated from each sprite's opaque rows, the light at its height), so low "
     "sprites cast shadows of finite length. Light and flat modes; with occluders footprints only.", obstacle_map,
     ISOLUX_FIELD(rays_over_obstacles)},
    {"delta_y", "--delta-y", nullptr, "delta y", "Δy", obstacle_group, ParamType::integer, 1, 4096, false, 1, 128,
     false, {}, "How many rows Algorithm 1 reads on each sprite, ending at its lowest opaque row (paper 3.1: 25 for "
     "128-px sprites).", obstacle_map, ISOLUX_FIELD(delta_y)},
    {"noise_window", "--noise-window", nullptr, "noise window", "n", obstacle_group, ParamType::integer, 1, 255, false,
     1, 16, false, {}, "The box noise filter's window: a pixel is cleared when its n x n window holds fewer than n "
     "obstacle pixels (paper 3.1).", obstacle_map, ISOLUX_FIELD(noise_window)},
    {"opacity_threshold", "--opacity-threshold", nullptr, "opacity threshold", "", obstacle_group, ParamType::real, 0,
     1, false, 0, 1, false, {}, "Alpha above this is opaque, for the opacity maps and Algorithm 1.", obstacle_map,
     ISOLUX_FIELD(opacity_threshold)},
    {"footprint", "--footprint", nullptr, "footprint", "", obstacle_group, ParamType::choice, 0, 1, false, 0, 1,
     false, {"auto", "paper"}, "Where sprites meet the ground, for sprites whose manifest sets none. auto: "
     "Algorithm 1 after taking out a baked ground diamond and baked shadows; paper: Algorithm 1 as written.",
     obstacle_map, ISOLUX_FIELD(footprint)},
};

#undef ISOLUX_FIELD

std::string number(double x) {
    if (x == std::floor(x) && std::abs(x) < 1e15) return std::to_string((long long)x);  // 10000, not 1e+04
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    // The shortest text that reads back to the same double.
    for (int digits = 1; digits <= 17; ++digits) {
        char b[32];
        std::snprintf(b, sizeof b, "%.*g", digits, x);
        if (std::strtod(b, nullptr) == x) return b;
    }
    return buf;
}

}  // namespace

std::span<const ParamInfo> param_table() { return table; }

const ParamInfo* find_param(std::string_view name) {
    for (const ParamInfo& info : table)
        if (name == info.name) return &info;
    return nullptr;
}

double param_default(const ParamInfo& info) { return info.get(Params{}); }

int choice_count(const ParamInfo& info) {
    int n = 0;
    while (n < int(info.choices.size()) && info.choices[n]) ++n;
    return n;
}

std::string param_range_text(const ParamInfo& info) {
    switch (info.type) {
        case ParamType::choice: {
            std::string s;
            for (int i = 0; i < choice_count(info); ++i) {
                if (i) s += ", ";
                s += info.choices[i];
            }
            return s;
        }
        case ParamType::boolean: return "true, false";
        default: {
            std::string s(info.min_open ? "(" : "[");
            s += number(info.min);
            s += ", ";
            s += number(info.max);
            s += "]";
            return s;
        }
    }
}

void check_param(const ParamInfo& info, double v, std::string_view source) {
    const bool in_range = std::isfinite(v) && v <= info.max && (info.min_open ? v > info.min : v >= info.min);
    const bool whole = info.type == ParamType::real || v == std::floor(v);
    if (in_range && whole) return;
    const std::string where = std::string(source) + ": " + info.name;
    if (info.type == ParamType::choice || info.type == ParamType::boolean)
        throw Error(where + " = " + number(v) + " is not one of " + param_range_text(info));
    throw Error(where + " = " + number(v) + " is out of range " + param_range_text(info));
}

void validate(const Params& p, std::string_view source) {
    for (const ParamInfo& info : table) check_param(info, info.get(p), source);
}

std::string format_param(const ParamInfo& info, double v) {
    switch (info.type) {
        case ParamType::choice: {
            const int i = int(v);
            return i >= 0 && i < choice_count(info) ? info.choices[i] : number(v);
        }
        case ParamType::boolean: return v != 0 ? "true" : "false";
        default: return number(v);
    }
}

double parse_param(const ParamInfo& info, std::string_view text, std::string_view source) {
    const std::string where = std::string(source) + ": " + info.name;
    const std::string t(text);
    double v = 0;
    switch (info.type) {
        case ParamType::choice: {
            for (int i = 0; i < choice_count(info); ++i)
                if (t == info.choices[i]) return i;
            throw Error(where + " \"" + t + "\" is not one of " + param_range_text(info));
        }
        case ParamType::boolean:
            if (t == "true" || t == "1") return 1;
            if (t == "false" || t == "0") return 0;
            throw Error(where + ": \"" + t + "\" is not true or false");
        case ParamType::integer: {
            std::size_t used = 0;
            long long x = 0;
            try {
                x = std::stoll(t, &used);
            } catch (...) {
                used = 0;
            }
            if (t.empty() || used != t.size()) throw Error(where + ": \"" + t + "\" is not an integer");
            v = x < -1e15 || x > 1e15 ? double(x > 0 ? 1e15 : -1e15) : double(x);
            break;
        }
        case ParamType::real: {
            // strtod, not stod: stod refuses denormals such as 5e-324
            char* end = nullptr;
            v = std::strtod(t.c_str(), &end);
            const std::size_t used = std::size_t(end - t.c_str());
            if (t.empty() || std::isspace((unsigned char)t[0]) || used != t.size() || !std::isfinite(v))
                throw Error(where + ": \"" + t + "\" is not a number");
            break;
        }
    }
    check_param(info, v, source);
    return v;
}

StageSet stages_changed(const Params& a, const Params& b) {
    StageSet s;
    for (const ParamInfo& info : table)
        if (info.get(a) != info.get(b)) s = s | info.reruns;
    return s;
}

std::string_view to_string(Mode m) { return find_param("mode")->choices[std::size_t(m)]; }

std::string_view to_string(Rays r) { return find_param("rays")->choices[std::size_t(r)]; }

Mode parse_mode(std::string_view s, std::string_view source) {
    return Mode(int(parse_param(*find_param("mode"), s, source)));
}

Rays parse_rays(std::string_view s, std::string_view source) {
    return Rays(int(parse_param(*find_param("rays"), s, source)));
}

std::vector<std::string> param_names() {
    std::vector<std::string> names;
    for (const ParamInfo& info : table) names.emplace_back(info.name);
    return names;
}

void set_param(Params& p, std::string_view name, std::string_view value, std::string_view source) {
    const ParamInfo* info = find_param(name);
    if (!info) throw Error(std::string(source) + ": unknown parameter \"" + std::string(name) + "\"");
    info->set(p, parse_param(*info, value, source));
}

std::string get_param(const Params& p, std::string_view name) {
    const ParamInfo* info = find_param(name);
    return info ? format_param(*info, info->get(p)) : "";
}

std::vector<std::string> builtin_preset_names() { return {"paper", "fast", "quality", "game"}; }

std::string builtin_preset_summary(std::string_view name) {
    if (name == "paper")
        return "paper: the paper's own settings: square falloff 255 / (1 + d) cut at the area's border, d in pixels "
               "(a small bright spot: raise falloff_scale or pick the game preset for wider light)";
    if (name == "fast") return "fast: half the border rays, a retrace every 4 frames, blurred";
    if (name == "quality") return "quality: a ray to every pixel, traced every frame";
    if (name == "game")
        return "game: round lights on the ground fading smoothly to their border, shadows from solids estimated from the "
               "sprites, sprites shaded by the way those solids face each light and keeping their colour, bright pools "
               "rolled off instead of burnt to white, soft blur";
    return "";
}

Params builtin_preset(std::string_view name) {
    Params p;
    if (name == "paper") return p;
    if (name == "fast") {
        // Half the border rays, retrace every 4 frames, blur hides the gaps.
        p.ray_skip = 2;
        p.trace_every = 4;
        p.blur_radius = 2;
        return p;
    }
    if (name == "game") {
        // A look for games: round, wide lights that fade out before their
        // border, lit sprites keeping their hue, and shadows from solids
        // estimated from the sprites (what measures closest to 3D on the
        // ground and on the sprites: docs/accuracy.md).
        p.occluders = Occluders::solids;
        p.falloff_shape = FalloffShape::euclidean;
        // Pools that lie on the ground: distances measured there, and the
        // area's box b = a / r around the ellipse a round light makes (r = 2,
        // the default tileset's 128 x 64 diamonds and most isometric art's).
        p.falloff_space = FalloffSpace::ground;
        p.area_b = p.area_a / 2;
        p.edge_fade = true;
        p.fade_curve = FadeCurve::smooth;
        p.falloff_scale = 12;
        p.light_mix = LightMix::surface;
        p.blur_radius = 3;
        // Bright pools roll off toward their colour instead of clipping each
        // channel to white (composite.hpp's tone_knee).
        p.tone_map = ToneMap::reinhard_knee;
        // Sprites shaded by the way the estimated solids face each light:
        // of none, solids and luminance the nearest to the shaded 3D truth
        // on every scene of docs/accuracy.md (shapes needs the manifest's).
        p.sprite_shading = SpriteShading::solids;
        return p;
    }
    if (name == "quality") {
        // The accuracy reference: a ray to every pixel, fresh every frame.
        p.rays = Rays::every_pixel;
        p.ray_skip = 1;
        p.trace_every = 1;
        p.blur_radius = 1;
        return p;
    }
    throw Error("preset \"" + std::string(name) + "\" is not one of paper, fast, quality, game");
}

}  // namespace isolux
