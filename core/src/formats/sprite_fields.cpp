// The fields a sprite carries beyond its pixels: sprite_fields.hpp.
#include "formats/sprite_fields.hpp"

#include <cstdint>

#include "isolux/error.hpp"
#include "isolux/footprint.hpp"

namespace isolux {

void read_sprite_fields(const Fields& f, Sprite& s) {
    if (f.has("anchor")) {
        const json& a = f.obj["anchor"];
        if (!a.is_array() || a.size() != 2 || !a[0].is_number_integer() || !a[1].is_number_integer())
            f.fail("anchor", "must be [x, y] integers");
        const auto within = [](const json& v) {
            return v.is_number_unsigned() ? v.get<std::uint64_t>() <= std::uint64_t(max_sprite_offset)
                                          : v.get<std::int64_t>() >= -max_sprite_offset &&
                                                v.get<std::int64_t>() <= max_sprite_offset;
        };
        if (!within(a[0]) || !within(a[1]))
            f.fail("anchor", "is too far off the sprite (each coordinate within ±" + std::to_string(max_sprite_offset) + ")");
        s.anchor_x = int(a[0].get<std::int64_t>());
        s.anchor_y = int(a[1].get<std::int64_t>());
    }
    if (f.has("tags")) {
        const json& t = f.obj["tags"];
        if (!t.is_array()) f.fail("tags", "must be an array of strings");
        s.tags.clear();
        for (const json& v : t) {
            if (!v.is_string()) f.fail("tags", "must be an array of strings");
            s.tags.push_back(v.get<std::string>());
        }
    }
    if (f.has("opacity_threshold")) {
        const double th = f.real("opacity_threshold");
        if (th < 0 || th > 1) f.fail("opacity_threshold", "must be in [0, 1]");
        s.opacity_threshold = th;
    }
    if (f.has("footprint")) s.footprint = footprint_from(f.obj["footprint"], f.where + ": footprint");
}

// "auto" | "paper" | "none" | {"mode": ..., "run": [x, y, length],
// "polygon": [[x, y], ...], "shadow_alpha": a, "shadow_luminance": l,
// "ground_tolerance": t, "object": {"foot": [x, y], "height": h}}; a run or
// polygon without a mode sets it.
FootprintSpec footprint_from(const json& j, const std::string& where) {
    FootprintSpec spec;
    auto mode_of = [&](const std::string& m) {
        for (FootprintMode k : {FootprintMode::automatic, FootprintMode::paper, FootprintMode::none, FootprintMode::run,
                                FootprintMode::polygon})
            if (m == to_string(k)) return k;
        throw Error(where + ": \"" + m + "\" is not one of auto, paper, none, run, polygon");
    };
    if (j.is_string()) {
        spec.mode = mode_of(j.get<std::string>());
        if (spec.mode == FootprintMode::run || spec.mode == FootprintMode::polygon)
            throw Error(where + ": " + j.get<std::string>() + " needs an object with its \"" + j.get<std::string>() + "\"");
        return spec;
    }
    check_object(j, where);
    Fields f{j, where};
    if (f.has("mode")) spec.mode = mode_of(f.text("mode"));
    auto unit = [&](const char* k, double& v) {
        if (!f.has(k)) return;
        v = f.real(k);
        if (v < 0 || v > 1) f.fail(k, "must be in [0, 1]");
    };
    unit("shadow_alpha", spec.shadow_alpha);
    unit("shadow_luminance", spec.shadow_luminance);
    unit("ground_tolerance", spec.ground_tolerance);
    auto coord = [&](const json& v, const char* k) {
        if (!v.is_number_integer()) f.fail(k, "must hold integers");
        const long long x = v.get<long long>();
        if (x < -max_sprite_offset || x > max_sprite_offset)
            f.fail(k, "holds a coordinate beyond ±" + std::to_string(max_sprite_offset));
        return int(x);
    };
    if (f.has("run")) {
        const json& r = j["run"];
        if (!r.is_array() || r.size() != 3) f.fail("run", "must be [x, y, length]");
        spec.run_x = coord(r[0], "run");
        spec.run_y = coord(r[1], "run");
        spec.run_length = coord(r[2], "run");
        if (spec.run_length < 1) f.fail("run", "length must be at least 1");
        if (!spec.mode) spec.mode = FootprintMode::run;
    }
    if (f.has("polygon")) {
        const json& poly = j["polygon"];
        if (!poly.is_array() || poly.size() < 3 || poly.size() > 1000) f.fail("polygon", "must be 3 to 1000 [x, y] points");
        for (const json& pt : poly) {
            if (!pt.is_array() || pt.size() != 2) f.fail("polygon", "must be [x, y] points");
            spec.polygon.push_back({coord(pt[0], "polygon"), coord(pt[1], "polygon")});
        }
        if (!spec.mode) spec.mode = FootprintMode::polygon;
    }
    if (f.has("object")) {
        // {"foot": [x, y], "height": h, "model": m}: the user's correction of the estimated solid.
        const json& o = j["object"];
        check_object(o, where + ": object");
        Fields of{o, where + ": object"};
        if (of.has("foot")) {
            const json& ft = o["foot"];
            if (!ft.is_array() || ft.size() != 2) of.fail("foot", "must be [x, y]");
            spec.object_foot = std::pair{coord(ft[0], "object"), coord(ft[1], "object")};
        }
        if (of.has("height")) spec.object_height = int(of.integer("height", 1, max_sprite_offset));
        if (of.has("model")) {
            const std::string m = of.text("model");
            spec.object_model = object_model_named(m);
            if (!spec.object_model) of.fail("model", "\"" + m + "\" is not one of revolution, prism, mound");
        }
    }
    if (spec.mode == FootprintMode::run && spec.run_length < 1) f.fail("run", "is required for mode run");
    if (spec.mode == FootprintMode::polygon && spec.polygon.empty()) f.fail("polygon", "is required for mode polygon");
    return spec;
}

json footprint_json(const FootprintSpec& f) {
    const FootprintSpec defaults;
    json j = json::object();
    if (f.mode) j["mode"] = std::string(to_string(*f.mode));
    if (f.mode == FootprintMode::run) j["run"] = {f.run_x, f.run_y, f.run_length};
    if (f.mode == FootprintMode::polygon) {
        j["polygon"] = json::array();
        for (auto [x, y] : f.polygon) j["polygon"].push_back({x, y});
    }
    if (f.shadow_alpha != defaults.shadow_alpha) j["shadow_alpha"] = f.shadow_alpha;
    if (f.shadow_luminance != defaults.shadow_luminance) j["shadow_luminance"] = f.shadow_luminance;
    if (f.ground_tolerance != defaults.ground_tolerance) j["ground_tolerance"] = f.ground_tolerance;
    if (f.object_foot || f.object_height > 0 || f.object_model) {
        json o = json::object();
        if (f.object_foot) o["foot"] = {f.object_foot->first, f.object_foot->second};
        if (f.object_height > 0) o["height"] = f.object_height;
        if (f.object_model) o["model"] = std::string(to_string(*f.object_model));
        j["object"] = o;
    }
    return j;
}

}  // namespace isolux
