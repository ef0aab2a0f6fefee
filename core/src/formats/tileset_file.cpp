// Tileset manifests as JSON: tileset_file.hpp.
#include "isolux/tileset_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>

#include "isolux/error.hpp"
#include "isolux/file_io.hpp"
#include "isolux/footprint.hpp"
#include "isolux/image_file.hpp"
#include "isolux/scene_file.hpp"
#include "formats/json_fields.hpp"
#include "formats/sprite_fields.hpp"

namespace fs = std::filesystem;

namespace isolux {

namespace {

// A shape stands where its sprite is drawn: the ground its solids stand
// over (their ground boxes, summed) may reach 16 times the sprite's image,
// and no further. Tracing against shapes fills each box at each instance, so
// a shape of huge solids would make every frame take minutes.
void check_shape_ground(const std::vector<Solid>& shape, Rect image, const Fields& sf) {
    const double most = std::max(16.0 * image.w * image.h, 65536.0);
    double ground = 0;
    for (const Solid& s : shape) {
        const auto g = ground_box(s);
        ground += double(g[2]) * double(g[3]);
    }
    if (ground > most) {
        char text[160];
        std::snprintf(text, sizeof text, "covers %.3g pixels of ground, over the %.3g its %dx%d image allows (16 times "
                                         "its pixels): a shape stands where its sprite is drawn",
                      ground, most, image.w, image.h);
        sf.fail("shape", text);
    }
}

// A sprite's solids: [{"kind": "box", "min": [x,y,z], "max": [x,y,z]},
// {"kind": "cylinder"|"cone", "base": [x,y,z], "radius": r, "height": h},
// {"kind": "ellipsoid", "center": [x,y,z], "radii": [x,y,z]}].
std::vector<Solid> shape_from(const json& arr, const std::string& where) {
    if (!arr.is_array()) throw Error(where + ": must be an array of solids");
    if (arr.size() > 1000) throw Error(where + ": holds more than 1000 solids");
    std::vector<Solid> out;
    for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string at = where + "[" + std::to_string(i) + "]";
        check_object(arr[i], at);
        Fields f{arr[i], at};
        auto vec = [&](const char* k) {
            if (!f.has(k)) f.fail(k, "is required");
            const json& v = arr[i][k];
            if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); }))
                f.fail(k, "must be [x, y, z] numbers");
            Vec3 r{v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
            if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || std::abs(r.x) > 1e6 ||
                std::abs(r.y) > 1e6 || std::abs(r.z) > 1e6)
                f.fail(k, "must be finite numbers within ±1e6");
            return r;
        };
        auto size = [&](const char* k) {
            if (!f.has(k)) f.fail(k, "is required");
            const double v = f.real(k);
            if (v < 0 || v > 1e6) f.fail(k, "= " + std::to_string(v) + " must be in [0, 1e6]");
            return v;
        };
        if (!f.has("kind")) f.fail("kind", "is required (box, cylinder, cone or ellipsoid)");
        const std::string kind = f.text("kind");
        Solid s;
        if (kind == "box") {
            s.kind = SolidKind::box;
            s.a = vec("min");
            s.b = vec("max");
            if (s.b.x < s.a.x || s.b.y < s.a.y || s.b.z < s.a.z) f.fail("max", "must not be below min (a negative size)");
        } else if (kind == "cylinder" || kind == "cone") {
            s.kind = kind == "cone" ? SolidKind::cone : SolidKind::cylinder;
            s.a = vec("base");
            const double r = size("radius");
            s.b = {r, r, size("height")};
        } else if (kind == "ellipsoid") {
            s.kind = SolidKind::ellipsoid;
            s.a = vec("center");
            s.b = vec("radii");
            if (s.b.x < 0 || s.b.y < 0 || s.b.z < 0) f.fail("radii", "must not be negative");
        } else {
            f.fail("kind", "\"" + kind + "\" is unknown (use box, cylinder, cone or ellipsoid)");
        }
        out.push_back(s);
    }
    return out;
}

json shape_json(const std::vector<Solid>& shape) {
    json arr = json::array();
    auto v = [](Vec3 p) { return json::array({p.x, p.y, p.z}); };
    for (const Solid& s : shape) {
        switch (s.kind) {
            case SolidKind::box: arr.push_back({{"kind", "box"}, {"min", v(s.a)}, {"max", v(s.b)}}); break;
            case SolidKind::cylinder:
            case SolidKind::cone:
                arr.push_back({{"kind", std::string(to_string(s.kind))}, {"base", v(s.a)}, {"radius", s.b.x}, {"height", s.b.z}});
                break;
            case SolidKind::ellipsoid: arr.push_back({{"kind", "ellipsoid"}, {"center", v(s.a)}, {"radii", v(s.b)}}); break;
        }
    }
    return arr;
}

}  // namespace

Tileset load_tileset(const fs::path& manifest) {
    const std::string src = manifest.string();
    json j = parse_json(read_text_file(manifest), src);
    check_object(j, src);
    Fields f{j, src};
    check_schema(f, nullptr);
    Tileset ts;
    ts.source = src;
    if (f.has("tile")) {
        const json& t = j["tile"];
        check_object(t, src + ": tile");
        Fields tf{t, src + ": tile"};
        if (tf.has("width")) ts.tile_width = int(tf.integer("width", 2, 4096));
        if (tf.has("height")) ts.tile_height = int(tf.integer("height", 2, 4096));
    }
    if (!f.has("sprites") || !j["sprites"].is_array()) f.fail("sprites", "must be an array of sprites");
    const json& arr = j["sprites"];
    std::map<fs::path, Image> sheets;  // ordered: loading order does not depend on hashing
    std::int64_t total_pixels = 0;     // every sprite's image, and every sheet, against max_input_sprite_pixels
    for (std::size_t i = 0; i < arr.size(); ++i) {
        std::string where = src + ": sprites[" + std::to_string(i) + "]";
        check_object(arr[i], where);
        Fields sf{arr[i], where};
        Sprite s;
        if (!sf.has("name")) sf.fail("name", "is required");
        s.name = sf.text("name");
        where += " (\"" + s.name + "\")";
        sf.where = where;
        if (!sf.has("image")) sf.fail("image", "is required");
        fs::path image_path = manifest.parent_path() / sf.text("image");
        auto it = sheets.find(image_path);
        if (it == sheets.end()) {
            try {
                it = sheets.emplace(image_path, load_image(image_path)).first;
                total_pixels += std::int64_t(it->second.width) * it->second.height;
            } catch (const Error& e) {
                throw Error(where + ": image: " + e.what());
            }
        }
        const Image& sheet = it->second;
        Rect rect{0, 0, sheet.width, sheet.height};
        if (sf.has("rect")) {
            const json& r = arr[i]["rect"];
            if (!r.is_array() || r.size() != 4 || !std::all_of(r.begin(), r.end(), [](const json& v) { return v.is_number_integer(); }))
                sf.fail("rect", "must be [x, y, w, h] integers");
            // Read wide and checked in 64 bits: no value wraps, no sum overflows.
            std::int64_t v[4];
            for (int k = 0; k < 4; ++k) {
                if (r[std::size_t(k)].is_number_unsigned() && r[std::size_t(k)].get<std::uint64_t>() > std::uint64_t(INT64_MAX))
                    sf.fail("rect", "holds a value beyond 64 bits");
                v[k] = r[std::size_t(k)].get<std::int64_t>();
            }
            if (v[2] <= 0 || v[3] <= 0) sf.fail("rect", "has zero size: zero-size sprite");
            if (v[0] < 0 || v[1] < 0 || v[0] > sheet.width || v[1] > sheet.height || v[2] > sheet.width ||
                v[3] > sheet.height || v[0] + v[2] > sheet.width || v[1] + v[3] > sheet.height)
                sf.fail("rect", "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
                                    ", " + std::to_string(v[3]) + "] lies outside " + image_path.filename().string() + " (" +
                                    std::to_string(sheet.width) + "x" + std::to_string(sheet.height) + ")");
            rect = {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
            if (rect.x + rect.w > sheet.width || rect.y + rect.h > sheet.height)
                sf.fail("rect", "[" + std::to_string(rect.x) + ", " + std::to_string(rect.y) + ", " +
                                    std::to_string(rect.w) + ", " + std::to_string(rect.h) + "] lies outside " +
                                    image_path.filename().string() + " (" + std::to_string(sheet.width) + "x" +
                                    std::to_string(sheet.height) + ")");
        }
        total_pixels += std::int64_t(rect.w) * rect.h;
        if (total_pixels > max_input_sprite_pixels)
            sf.fail("rect", "brings the sprites' images to " + std::to_string(total_pixels >> 20) +
                                " megapixels, over the " + std::to_string(max_input_sprite_pixels >> 20) +
                                " a tileset may load (give each sprite its own rect on the sheet)");
        s.image = Image(rect.w, rect.h);
        for (int y = 0; y < rect.h; ++y)
            std::copy_n(sheet.at(rect.x, rect.y + y), std::size_t(rect.w) * 4, s.image.at(0, y));
        if (!sheet.alpha16.empty()) {
            s.image.alpha16.resize(std::size_t(rect.w) * rect.h);
            for (int y = 0; y < rect.h; ++y)
                std::copy_n(&sheet.alpha16[std::size_t(rect.y + y) * sheet.width + rect.x], std::size_t(rect.w),
                            &s.image.alpha16[std::size_t(y) * rect.w]);
        }
        if (!sf.has("kind")) sf.fail("kind", "is required (floor or overlay)");
        std::string kind = sf.text("kind");
        if (kind == "floor") s.kind = SpriteKind::floor;
        else if (kind == "overlay") s.kind = SpriteKind::overlay;
        else sf.fail("kind", "\"" + kind + "\" is unknown (use floor or overlay)");
        // The default anchor: floors at the diamond's centre with the diamond
        // at the sprite's top; overlays standing on the sprite's bottom centre.
        s.anchor_x = rect.w / 2;
        s.anchor_y = s.kind == SpriteKind::floor ? ts.tile_height / 2 : rect.h - 1;
        read_sprite_fields(sf, s);
        total_pixels += footprint_pixels(rect.w, rect.h, s.footprint);
        if (total_pixels > max_input_sprite_pixels)
            sf.fail("footprint", "brings the sprites' images and footprints to " + std::to_string(total_pixels >> 20) +
                                     " megapixels, over the " + std::to_string(max_input_sprite_pixels >> 20) +
                                     " a tileset may load (Algorithm 1 marks a run's quarter above and below it: a "
                                     "sprite W pixels wide may need W x W/2)");
        if (sf.has("height_map")) {
            try {
                s.height = load_gray16(manifest.parent_path() / sf.text("height_map"), rect.w, rect.h);
            } catch (const Error& e) {
                throw Error(where + ": height_map: " + e.what());
            }
        }
        if (sf.has("shape")) {
            s.shape = shape_from(arr[i]["shape"], where + ": shape");
            check_shape_ground(s.shape, rect, sf);
        }
        ts.sprites.push_back(std::move(s));
    }
    validate(ts);
    return ts;
}

FootprintSpec parse_footprint(std::string_view text, std::string_view source) {
    return footprint_from(parse_json(text, source), std::string(source));
}

std::string footprint_to_json(const FootprintSpec& spec) {
    const json j = footprint_json(spec);
    return j.empty() ? "" : j.dump(-1, ' ', false, json::error_handler_t::replace);
}

void save_manifest_footprints(const fs::path& manifest, const Tileset& ts) {
    const std::string src = manifest.string();
    json j = parse_json(read_text_file(manifest), src);
    check_object(j, src);
    if (!j.contains("sprites") || !j["sprites"].is_array() || j["sprites"].size() != ts.sprites.size())
        throw Error(src + ": sprites no longer match the loaded tileset: reload it before saving footprints");
    for (std::size_t i = 0; i < ts.sprites.size(); ++i) {
        json& entry = j["sprites"][i];
        if (!entry.is_object() || !entry.contains("name") || entry["name"] != ts.sprites[i].name)
            throw Error(src + ": sprites[" + std::to_string(i) + "] is no longer \"" + ts.sprites[i].name + "\"");
        const json f = footprint_json(ts.sprites[i].footprint);
        if (f.empty()) entry.erase("footprint");
        else entry["footprint"] = f;
    }
    write_file_atomic(manifest, file_text(j));
}

void save_generated_tileset(const fs::path& folder, const GeneratedTileset& g) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw Error(folder.string() + ": cannot create folder: " + ec.message());
    auto height_file_of = [](const std::string& file) { return fs::path(file).stem().string() + ".height.png"; };
    check_own_name(folder / "tileset.json");  // every name refused before any file is written
    for (const std::string& file : g.image_files) {
        check_own_name(folder / file);
        check_own_name(folder / height_file_of(file));
    }
    json sprites = json::array();
    for (std::size_t i = 0; i < g.tileset.sprites.size(); ++i) {
        const Sprite& s = g.tileset.sprites[i];
        const std::string file = g.image_files[i];
        const std::string height_file = height_file_of(file);
        save_image(folder / file, s.image);
        save_gray16(folder / height_file, s.image.width, s.image.height, g.heights[i]);
        sprites.push_back({{"name", s.name},
                           {"image", file},
                           {"anchor", {s.anchor_x, s.anchor_y}},
                           {"kind", s.kind == SpriteKind::floor ? "floor" : "overlay"},
                           {"tags", s.tags},
                           {"height_map", height_file},
                           {"shape", shape_json(s.shape)}});
    }
    json j{{"schema_version", schema_version},
           {"tile", {{"width", g.tileset.tile_width}, {"height", g.tileset.tile_height}}},
           {"sprites", sprites}};
    write_file_atomic(folder / "tileset.json", file_text(j));
}

}  // namespace isolux
