// Presets (parameters only) and scenes (a level: seed or map, tileset,
// preset, lights, camera, edits) as JSON; schema in docs/guide.md. Readers
// throw Error naming the file and the field; writers are atomic.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/params.hpp"
#include "isolux/scene.hpp"

namespace isolux {

inline constexpr int schema_version = 1;  // presets and tileset manifests
// Scenes: 2 added "edits" (hand edits over the seeded map); version 1 scenes
// load unchanged.
inline constexpr int scene_schema_version = 2;

// Presets. Unknown fields are reported in `warnings`.
Params load_preset(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);
// A preset by name or path, as every front end takes one (--preset, the C
// API, Godot): a built-in name (builtin_preset_names) is always the built-in,
// whatever the working folder holds; anything else is a preset file's path
// ("./game" reaches a file named game).
Params preset_named(const std::string& name_or_path, std::vector<std::string>* warnings = nullptr);
void save_preset(const std::filesystem::path& path, const Params& params);
std::string preset_to_json(const Params& params);
Params preset_from_json(std::string_view text, std::string_view source,
                        std::vector<std::string>* warnings = nullptr);

// Scenes. A relative tileset path is resolved against the scene's folder on
// load and written relative to it on save when possible.
Scene load_scene(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);
void save_scene(const std::filesystem::path& path, const Scene& scene);
std::string scene_to_json(const Scene& scene);
Scene scene_from_json(std::string_view text, std::string_view source,
                      std::vector<std::string>* warnings = nullptr);

// Parses "RRGGBB" (optionally with a leading '#'); false when malformed.
bool parse_hex_color(std::string_view s, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b);

}  // namespace isolux
