// Helpers shared by the tests: tiny hand-made sprites and the default tileset.
#pragma once
#include <string>
#include <vector>

#include "isolux/files.hpp"
#include "isolux/image.hpp"
#include "isolux/light_trace.hpp"

namespace isolux::test {

// A sprite from rows of characters: '#' opaque (alpha 255), '+' half (alpha
// 128), anything else transparent.
inline Image sprite_from(const std::vector<std::string>& rows) {
    Image im(int(rows[0].size()), int(rows.size()));
    for (int y = 0; y < im.height; ++y)
        for (int x = 0; x < im.width; ++x) {
            std::uint8_t* p = im.at(x, y);
            p[0] = p[1] = p[2] = 200;
            p[3] = rows[y][x] == '#' ? 255 : rows[y][x] == '+' ? 128 : 0;
        }
    return im;
}

// A mask from rows of characters: '#' set.
inline Mask mask_from(const std::vector<std::string>& rows, int x0 = 0, int y0 = 0) {
    Mask m(Rect{x0, y0, int(rows[0].size()), int(rows.size())});
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) m.bits[std::size_t(y) * m.width + x] = rows[y][x] == '#';
    return m;
}

// The set pixels of a mask, as "x,y" strings in raster order, for readable failures.
inline std::vector<std::string> set_pixels(const Mask& m) {
    std::vector<std::string> out;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            if (m.bits[std::size_t(y) * m.width + x])
                out.push_back(std::to_string(x + m.x0) + "," + std::to_string(y + m.y0));
    return out;
}

// A traced light's pixels as 0/1: lit or not.
inline std::vector<std::uint8_t> lit_of(const LightMask& m) {
    std::vector<std::uint8_t> out(m.value.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = m.value[i] ? 1 : 0;
    return out;
}

inline Tileset default_tileset() { return load_tileset(std::string(ISOLUX_ASSETS_DIR) + "/default/tileset.json"); }
inline Tileset foreign_tileset() {
    return load_tileset(std::string(ISOLUX_TEST_DATA) + "/foreign_tileset/tileset.json");
}

}  // namespace isolux::test
