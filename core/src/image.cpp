#include "isolux/image.hpp"

#include <algorithm>
#include <numeric>

namespace isolux {

Rect bounding(const Rect& a, const Rect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    const int x0 = std::min(a.x, b.x), y0 = std::min(a.y, b.y);
    const int x1 = std::max(a.x + a.w, b.x + b.w), y1 = std::max(a.y + a.h, b.y + b.h);
    return {x0, y0, x1 - x0, y1 - y0};
}

long Mask::count() const { return std::accumulate(bits.begin(), bits.end(), 0L); }

void paint_mask(Image& image, Rect image_rect, const Mask& mask, int dx, int dy, const std::uint8_t rgba[4]) {
    Rect placed = mask.rect();
    placed.x += dx;
    placed.y += dy;
    const Rect r = intersect(intersect(placed, image_rect), Rect{image_rect.x, image_rect.y, image.width, image.height});
    for (int y = r.y; y < r.y + r.h; ++y)
        for (int x = r.x; x < r.x + r.w; ++x)
            if (mask.get(x - dx, y - dy)) std::copy_n(rgba, 4, image.at(x - image_rect.x, y - image_rect.y));
}

Image mask_image(const Mask& mask, Rect region) {
    Image im(region.w, region.h);
    for (std::size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 255;
    static constexpr std::uint8_t white[4] = {255, 255, 255, 255};
    paint_mask(im, region, mask, 0, 0, white);
    return im;
}

}  // namespace isolux
