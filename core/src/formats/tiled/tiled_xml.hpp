// Inside core: reading TMX and TSX elements with errors that name the file
// and the element, and a tile layer's data in every encoding Tiled writes.
#pragma once
#include <pugixml.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace isolux {

// A gid's flip flags (Tiled's high bits) and what is left: the gid itself.
constexpr std::uint32_t flip_h = 0x80000000u, flip_v = 0x40000000u, flip_d = 0x20000000u, rotate_hex = 0x10000000u;
constexpr std::uint32_t gid_mask = ~(flip_h | flip_v | flip_d | rotate_hex);

// "FILE: <layer id="3" name="trees">", for messages.
std::string where_of(const std::filesystem::path& file, const pugi::xml_node& node);
[[noreturn]] void fail(const std::filesystem::path& file, const pugi::xml_node& node, const std::string& what);

// An integer attribute in [lo, hi]; `def` when absent (an error without one).
int int_attr(const std::filesystem::path& file, const pugi::xml_node& node, const char* name, int lo, int hi,
             std::optional<int> def = {});
// A number attribute in [-1e9, 1e9]; `def` when absent.
double real_attr(const std::filesystem::path& file, const pugi::xml_node& node, const char* name, double def);

// A whole XML file, after check_input_file.
pugi::xml_document read_xml(const std::filesystem::path& path);

// The value of the <properties> entry `name` of `node`; "" when it has none.
std::string property(const pugi::xml_node& node, const char* name);

// A tile layer's gids, w x h of them, from its <data> in CSV, base64
// (uncompressed, zlib, gzip or zstd, never inflated past the layer's size)
// or XML <tile>s.
std::vector<std::uint32_t> layer_gids(const std::filesystem::path& file, const pugi::xml_node& layer, int w, int h);
// An infinite map's layer: its <chunk>s (each decoded as a layer's data is)
// laid into the w x h cells whose first is Tiled's (x0, y0); cells no chunk
// holds are empty (gid 0). Every chunk must lie inside those cells.
std::vector<std::uint32_t> chunked_layer_gids(const std::filesystem::path& file, const pugi::xml_node& layer, int x0,
                                              int y0, int w, int h);

}  // namespace isolux
