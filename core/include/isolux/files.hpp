// Every file format of isolux::core, kept apart from the algorithms: one
// header per job. Every reader throws Error naming the file and the entry or
// field; every writer is atomic.
#pragma once
#include "isolux/file_io.hpp"       // checked reads, atomic writes
#include "isolux/image_file.hpp"    // images (OpenImageIO)
#include "isolux/scene_file.hpp"    // presets and scenes (JSON)
#include "isolux/tileset_file.hpp"  // tileset manifests (JSON)
