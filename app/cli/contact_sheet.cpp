#include "cli/contact_sheet.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "common/model_colours.hpp"
#include "isolux/error.hpp"

namespace isolux::app {

Image contact_sheet(const std::vector<SheetSprite>& drawn) {
    int cell_w = 1, cell_h = 1;
    for (const SheetSprite& d : drawn)
        cell_w = std::max(cell_w, d.sprite->image.width + 8), cell_h = std::max(cell_h, d.sprite->image.height + 8);
    const int cols = std::max(1, std::min(int(drawn.size()), 2048 / cell_w));
    const int rows = std::max(1, int((drawn.size() + std::size_t(cols) - 1) / std::size_t(cols)));
    if (std::int64_t(cols) * cell_w * std::int64_t(rows) * cell_h > (1LL << 26))
        throw Error("--sheet: " + std::to_string(drawn.size()) + " sprites of up to " + std::to_string(cell_w) + "x" +
                    std::to_string(cell_h) + " make too large a sheet");
    Image sheet(cols * cell_w, rows * cell_h);
    for (std::size_t i = 3; i < sheet.rgba.size(); i += 4) sheet.rgba[i] = 255;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
        const Sprite& s = *drawn[k].sprite;
        const int ox = int(k % std::size_t(cols)) * cell_w + 4, oy = int(k / std::size_t(cols)) * cell_h + 4;
        for (int y = 0; y < s.image.height; ++y)
            for (int x = 0; x < s.image.width; ++x) {
                const std::uint8_t* src = s.image.at(x, y);
                std::uint8_t* d = sheet.at(ox + x, oy + y);
                for (int c = 0; c < 3; ++c) d[c] = std::uint8_t((src[c] * src[3] + 40 * (255 - src[3])) / 255);
            }
        static constexpr std::uint8_t red[4] = {255, 40, 40, 255}, cyan[4] = {0, 255, 255, 255};
        // Each estimated solid's outline, in its model's colour (model_colours.hpp).
        for (const EstimatedObject& o : drawn[k].objects) {
            const Mask solid = solid_silhouette({o}, s.image.width, s.image.height);
            const auto colour = model_colour(o.model).rgba;
            for (int y = 0; y < solid.height; ++y)
                for (int x = 0; x < solid.width; ++x)
                    if (solid.get(x, y) && (!solid.get(x - 1, y) || !solid.get(x + 1, y) || !solid.get(x, y - 1) ||
                                            !solid.get(x, y + 1)))
                        std::copy_n(colour.data(), 4, sheet.at(ox + x, oy + y));
        }
        paint_mask(sheet, Rect{-ox, -oy, sheet.width, sheet.height}, drawn[k].footprint, 0, 0, red);
        // Each object's footprint (orange outline): a grove has one per tree.
        static constexpr std::uint8_t orange[4] = {255, 140, 0, 255};
        for (const EstimatedObject& o : drawn[k].objects)
            for (int y = o.rect.y; y < o.rect.y + o.rect.h; ++y)
                for (int x = o.rect.x; x < o.rect.x + o.rect.w; ++x)
                    if ((y == o.rect.y || y == o.rect.y + o.rect.h - 1 || x == o.rect.x || x == o.rect.x + o.rect.w - 1) &&
                        x >= 0 && y >= 0 && x < cell_w - 8 && y < cell_h - 8)
                        std::copy_n(orange, 4, sheet.at(ox + x, oy + y));
        for (int d = -5; d <= 5; ++d) {
            for (auto [x, y] : {std::pair{s.anchor_x + d, s.anchor_y}, std::pair{s.anchor_x, s.anchor_y + d}})
                if (x >= 0 && y >= 0 && x < cell_w - 8 && y < cell_h - 8) std::copy_n(cyan, 4, sheet.at(ox + x, oy + y));
        }
    }
    return sheet;
}

}  // namespace isolux::app
