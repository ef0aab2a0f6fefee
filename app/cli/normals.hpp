// isolux-cli normals: each sprite's normal map and height map, from the
// estimated solids, the manifest's shapes or the picture's brightness, for
// an engine's 2D lights (docs/games.md).
#pragma once
#include <string>

#include "cli/args.hpp"

namespace isolux::cli {

struct NormalsArgs {
    std::string tileset, out;
    std::string from = "solids";        // solids, shapes or luminance
    std::string convention = "opengl";  // opengl or directx
    ParamArgs params;
};

// Writes DIR/NAME.normal.png and DIR/NAME.height.png for every sprite;
// throws Error naming the file or sprite at fault before anything is
// written (an output that is one of the tileset's own files, a sprite name
// that is not a plain file name, shapes missing for --from shapes).
int run_normals(const NormalsArgs& a);

}  // namespace isolux::cli
