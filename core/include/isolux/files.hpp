// File I/O, kept apart from the algorithms: images through OpenImageIO, JSON
// (presets, scenes, tileset manifests) through nlohmann-json. Every reader
// throws Error naming the file and the entry or field; every writer is atomic
// (a temporary file in the same folder, then rename).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "isolux/image.hpp"
#include "isolux/params.hpp"
#include "isolux/scene.hpp"
#include "isolux/tileset.hpp"
#include "isolux/tileset_generator.hpp"

namespace isolux {

inline constexpr int schema_version = 1;  // presets and tileset manifests
// Scenes: 2 added "edits" (hand edits over the seeded map); version 1 scenes
// load unchanged.
inline constexpr int scene_schema_version = 2;

// Largest image we read or write, pixels per side.
inline constexpr int max_image_side = 65536;
// Most pixels an image we read may declare (16 Mpx, 4096 x 4096: 64 MB as
// RGBA), checked from its header before decoding.
inline constexpr std::int64_t max_image_pixels = std::int64_t(1) << 24;
// Largest files we read: images, and JSON (presets, scenes, manifests).
inline constexpr std::uintmax_t max_image_file_bytes = std::uintmax_t(512) << 20;
inline constexpr std::uintmax_t max_text_file_bytes = std::uintmax_t(64) << 20;

// The one way in for every file isolux reads: throws Error naming the path
// unless it is a regular file (not a FIFO, device, folder or socket, nor a
// symlink loop) of at most `max_bytes`.
void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes);

// Reads any image OpenImageIO can (PNG 8/16-bit, palette, grey, grey+alpha,
// RGB, RGBA, ...) and converts it to 8-bit RGBA.
Image load_image(const std::filesystem::path& path);

// Writes RGBA8 as PNG, or EXR (half float) when the extension is .exr.
void save_image(const std::filesystem::path& path, const Image& image);
// What save_image refuses before it writes (a folder, an extension other than
// .png or .exr), checked up front: a render says so before its work.
void check_image_output(const std::filesystem::path& path);

// Reads the first channel of an image as 16-bit values (height maps: pixels
// above the ground, not scaled); throws Error unless it is width x height.
std::vector<std::uint16_t> load_gray16(const std::filesystem::path& path, int width, int height);

// Writes a single-channel 16-bit PNG (height maps).
void save_gray16(const std::filesystem::path& path, int width, int height,
                 const std::vector<std::uint16_t>& values);

// Writes text through a temporary file and rename, so a crash never leaves a
// half-written file where the old one was.
void write_file_atomic(const std::filesystem::path& path, std::string_view contents);

// Tileset manifests (schema in docs/guide.md). Images are relative to the manifest.
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

// Presets: parameters only. Unknown fields are reported in `warnings`.
Params load_preset(const std::filesystem::path& path, std::vector<std::string>* warnings = nullptr);
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
