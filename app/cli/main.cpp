// isolux-cli: the headless front end. Everything here runs with no display and
// no GL context; it only parses arguments and calls isolux::core. Each
// subcommand's work is in its own file: render, check_tileset, sweep,
// export_tiled (and args: the flags they share).
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "cli/args.hpp"
#include "cli/check_tileset.hpp"
#include "cli/export_tiled.hpp"
#include "cli/normals.hpp"
#include "cli/render.hpp"
#include "cli/sweep.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/frame.hpp"
#include "isolux/params.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/tileset_generator.hpp"

using namespace isolux;

namespace {

// One line a row of the parameter table, tab-separated, with a header.
void print_param_table() {
    std::cout << "name\tflag\told_flag\ttype\tmin\tmax\tdefault\tsymbol\treruns\thelp\n";
    static const char* types[] = {"integer", "real", "choice", "boolean"};
    for (const ParamInfo& info : param_table()) {
        std::string reruns;
        for (int k = 0; k < stage_count; ++k)
            if (info.reruns.has(Stage(k))) reruns += (reruns.empty() ? "" : ",") + std::string(to_string(Stage(k)));
        const bool numeric = info.type == ParamType::integer || info.type == ParamType::real;
        std::cout << info.name << '\t' << info.flag << '\t' << (info.old_flag ? info.old_flag : "-") << '\t'
                  << types[int(info.type)] << '\t'
                  << (numeric ? format_param(info, info.min) : std::string(info.type == ParamType::boolean ? "false" : info.choices[0]))
                  << (info.min_open ? " (excluded)" : "") << '\t'
                  << (numeric ? format_param(info, info.max) : format_param(info, info.max)) << '\t'
                  << format_param(info, param_default(info)) << '\t' << (*info.symbol ? info.symbol : "-") << '\t'
                  << (reruns.empty() ? "-" : reruns) << '\t' << info.help << '\n';
    }
}

}  // namespace

// The whole command line (tests/fuzz/fuzz_cli.cpp calls it too).
int isolux_cli_main(int argc, char** argv) {
    // What the saves had to do that the user should know (a hard link that
    // could not be kept), said once the command ends, however it ends.
    struct SayNotes {
        ~SayNotes() {
            for (const std::string& n : take_write_notes()) std::cerr << "isolux-cli: note: " << printable(n) << "\n";
        }
    } say_notes;
    CLI::App app{"isolux-cli: renders seeded isometric maps and the paper's lighting with no display."};
    app.require_subcommand(1);

    cli::RenderArgs ra;
    CLI::App* render = app.add_subcommand("render", "Render a seeded map (or a scene) to an image");
    render->add_option("--seed", ra.seed, "Map seed text (default \"isolux\")");
    render->add_option("--size", ra.size, "Map size in tiles, WxH (default 16x16), or endless (needs --view or a scene camera with a size)");
    render->add_option("--layout", ra.layout, "paper, diamond or staggered (default diamond)");
    render->add_option("--tileset", ra.tileset, "Tileset manifest (default: assets/default/tileset.json)");
    render->add_option("--scene", ra.scene, "Scene JSON file; other flags override its fields");
    render->add_option("--map", ra.map, "A Tiled map (.tmx, isometric or staggered) to render and light in place of a seeded one");
    render->add_option("--layer", ra.layer,
                       "final (default), light, map, obstacles, opacity, truth (lit by --reference) or difference "
                       "(magenta: lit by the model only; cyan: by the reference only)")
        ->check(CLI::IsMember(cli::render_layer_names()));
    render->add_option("--reference", ra.reference,
                       "For --layer truth and difference: 3d (default; the sprites' true shapes, lights at their "
                       "height), 3d_facing, 3d_shaded, exact_line or every_pixel");
    render->add_option("--light", ra.lights,
                       "A light X,Y[,A,B[,RRGGBB]][,h=HEIGHT] in world pixels: its ground point, own half-extents, "
                       "colour and height above the ground (default --light-height) (repeatable)");
    render->add_option("--frames", ra.frames, "Frames to run; the last is written (default 1)")
        ->check(CLI::Range(1, 100000));
    render->add_option("--camera-step", ra.camera_step, "Camera movement per frame DX,DY (pixels)");
    render->add_flag("--stats", ra.stats,
                     "Print each frame's stages: time (ms) and the world rectangle each wrote (WxH at X,Y)");
    render->add_option("--threads", ra.threads, "Threads for the frame's stages, 0: one per core (default 1); the "
                                                "pixels are the same for any count")
        ->check(CLI::Range(0, 256));
    render->add_flag("--no-opacity-correction", ra.no_opacity_correction,
                     "Skip the opacity-map correction (shows the paper's Figure 6 problem)");
    cli::add_param_flags(*render, ra.params);
    render->add_flag("--allow-huge", ra.allow_huge, "Run even when the estimated work is beyond a few seconds");
    render->add_option("--view", ra.view, "World-pixel rectangle X,Y,W,H to render (default: the whole map)");
    render->add_option("--out", ra.out, "Output image (.png or .exr)")->required();

    cli::ParamArgs pa;
    std::string preset_out;
    CLI::App* preset = app.add_subcommand("preset", "Write a preset: a built-in or file, with any parameter changed");
    cli::add_param_flags(*preset, pa);
    preset->add_option("--out", preset_out, "Preset JSON to write (atomically)")->required();

    cli::CheckArgs ca;
    CLI::App* check = app.add_subcommand("check-tileset",
                                         "For every overlay sprite: where its obstacle lands against its anchor, and "
                                         "what the footprint estimate detected (baked ground, baked shadow)");
    check->add_option("manifest", ca.manifest, "Tileset manifest")->required();
    check->add_flag("--json", ca.json, "Print one JSON object: {\"sprites\": [{\"name\", \"obstacle_center\", ...}]}");
    check->add_option("--sheet", ca.sheet,
                      "Write a contact sheet: every sprite with its obstacle (red), each estimated solid's outline "
                      "in its model's colour (revolution yellow, prism magenta, mound green), each solid's footprint "
                      "box (orange) and the anchor (cyan)");
    cli::add_param_flags(*check, ca.params);

    CLI::App* params = app.add_subcommand("params", "List the parameters: field, flag, type, range, default, what a change re-runs");

    std::string tileset_out;
    double tileset_scale = 1.0;
    std::string tileset_name = "default";
    CLI::App* tileset = app.add_subcommand("tileset", "Regenerate a built-in tileset (deterministic)");
    tileset->add_option("--name", tileset_name,
                        "default (trees, bushes, rocks: assets/default) or town (walls, houses, a town, rocks, a "
                        "mountain, a grove, a tall tree, in another look: assets/town)")
        ->check(CLI::IsMember({"default", "town"}));
    tileset->add_option("--out", tileset_out, "Folder to write tileset.json, sprites and height maps")->required();
    tileset->add_option("--scale", tileset_scale, "Sprite scale: 1 gives 128x128 sprites")
        ->check(CLI::Range(0.25, 4.0));

    cli::SweepArgs sa;
    CLI::App* sweep = app.add_subcommand("sweep", "Accuracy against time: time and error of every parameter combination");
    sweep->add_option("--scene", sa.scene, "Scene JSON (its camera starts the path; size 0 = whole map)")->required();
    sweep->add_option("--param", sa.params, "NAME=V1,V2,... (repeatable): a preset parameter and its values");
    sweep->add_option("--out", sa.out, "CSV to write")->required();
    sweep->add_option("--chart", sa.chart, "SVG chart of error against time");
    sweep->add_option("--frames", sa.frames, "Frames per run (default 8)")->check(CLI::Range(1, 1000));
    sweep->add_option("--repeats", sa.repeats, "Runs per combination; times are medians (default 3)")
        ->check(CLI::Range(1, 100));
    sweep->add_option("--step", sa.step, "Camera movement per frame DX,DY (default 24,12)");
    sweep->add_flag("--no-carried-light", sa.no_carry, "No light moving with the camera");
    sweep->add_flag("--allow-huge", sa.allow_huge, "Run even when the estimated work is beyond a few minutes");
    sweep->add_flag("--no-opacity-correction", sa.no_opacity_correction,
                    "Measure the model without its opacity correction (the paper's Figure 6)");
    sweep->add_option("--reference", sa.references,
                      "What the error is measured against: every_pixel (default; the model's own 4ab rays), "
                      "exact_line, 3d (the sprites' true shapes), 3d_facing or 3d_shaded (3d with Lambert's cosine on sprites); a "
                      "comma list measures each");

    cli::NormalsArgs na;
    CLI::App* normals = app.add_subcommand(
        "normals", "Write each sprite's normal map (NAME.normal.png) and height map (NAME.height.png) for an engine's 2D lights");
    normals->add_option("--tileset", na.tileset, "Tileset manifest")->required();
    normals->add_option("--out", na.out, "Folder to write into (never over the tileset's own files)")->required();
    normals->add_option("--from", na.from,
                        "solids (default: the solids estimated from each sprite), shapes (the manifest's shapes or "
                        "height maps) or luminance (the picture's brightness, as normal-map generators make them)")
        ->check(CLI::IsMember({"solids", "shapes", "luminance"}));
    normals->add_option("--convention", na.convention,
                        "opengl (default: green is +Y up, as Godot reads it) or directx (green is +Y down)")
        ->check(CLI::IsMember({"opengl", "directx"}));
    cli::add_param_flags(*normals, na.params);

    cli::ExportArgs ea;
    CLI::App* export_tiled_cmd = app.add_subcommand("export-tiled", "Write a scene's level as a Tiled map (TMX, TSX, images)");
    export_tiled_cmd->add_option("--scene", ea.scene, "Scene JSON file")->required();
    export_tiled_cmd->add_option("--out", ea.out, "The map to write: DIR/NAME.tmx")->required();
    export_tiled_cmd->add_flag("--images", ea.images, "Also the light texture and the final frame as (hidden) image layers");
    export_tiled_cmd->add_flag("--allow-huge", ea.allow_huge, "Run even when the export would hold over 1 GiB at once");
    export_tiled_cmd->add_flag("--normal-maps", ea.normal_maps,
                               "Also each sprite's normal map and height map beside its image (NAME.normal.png, "
                               "NAME.height.png), named in its tile's properties (normal_map): from the scene's "
                               "sprite_shading, or the estimated solids when it is none");
    export_tiled_cmd->add_option("--view", ea.view,
                                 "An endless world's view, X,Y,W,H: the window of chunks it needs is the map written");
    export_tiled_cmd->add_option("--infinite", ea.chunk,
                                 "Write an infinite map: tile layers as chunks of N x N tiles (Tiled's own: 16)")
        ->check(CLI::Range(1, 1024))
        ->expected(0, 1)
        ->default_str("16");

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
        if (*render) return cli::run_render(ra);
        if (*sweep) return cli::run_sweep_command(sa);
        if (*check) return cli::run_check_tileset(ca);
        if (*normals) return cli::run_normals(na);
        if (*export_tiled_cmd) {
            ea.chunk = export_tiled_cmd->count("--infinite") ? (ea.chunk > 0 ? ea.chunk : 16) : 0;
            return cli::run_export_tiled(ea);
        }
        if (*preset) {
            save_preset(preset_out, cli::params_from_args(pa, Params{}));
            std::cout << "wrote " << preset_out << "\n";
            return 0;
        }
        if (*params) {
            print_param_table();
            return 0;
        }
        if (*tileset) {
            save_generated_tileset(tileset_out, tileset_name == "town" ? generate_town_tileset(tileset_scale)
                                                                        : generate_default_tileset(tileset_scale));
            std::cout << "wrote " << tileset_out << "/tileset.json\n";
            return 0;
        }
    } catch (const Error& e) {
        std::cerr << "isolux-cli: " << e.what() << "\n";
        return 2;
    } catch (const std::bad_alloc&) {
        std::cerr << "isolux-cli: out of memory: try a smaller map or --view\n";
        return 2;
    } catch (const std::exception& e) {  // a library's own (a file system error, say): still one line, exit 2
        std::cerr << "isolux-cli: " << printable(e.what()) << "\n";
        return 2;
    }
    return 0;
}

#ifndef ISOLUX_CLI_NO_MAIN
int main(int argc, char** argv) { return isolux_cli_main(argc, argv); }
#endif
