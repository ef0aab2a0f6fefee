// Images in and out through OpenImageIO: sprites and sheets of any format it
// reads, renders as PNG or EXR, height maps as 16-bit grey PNG. Reads are
// bounded before decoding; writes are atomic (file_io.hpp).
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "isolux/image.hpp"

namespace isolux {

// Largest image we read or write, pixels per side.
inline constexpr int max_image_side = 65536;
// Most pixels an image we read may declare (16 Mpx, 4096 x 4096: 64 MB as
// RGBA), checked from its header before decoding.
inline constexpr std::int64_t max_image_pixels = std::int64_t(1) << 24;
// Most pixels of sprite images one input (a tileset manifest, or a Tiled
// map with all its tilesets) may load in all (64 Mpx: 256 MB as RGBA): a
// small file that names one large sheet a hundred times, or a hundred large
// images, is refused with its total, not loaded.
inline constexpr std::int64_t max_input_sprite_pixels = std::int64_t(1) << 26;

// Largest image files we read.
inline constexpr std::uintmax_t max_image_file_bytes = std::uintmax_t(512) << 20;

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
// An 8-bit RGB PNG (a normal map), `rgb` 3 bytes a pixel row by row,
// written as save_gray16 writes.
void save_rgb8(const std::filesystem::path& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace isolux
