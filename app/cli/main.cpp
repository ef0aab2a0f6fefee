// isolux-cli: the headless front end. Everything here runs with no display and
// no GL context; it only parses arguments and calls isolux::core.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "common/world.hpp"
#include "isolux/error.hpp"
#include "isolux/files.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/tileset_generator.hpp"

using namespace isolux;

namespace {

constexpr long long max_render_pixels = 1LL << 28;  // 256 Mpx: 1 GiB of RGBA

struct RenderArgs {
    std::string seed, size, layout, tileset, preset, scene, view, out;
    std::string layer = "map";
};

bool parse_ints(const std::string& s, char sep, std::vector<long long>& out) {
    out.clear();
    std::size_t pos = 0;
    while (true) {
        std::size_t end = s.find(sep, pos);
        std::string part = s.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (part.empty() || part.size() > 12) return false;
        std::size_t used = 0;
        try {
            out.push_back(std::stoll(part, &used));
        } catch (...) {
            return false;
        }
        if (used != part.size()) return false;
        if (end == std::string::npos) return true;
        pos = end + 1;
    }
}

Scene scene_from_args(const RenderArgs& a) {
    Scene s;
    if (!a.scene.empty()) {
        std::vector<std::string> warnings;
        s = load_scene(a.scene, &warnings);
        for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << w << "\n";
    }
    if (!a.seed.empty()) s.seed = a.seed;
    if (!a.size.empty()) {
        std::vector<long long> v;
        if (!parse_ints(a.size, 'x', v) || v.size() != 2)
            throw Error("--size \"" + a.size + "\": expected WxH, e.g. 16x16");
        if (v[0] < 1 || v[1] < 1 || v[0] > max_map_side || v[1] > max_map_side)
            throw Error("--size " + a.size + ": each side must be in [1, " + std::to_string(max_map_side) + "] tiles");
        s.width = int(v[0]);
        s.height = int(v[1]);
    }
    if (!a.layout.empty()) s.layout = parse_layout(a.layout, "--layout");
    if (!a.tileset.empty()) s.tileset = a.tileset;
    if (!a.preset.empty()) {
        std::vector<std::string> warnings;
        bool builtin = !std::filesystem::exists(a.preset) && a.preset.find('.') == std::string::npos;
        s.params = builtin ? builtin_preset(a.preset) : load_preset(a.preset, &warnings);
        for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << w << "\n";
    }
    validate(s.params, "parameters");
    return s;
}

Rect view_from_args(const RenderArgs& a, const Scene& s, const World& w) {
    Rect view = w.placed.bounds;
    if (s.camera.width > 0 && s.camera.height > 0)
        view = {int(s.camera.x), int(s.camera.y), s.camera.width, s.camera.height};
    if (!a.view.empty()) {
        std::vector<long long> v;
        if (!parse_ints(a.view, ',', v) || v.size() != 4 || v[2] < 1 || v[3] < 1 || v[2] > max_image_side ||
            v[3] > max_image_side || std::abs(v[0]) > 1e9 || std::abs(v[1]) > 1e9)
            throw Error("--view \"" + a.view + "\": expected X,Y,W,H with W and H in [1, " +
                        std::to_string(max_image_side) + "]");
        view = {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
    }
    if ((long long)view.w * view.h > max_render_pixels)
        throw Error("the view is " + std::to_string(view.w) + "x" + std::to_string(view.h) +
                    " pixels, over the 256-megapixel limit: render part of the map with --view X,Y,W,H");
    return view;
}

int run_render(const RenderArgs& a) {
    Scene s = scene_from_args(a);
    World w = build_world(s);
    Rect view = view_from_args(a, s, w);
    Image out;
    if (a.layer == "map" || a.layer == "obstacles") {
        out = render_sprites(w.tileset, w.placed, view);
        if (a.layer == "obstacles") {
            // The paper's Figure 6: obstacle pixels in white over the map.
            Mask obstacles = build_obstacle_map(w.tileset, w.placed, s.params, view);
            for (int y = 0; y < view.h; ++y)
                for (int x = 0; x < view.w; ++x)
                    if (obstacles.bits[std::size_t(y) * view.w + x]) {
                        std::uint8_t* p = out.at(x, y);
                        p[0] = p[1] = p[2] = p[3] = 255;
                    }
        }
    } else if (a.layer == "opacity") {
        out = Image(view.w, view.h);
        for (std::size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
        std::vector<std::optional<Mask>> maps(w.tileset.sprites.size());
        for (std::size_t i = w.placed.first_overlay; i < w.placed.instances.size(); ++i) {
            const SpriteInstance& in = w.placed.instances[i];
            const Sprite& sp = w.tileset.sprites[in.sprite];
            if (!maps[in.sprite]) maps[in.sprite] = opacity_map(sp.image, sprite_threshold(sp, s.params.opacity_threshold));
            const Mask& m = *maps[in.sprite];
            Rect r = intersect({in.x, in.y, m.width, m.height}, view);
            for (int y = r.y; y < r.y + r.h; ++y)
                for (int x = r.x; x < r.x + r.w; ++x)
                    if (m.get(x - in.x, y - in.y)) {
                        std::uint8_t* p = out.at(x - view.x, y - view.y);
                        p[0] = p[1] = p[2] = 255;
                    }
        }
    }
    save_image(a.out, out);
    std::cout << "wrote " << a.out << " (" << view.w << "x" << view.h << ", layer " << a.layer << ", seed \""
              << s.seed << "\")\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"isolux-cli: renders seeded isometric maps and the paper's lighting with no display."};
    app.require_subcommand(1);

    RenderArgs ra;
    CLI::App* render = app.add_subcommand("render", "Render a seeded map (or a scene) to an image");
    render->add_option("--seed", ra.seed, "Map seed text (default \"isolux\")");
    render->add_option("--size", ra.size, "Map size in tiles, WxH (default 16x16)");
    render->add_option("--layout", ra.layout, "paper, diamond or staggered (default diamond)");
    render->add_option("--tileset", ra.tileset, "Tileset manifest (default: assets/default/tileset.json)");
    render->add_option("--preset", ra.preset, "Preset JSON file, or a built-in: paper, fast, quality");
    render->add_option("--scene", ra.scene, "Scene JSON file; other flags override its fields");
    render->add_option("--layer", ra.layer, "map, obstacles or opacity")
        ->check(CLI::IsMember({"map", "obstacles", "opacity"}));
    render->add_option("--view", ra.view, "World-pixel rectangle X,Y,W,H to render (default: the whole map)");
    render->add_option("--out", ra.out, "Output image (.png or .exr)")->required();

    std::string tileset_out;
    double tileset_scale = 1.0;
    CLI::App* tileset = app.add_subcommand("tileset", "Regenerate the default tileset (deterministic)");
    tileset->add_option("--out", tileset_out, "Folder to write tileset.json, sprites and height maps")->required();
    tileset->add_option("--scale", tileset_scale, "Sprite scale: 1 gives 128x128 sprites")
        ->check(CLI::Range(0.25, 4.0));

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "isolux-cli: " << e.what() << " (see isolux-cli --help)\n";
        return 2;
    }
    try {
        if (*render) return run_render(ra);
        if (*tileset) {
            save_generated_tileset(tileset_out, generate_default_tileset(tileset_scale));
            std::cout << "wrote " << tileset_out << "/tileset.json\n";
            return 0;
        }
    } catch (const Error& e) {
        std::cerr << "isolux-cli: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << "isolux-cli: out of memory: try a smaller map or --view\n";
        return 2;
    }
    return 0;
}
