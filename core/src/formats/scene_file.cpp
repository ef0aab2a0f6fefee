// Presets and scenes as JSON: scene_file.hpp.
#include "isolux/scene_file.hpp"

#include <algorithm>
#include <cmath>

#include "isolux/error.hpp"
#include "isolux/file_io.hpp"
#include "isolux/image_file.hpp"
#include "isolux/map.hpp"
#include "formats/json_fields.hpp"

namespace fs = std::filesystem;

namespace isolux {

bool parse_hex_color(std::string_view s, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b) {
    if (!s.empty() && s[0] == '#') s.remove_prefix(1);
    if (s.size() != 6) return false;
    unsigned v[6];
    for (int i = 0; i < 6; ++i) {
        char c = s[i];
        if (c >= '0' && c <= '9') v[i] = unsigned(c - '0');
        else if (c >= 'a' && c <= 'f') v[i] = unsigned(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F') v[i] = unsigned(c - 'A' + 10);
        else return false;
    }
    r = std::uint8_t(v[0] * 16 + v[1]);
    g = std::uint8_t(v[2] * 16 + v[3]);
    b = std::uint8_t(v[4] * 16 + v[5]);
    return true;
}

// Presets

Params preset_from_json(std::string_view text, std::string_view source, std::vector<std::string>* warnings) {
    json j = parse_json(text, source);
    check_object(j, std::string(source));
    Fields f{j, std::string(source)};
    check_schema(f, warnings);
    warn_unknown_params(f, {"schema_version", "name"}, warnings);
    return params_from(f);
}

std::string preset_to_json(const Params& p) {
    json j = params_json(p);
    j["schema_version"] = schema_version;
    return file_text(j);
}

Params load_preset(const fs::path& path, std::vector<std::string>* warnings) {
    return preset_from_json(read_text_file(path), path.string(), warnings);
}

void save_preset(const fs::path& path, const Params& p) {
    validate(p, path.string());
    write_file_atomic(path, preset_to_json(p));
}

// Scenes

namespace {

std::string hex_color(const Light& l) {
    static const char* d = "0123456789abcdef";
    std::string s;
    for (std::uint8_t c : {l.r, l.g, l.b}) {
        s += d[c >> 4];
        s += d[c & 15];
    }
    return s;
}

// "edits": [{"tile": [x, y], "floor": "water"}, {"tile": [x, y], "overlays": ["oak"]}]
std::vector<TileEdit> edits_from(const json& arr, const Fields& scene) {
    if (!arr.is_array()) scene.fail("edits", "must be an array");
    // A tile holds one edit that matters; more than the largest map's worth is not a level.
    constexpr std::size_t max_edits = std::size_t(max_map_tiles);
    if (arr.size() > max_edits) scene.fail("edits", "holds more than " + std::to_string(max_edits) + " entries");
    std::vector<TileEdit> out;
    out.reserve(arr.size());
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string where = scene.where + ": edits[" + std::to_string(i) + "]";
        check_object(arr[i], where);
        Fields ef{arr[i], where};
        for (auto it = arr[i].begin(); it != arr[i].end(); ++it)
            if (it.key() != "tile" && it.key() != "floor" && it.key() != "overlays")
                ef.fail("\"" + it.key() + "\"", "is not a field of an edit (tile, floor, overlays)");
        if (!ef.has("tile")) ef.fail("tile", "is required: [column, row]");
        const json& t = arr[i]["tile"];
        if (!t.is_array() || t.size() != 2 || !t[0].is_number_integer() || !t[1].is_number_integer())
            ef.fail("tile", "must be [column, row], two integers");
        TileEdit e;
        auto coord = [&](const json& v) {
            const long long x = v.is_number_unsigned()
                                    ? (long long)std::min<unsigned long long>(v.get<unsigned long long>(), 1ull << 40)
                                    : v.get<long long>();
            if (x < -max_edit_tile || x > max_edit_tile)
                ef.fail("tile", "= " + std::to_string(x) + " is beyond +-" + std::to_string(max_edit_tile) +
                                    ", the farthest tile a world reaches");
            return std::int64_t(x);
        };
        e.col = coord(t[0]);
        e.row = coord(t[1]);
        if (ef.has("floor")) e.floor = ef.text("floor");
        if (ef.has("overlays")) {
            const json& o = arr[i]["overlays"];
            if (!o.is_array()) ef.fail("overlays", "must be an array of sprite names");
            if (o.size() > 3) ef.fail("overlays", "holds " + std::to_string(o.size()) + " sprites; a tile holds at most 3");
            e.overlays.emplace();
            for (const json& n : o) {
                if (!n.is_string()) ef.fail("overlays", "must hold sprite names (strings)");
                e.overlays->push_back(n.get<std::string>());
            }
        }
        if (!e.floor && !e.overlays) ef.fail("floor, overlays", "are both missing: an edit sets at least one");
        out.push_back(std::move(e));
    }
    return out;
}

json edits_json(const std::vector<TileEdit>& edits) {
    json arr = json::array();
    for (const TileEdit& e : edits) {
        json o{{"tile", {e.col, e.row}}};
        if (e.floor) o["floor"] = *e.floor;
        if (e.overlays) o["overlays"] = *e.overlays;
        arr.push_back(o);
    }
    return arr;
}

}  // namespace

Scene scene_from_json(std::string_view text, std::string_view source, std::vector<std::string>* warnings) {
    json j = parse_json(text, source);
    const std::string src(source);
    check_object(j, src);
    Fields f{j, src};
    check_schema(f, warnings, scene_schema_version);
    f.warn_unknown(
        {"schema_version", "seed", "width", "height", "layout", "tileset", "map", "preset", "lights", "camera", "edits"},
        warnings);
    Scene s;
    if (f.has("seed")) s.seed = f.text("seed");
    // A side is a number of tiles, or "endless" (both sides or neither).
    auto endless_side = [&](const char* k) { return f.has(k) && j[k].is_string(); };
    if (endless_side("width") || endless_side("height")) {
        for (const char* k : {"width", "height"})
            if (!endless_side(k) || j[k].get<std::string>() != "endless")
                f.fail(k, "must be \"endless\" on both sides, or a number of tiles on both (an endless world has no edge in either direction)");
        s.endless = true;
    } else {
        if (f.has("width")) s.width = int(f.integer("width", 1, max_map_side));
        if (f.has("height")) s.height = int(f.integer("height", 1, max_map_side));
        if (!map_size_ok(s.width, s.height))
            f.fail("width", "x height = " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is " +
                                std::to_string((long long)s.width * s.height) + " tiles: " + map_size_rule());
    }
    if (f.has("layout")) s.layout = parse_layout(f.text("layout"), src + ": layout");
    if (f.has("tileset")) s.tileset = f.text("tileset");
    if (f.has("map")) s.map = f.text("map");
    // A Tiled map has its own edge: one meaning for every reader (the CLI,
    // the editor and the C API), so the contradiction is refused here.
    if (s.endless && !s.map.empty())
        f.fail("map", "names a Tiled map, which has its own size, while width and height say \"endless\": drop one of them");
    if (f.has("preset")) {
        const json& p = j["preset"];
        if (p.is_string()) {
            s.params = builtin_preset(p.get<std::string>());
        } else {
            check_object(p, src + ": preset");
            Fields pf{p, src + ": preset"};
            warn_unknown_params(pf, {"name"}, warnings);
            s.params = params_from(pf);
        }
    }
    if (f.has("lights")) {
        const json& arr = j["lights"];
        if (!arr.is_array()) f.fail("lights", "must be an array");
        if (arr.size() > 100000) f.fail("lights", "holds more than 100000 lights");
        for (std::size_t i = 0; i < arr.size(); ++i) {
            std::string where = src + ": lights[" + std::to_string(i) + "]";
            check_object(arr[i], where);
            Fields lf{arr[i], where};
            lf.warn_unknown({"x", "y", "a", "b", "color", "intensity", "height", "name", "hidden", "locked"}, warnings);
            Light l;
            if (!lf.has("x") || !lf.has("y")) lf.fail("x, y", "are required");
            l.x = lf.real("x");
            l.y = lf.real("y");
            if (std::abs(l.x) > 1e15 || std::abs(l.y) > 1e15) lf.fail("x, y", "must be within ±1e15 pixels");
            if (lf.has("a")) l.area_a = int(lf.integer("a", 0, max_area));
            if (lf.has("b")) l.area_b = int(lf.integer("b", 0, max_area));
            if (lf.has("color") && !parse_hex_color(lf.text("color"), l.r, l.g, l.b))
                lf.fail("color", "must be RRGGBB hex, got \"" + lf.text("color") + "\"");
            if (lf.has("intensity")) {
                l.intensity = lf.real("intensity");
                if (l.intensity < 0 || l.intensity > 1000) lf.fail("intensity", "must be in [0, 1000]");
            }
            if (lf.has("height")) {
                const ParamInfo& range = *find_param("light_height");
                l.height = lf.real("height");
                if (*l.height < range.min || *l.height > range.max)
                    lf.fail("height", "must be in " + param_range_text(range) + " pixels");
            }
            if (lf.has("name")) l.name = lf.text("name");
            if (lf.has("hidden")) l.hidden = lf.boolean("hidden");
            if (lf.has("locked")) l.locked = lf.boolean("locked");
            s.lights.push_back(l);
        }
    }
    if (f.has("camera")) {
        const json& c = j["camera"];
        check_object(c, src + ": camera");
        Fields cf{c, src + ": camera"};
        cf.warn_unknown({"x", "y", "width", "height"}, warnings);
        if (cf.has("x")) s.camera.x = cf.real("x");
        if (cf.has("y")) s.camera.y = cf.real("y");
        if (cf.has("width")) s.camera.width = int(cf.integer("width", 0, max_image_side));
        if (cf.has("height")) s.camera.height = int(cf.integer("height", 0, max_image_side));
    }
    if (f.has("edits")) s.edits = edits_from(j["edits"], f);
    return s;
}

std::string scene_to_json(const Scene& s) {
    json lights = json::array();
    for (const Light& l : s.lights) {
        json o{{"x", l.x}, {"y", l.y}, {"color", hex_color(l)}, {"intensity", l.intensity}};
        if (l.area_a) o["a"] = *l.area_a;
        if (l.area_b) o["b"] = *l.area_b;
        if (l.height) o["height"] = *l.height;
        if (!l.name.empty()) o["name"] = l.name;
        if (l.hidden) o["hidden"] = true;
        if (l.locked) o["locked"] = true;
        lights.push_back(o);
    }
    json j{{"schema_version", scene_schema_version},
           {"seed", s.seed},
           {"width", s.endless ? json("endless") : json(s.width)},
           {"height", s.endless ? json("endless") : json(s.height)},
           {"layout", std::string(to_string(s.layout))},
           {"tileset", s.tileset},
           {"preset", params_json(s.params)},
           {"lights", lights},
           {"camera", {{"x", s.camera.x}, {"y", s.camera.y}, {"width", s.camera.width}, {"height", s.camera.height}}}};
    if (!s.edits.empty()) j["edits"] = edits_json(s.edits);
    if (!s.map.empty()) j["map"] = s.map;
    return file_text(j);
}

Scene load_scene(const fs::path& path, std::vector<std::string>* warnings) {
    Scene s = scene_from_json(read_text_file(path), path.string(), warnings);
    if (!s.tileset.empty() && fs::path(s.tileset).is_relative())
        s.tileset = (path.parent_path() / s.tileset).lexically_normal().string();
    if (!s.map.empty() && fs::path(s.map).is_relative())
        s.map = (path.parent_path() / s.map).lexically_normal().string();
    return s;
}

void save_scene(const fs::path& path, const Scene& scene) {
    validate(scene.params, path.string());
    Scene copy = scene;
    for (std::string* file : {&copy.tileset, &copy.map}) {
        if (file->empty()) continue;
        fs::path base = fs::absolute(path).parent_path();
        fs::path rel = fs::absolute(*file).lexically_relative(base);
        if (!rel.empty()) *file = rel.string();
    }
    write_file_atomic(path, scene_to_json(copy));
}

Params preset_named(const std::string& name_or_path, std::vector<std::string>* warnings) {
    const std::vector<std::string> names = builtin_preset_names();
    if (std::find(names.begin(), names.end(), name_or_path) != names.end()) return builtin_preset(name_or_path);
    return load_preset(name_or_path, warnings);
}

}  // namespace isolux
