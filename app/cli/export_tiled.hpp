// isolux-cli export-tiled: a scene's level as a Tiled map (tiled.hpp); an
// endless world's, a view's window of chunks at a time.
#pragma once
#include <string>

namespace isolux::cli {

struct ExportArgs {
    std::string scene, out, view;  // view: X,Y,W,H in an endless world's pixels
    bool images = false;
    bool allow_huge = false;
    bool normal_maps = false;
    int chunk = 0;  // > 0: an infinite map, chunks of that many tiles a side
};

// Writes the map and prints what it wrote; throws Error naming the file
// and field at fault.
int run_export_tiled(const ExportArgs& a);

}  // namespace isolux::cli
