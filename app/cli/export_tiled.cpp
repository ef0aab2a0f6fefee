#include "cli/export_tiled.hpp"

#include <iostream>

#include "common/world.hpp"
#include "isolux/endless.hpp"
#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/tiled.hpp"

namespace isolux::cli {

int run_export_tiled(const ExportArgs& a) {
    check_output_file(a.out);  // before the world is built: a missing folder costs nothing
    std::vector<std::string> warnings;
    Scene scene = load_scene(a.scene, &warnings);
    for (const auto& w : warnings) std::cerr << "isolux-cli: warning: " << printable(w) << "\n";
    TiledExport opt;
    opt.images = a.images;
    opt.chunk = a.chunk;
    opt.allow_huge = a.allow_huge;
    opt.normal_maps = a.normal_maps;
    World world;
    std::string region;
    if (scene.endless) {
        // An endless world has no whole map: the window of chunks a view needs.
        if (a.view.empty())
            throw Error(a.scene + ": an endless world is exported a region at a time: give --view X,Y,W,H");
        const WorldRect v = app::parse_endless_view(a.view);
        EndlessWindow win = app::build_endless_window(scene, v, a.scene);
        scene = scene_in_window(scene, win, v);
        region = "; tiles " + std::to_string(win.chunks.col0) + ".." + std::to_string(win.chunks.col0 + win.chunks.cols - 1) +
                 " x " + std::to_string(win.chunks.row0) + ".." + std::to_string(win.chunks.row0 + win.chunks.rows - 1) +
                 " of the endless world, its pixel (x, y) the world's (" + std::to_string(win.origin_x) + " + x, " +
                 std::to_string(win.origin_y) + " + y)";
        world = std::move(win.world);
    } else {
        if (!a.view.empty()) throw Error("--view: export-tiled writes a map with an edge whole; --view is for endless worlds");
        world = app::build_world(scene, a.scene);
    }
    const auto [ox, oy] = export_tiled(world, scene, a.out, opt);
    std::cout << "wrote " << a.out << " (" << world.map.width << "x" << world.map.height << " "
              << (world.map.layout == Layout::staggered ? "staggered" : "isometric") << ", " << scene.lights.size()
              << " lights; Tiled's pixel (0, 0) is world (" << ox << ", " << oy << ")" << region << ")\n";
    return 0;
}

}  // namespace isolux::cli
