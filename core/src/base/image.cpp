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

std::vector<Rect> outside(Rect region, Rect keep) {
    std::vector<Rect> parts{Rect{region.x, region.y, region.w, keep.y - region.y},
                            Rect{region.x, keep.y + keep.h, region.w, region.y + region.h - keep.y - keep.h},
                            Rect{region.x, keep.y, keep.x - region.x, keep.h},
                            Rect{keep.x + keep.w, keep.y, region.x + region.w - keep.x - keep.w, keep.h}};
    std::erase_if(parts, [](Rect r) { return r.empty(); });
    return parts;
}

std::vector<Rect> disjoint_union(std::vector<Rect> parts, int gap) {
    std::erase_if(parts, [](const Rect& r) { return r.empty(); });
    if (parts.size() <= 1) return parts;
    std::vector<int> edges;
    for (const Rect& r : parts) edges.push_back(r.y), edges.push_back(r.y + r.h);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<Rect> out;
    std::vector<std::size_t> above, here;  // out's rectangles ending at the band's top, and at its bottom
    std::vector<std::pair<int, int>> runs;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const int y0 = edges[e], y1 = edges[e + 1];
        runs.clear();
        for (const Rect& r : parts)
            if (r.y <= y0 && r.y + r.h >= y1) runs.push_back({r.x, r.x + r.w});
        std::sort(runs.begin(), runs.end());
        here.clear();
        for (std::size_t i = 0; i < runs.size();) {
            int x0 = runs[i].first, x1 = runs[i].second;
            for (++i; i < runs.size() && runs[i].first <= x1 + gap; ++i) x1 = std::max(x1, runs[i].second);
            const auto same = std::find_if(above.begin(), above.end(), [&](std::size_t k) {
                return out[k].x == x0 && out[k].w == x1 - x0;
            });
            if (same != above.end()) {
                out[*same].h += y1 - y0;
                here.push_back(*same);
            } else {
                out.push_back({x0, y0, x1 - x0, y1 - y0});
                here.push_back(out.size() - 1);
            }
        }
        std::swap(above, here);
    }
    return out;
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
