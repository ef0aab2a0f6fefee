#include "cli/normals.hpp"

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>

#include "isolux/error.hpp"
#include "isolux/file_io.hpp"
#include "isolux/image_file.hpp"
#include "isolux/sprite_shading.hpp"
#include "isolux/tileset_file.hpp"

namespace isolux::cli {

namespace fs = std::filesystem;

namespace {

// The files a manifest reads: itself, its sprites' images and height maps
// (it loaded, so its fields are what load_tileset accepted).
std::vector<fs::path> tileset_inputs(const fs::path& manifest) {
    std::vector<fs::path> files{manifest};
    const nlohmann::json j = nlohmann::json::parse(read_text_file(manifest), nullptr, false);
    if (!j.is_object() || !j.contains("sprites") || !j["sprites"].is_array()) return files;
    for (const nlohmann::json& s : j["sprites"]) {
        if (!s.is_object()) continue;
        for (const char* field : {"image", "height_map"})
            if (s.contains(field) && s[field].is_string()) files.push_back(manifest.parent_path() / s[field].get<std::string>());
    }
    return files;
}

bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

// A sprite's name as a file name of its own: no folder, nothing hidden.
void check_file_name(const Tileset& ts, const Sprite& s) {
    const bool plain = !s.name.empty() && s.name != "." && s.name != ".." && s.name.find('/') == std::string::npos &&
                       s.name.find('\\') == std::string::npos && s.name.find('\0') == std::string::npos;
    if (!plain)
        throw Error(ts.source + ": sprite \"" + s.name +
                    "\": its name is not a plain file name, so normals cannot name its files after it");
}

}  // namespace

int run_normals(const NormalsArgs& a) {
    const Params p = params_from_args(a.params, Params{});
    const SpriteShading from = a.from == "shapes"      ? SpriteShading::shapes
                               : a.from == "luminance" ? SpriteShading::luminance
                                                       : SpriteShading::solids;
    const NormalConvention convention = a.convention == "directx" ? NormalConvention::directx : NormalConvention::opengl;
    const Tileset ts = load_tileset(a.tileset);
    const fs::path out = a.out;
    std::error_code ec;
    if (fs::exists(out, ec) && !fs::is_directory(out, ec)) throw Error(out.string() + ": is not a folder");
    // Every check and every map before the first file is written: an error
    // leaves the folder as it was.
    const std::vector<fs::path> inputs = tileset_inputs(a.tileset);
    std::set<std::string> names;
    struct Files {
        fs::path normal, height;
        std::vector<std::uint8_t> rgb;
        std::vector<std::uint16_t> heights;
        int w, h;
    };
    std::vector<Files> files;
    for (const Sprite& s : ts.sprites) {
        check_file_name(ts, s);
        if (!names.insert(s.name).second)
            throw Error(ts.source + ": two sprites are named \"" + s.name + "\": their normal maps would be one file");
        Files f{out / (s.name + ".normal.png"), out / (s.name + ".height.png"), {}, {}, s.image.width, s.image.height};
        for (const fs::path& o : {f.normal, f.height}) {
            for (const fs::path& in : inputs)
                if (same_file(o, in))
                    throw Error(o.string() + ": is one of the tileset's own files; normals never writes over them "
                                            "(choose another --out folder)");
            check_own_name(o);
            if (fs::is_directory(out, ec)) check_output_file(o);  // a fresh folder is made below
        }
        const SpriteNormals n = sprite_normals(ts, s, p, from);
        f.rgb = normal_map_rgb(n, convention);
        f.heights = height_map_values(n);
        files.push_back(std::move(f));
    }
    fs::create_directories(out, ec);
    if (ec) throw Error(out.string() + ": cannot create the folder: " + ec.message());
    for (const Files& f : files) {
        save_rgb8(f.normal, f.w, f.h, f.rgb);
        save_gray16(f.height, f.w, f.h, f.heights);
    }
    std::cout << "wrote " << files.size() << " normal maps and height maps (" << a.from << ", " << a.convention
              << ") to " << out.string() << "\n";
    return 0;
}

}  // namespace isolux::cli
