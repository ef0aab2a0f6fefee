#include "isolux/params.hpp"

#include <cmath>
#include <string>

#include "isolux/error.hpp"

namespace isolux {

namespace {
void check_int(std::string_view source, const char* field, int v, int lo, int hi) {
    if (v < lo || v > hi)
        throw Error(std::string(source) + ": " + field + " = " + std::to_string(v) +
                    " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}
void check_real(std::string_view source, const char* field, double v, double lo, double hi,
                bool open_low = false) {
    bool bad = !std::isfinite(v) || v > hi || (open_low ? v <= lo : v < lo);
    if (bad)
        throw Error(std::string(source) + ": " + field + " = " + std::to_string(v) +
                    " is out of range " + (open_low ? "(" : "[") + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
}
}  // namespace

void validate(const Params& p, std::string_view source) {
    using L = ParamLimits;
    check_int(source, "delta_y", p.delta_y, 1, L::max_delta_y);
    check_int(source, "noise_window", p.noise_window, 1, L::max_noise_window);
    check_int(source, "ray_skip", p.ray_skip, 1, L::max_ray_skip);
    check_int(source, "trace_every", p.trace_every, 1, L::max_trace_every);
    check_int(source, "area_a", p.area_a, 0, L::max_area);
    check_int(source, "area_b", p.area_b, 0, L::max_area);
    check_real(source, "ambient_clarity", p.ambient_clarity, 0.0, 1.0);
    check_real(source, "opacity_threshold", p.opacity_threshold, 0.0, 1.0);
    check_int(source, "blur_radius", p.blur_radius, 0, L::max_blur_radius);
    check_real(source, "falloff_scale", p.falloff_scale, 0.0, L::max_falloff_scale, true);
}

std::string_view to_string(Mode m) {
    switch (m) {
        case Mode::light: return "light";
        case Mode::shadow: return "shadow";
        case Mode::flat: return "flat";
    }
    return "light";
}

std::string_view to_string(Rays r) { return r == Rays::border ? "border" : "every_pixel"; }

Mode parse_mode(std::string_view s, std::string_view source) {
    if (s == "light") return Mode::light;
    if (s == "shadow") return Mode::shadow;
    if (s == "flat") return Mode::flat;
    throw Error(std::string(source) + ": mode \"" + std::string(s) +
                "\" is not one of light, shadow, flat");
}

Rays parse_rays(std::string_view s, std::string_view source) {
    if (s == "border") return Rays::border;
    if (s == "every_pixel") return Rays::every_pixel;
    throw Error(std::string(source) + ": rays \"" + std::string(s) +
                "\" is not one of border, every_pixel");
}

std::vector<std::string> builtin_preset_names() { return {"paper", "fast", "quality"}; }

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
    if (name == "quality") {
        // The accuracy reference: a ray to every pixel, fresh every frame.
        p.rays = Rays::every_pixel;
        p.ray_skip = 1;
        p.trace_every = 1;
        p.blur_radius = 1;
        return p;
    }
    throw Error("preset \"" + std::string(name) + "\" is not one of paper, fast, quality");
}

}  // namespace isolux
