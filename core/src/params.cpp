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

std::vector<std::string> param_names() {
    return {"delta_y", "noise_window", "ray_skip", "trace_every", "area_a", "area_b", "ambient_clarity",
            "opacity_threshold", "blur_radius", "falloff_scale", "mode", "dark_unlit", "rays"};
}

void set_param(Params& p, std::string_view name, std::string_view value, std::string_view source) {
    const std::string where = std::string(source) + ": " + std::string(name);
    const std::string v(value);
    auto as_int = [&]() {
        std::size_t used = 0;
        long long x = 0;
        try {
            x = std::stoll(v, &used);
        } catch (...) {
            used = 0;
        }
        if (used != v.size() || v.empty() || x < -1000000000LL || x > 1000000000LL)
            throw Error(where + ": \"" + v + "\" is not an integer");
        return int(x);
    };
    auto as_real = [&]() {
        std::size_t used = 0;
        double x = 0;
        try {
            x = std::stod(v, &used);
        } catch (...) {
            used = 0;
        }
        if (used != v.size() || v.empty() || !std::isfinite(x)) throw Error(where + ": \"" + v + "\" is not a number");
        return x;
    };
    Params q = p;
    if (name == "delta_y") q.delta_y = as_int();
    else if (name == "noise_window") q.noise_window = as_int();
    else if (name == "ray_skip") q.ray_skip = as_int();
    else if (name == "trace_every") q.trace_every = as_int();
    else if (name == "area_a") q.area_a = as_int();
    else if (name == "area_b") q.area_b = as_int();
    else if (name == "ambient_clarity") q.ambient_clarity = as_real();
    else if (name == "opacity_threshold") q.opacity_threshold = as_real();
    else if (name == "blur_radius") q.blur_radius = as_int();
    else if (name == "falloff_scale") q.falloff_scale = as_real();
    else if (name == "mode") q.mode = parse_mode(v, where);
    else if (name == "rays") q.rays = parse_rays(v, where);
    else if (name == "dark_unlit") {
        if (v != "true" && v != "false" && v != "1" && v != "0") throw Error(where + ": \"" + v + "\" is not true or false");
        q.dark_unlit = v == "true" || v == "1";
    } else {
        throw Error(std::string(source) + ": unknown parameter \"" + std::string(name) + "\"");
    }
    validate(q, source);
    p = q;
}

std::string get_param(const Params& p, std::string_view name) {
    auto real = [](double x) {
        std::string s = std::to_string(x);
        while (!s.empty() && s.back() == '0') s.pop_back();
        if (!s.empty() && s.back() == '.') s.pop_back();
        return s;
    };
    if (name == "delta_y") return std::to_string(p.delta_y);
    if (name == "noise_window") return std::to_string(p.noise_window);
    if (name == "ray_skip") return std::to_string(p.ray_skip);
    if (name == "trace_every") return std::to_string(p.trace_every);
    if (name == "area_a") return std::to_string(p.area_a);
    if (name == "area_b") return std::to_string(p.area_b);
    if (name == "ambient_clarity") return real(p.ambient_clarity);
    if (name == "opacity_threshold") return real(p.opacity_threshold);
    if (name == "blur_radius") return std::to_string(p.blur_radius);
    if (name == "falloff_scale") return real(p.falloff_scale);
    if (name == "mode") return std::string(to_string(p.mode));
    if (name == "rays") return std::string(to_string(p.rays));
    if (name == "dark_unlit") return p.dark_unlit ? "true" : "false";
    return "";
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
