// isolux: real-time lighting for procedurally generated 2D isometric maps
// (Rodrigues & Clua), as plain data types and free functions. The one header
// a game or tool includes; docs/games.md shows it in use, docs/method.md
// and docs/beyond.md say what each step does and why.
//
// The headers it gathers, by concern (core/src/ has the same folders):
//   base     image.hpp (images, masks, rectangles), hash.hpp (seeded noise), error.hpp
//   map      tileset.hpp, tileset_generator.hpp, map.hpp (seeded maps, placement),
//            world.hpp, edits.hpp, endless.hpp, footprint.hpp
//   formats  file_io.hpp, image_file.hpp, scene_file.hpp, tileset_file.hpp, tiled.hpp
//   frame    params.hpp, scene.hpp, stage.hpp, opacity_map.hpp, obstacle_map.hpp,
//            light_trace.hpp, light_texture.hpp, opacity_correction.hpp, blur.hpp,
//            composite.hpp, frame.hpp (the whole pipeline, one call a frame)
//   solids   solid.hpp, solid_estimate.hpp, occluder_map.hpp, height_rays.hpp
//   shading  sprite_shading.hpp (sprites shaded by their surfaces' facing)
//   truth    truth.hpp (the 3D reference), accuracy.hpp (metrics and sweeps)
#pragma once

#include "isolux/error.hpp"
#include "isolux/hash.hpp"
#include "isolux/image.hpp"

#include "isolux/edits.hpp"
#include "isolux/endless.hpp"
#include "isolux/footprint.hpp"
#include "isolux/map.hpp"
#include "isolux/tileset.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/world.hpp"

#include "isolux/file_io.hpp"
#include "isolux/image_file.hpp"
#include "isolux/scene_file.hpp"
#include "isolux/tiled.hpp"
#include "isolux/tileset_file.hpp"

#include "isolux/blur.hpp"
#include "isolux/composite.hpp"
#include "isolux/frame.hpp"
#include "isolux/light_texture.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_correction.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/params.hpp"
#include "isolux/scene.hpp"
#include "isolux/stage.hpp"

#include "isolux/height_rays.hpp"
#include "isolux/occluder_map.hpp"
#include "isolux/solid.hpp"
#include "isolux/solid_estimate.hpp"

#include "isolux/sprite_shading.hpp"

#include "isolux/accuracy.hpp"
#include "isolux/truth.hpp"
