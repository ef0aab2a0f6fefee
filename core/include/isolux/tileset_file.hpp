// Tileset manifests (JSON; schema in docs/guide.md): the sprites, their
// images (relative to the manifest) and what isolux knows of each beyond its
// pixels. Readers throw Error naming the file, the sprite and the field;
// writers are atomic.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

#include "isolux/tileset.hpp"
#include "isolux/tileset_generator.hpp"

namespace isolux {

Tileset load_tileset(const std::filesystem::path& manifest);

// Writes each sprite's footprint (Sprite::footprint) into the manifest it was
// loaded from, by index, keeping every other field, atomically. Throws Error
// naming the file when it cannot, or when the manifest no longer matches.
void save_manifest_footprints(const std::filesystem::path& manifest, const Tileset& tileset);
std::string footprint_to_json(const FootprintSpec& spec);  // "" for the default (no field)
// A footprint as the manifest spells it ("auto", {"run": [x, y, length]}, ...);
// throws Error naming `source`.
FootprintSpec parse_footprint(std::string_view text, std::string_view source);

// Writes a generated tileset into `folder`: tileset.json, one PNG per sprite
// and its height map as <name>.height.png (16-bit grey, pixels above ground).
void save_generated_tileset(const std::filesystem::path& folder, const GeneratedTileset& g);

}  // namespace isolux
