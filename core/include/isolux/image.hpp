// Plain rasters shared by every stage: RGBA sprites and frames, boolean masks
// (opacity maps, obstacle maps) and rectangles in world pixels.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace isolux {

// An axis-aligned rectangle of pixels: [x, x+w) x [y, y+h).
struct Rect {
    int x = 0, y = 0, w = 0, h = 0;

    bool empty() const { return w <= 0 || h <= 0; }
    bool contains(int px, int py) const { return px >= x && py >= y && px < x + w && py < y + h; }
    friend bool operator==(const Rect&, const Rect&) = default;
};

// Intersection of two rectangles (empty when they do not meet). Inline: the
// sprite queries of every frame call it per candidate.
inline Rect intersect(const Rect& a, const Rect& b) {
    const int x0 = a.x > b.x ? a.x : b.x, y0 = a.y > b.y ? a.y : b.y;
    const int ax1 = a.x + a.w, bx1 = b.x + b.w, ay1 = a.y + a.h, by1 = b.y + b.h;
    const int x1 = ax1 < bx1 ? ax1 : bx1, y1 = ay1 < by1 ? ay1 : by1;
    if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
    return {x0, y0, x1 - x0, y1 - y0};
}

// The smallest rectangle holding both (an empty one counts as nothing).
Rect bounding(const Rect& a, const Rect& b);

// Every pixel of the parts once: disjoint rectangles covering exactly their
// union, top to bottom. Cut into bands at the parts' top and bottom edges,
// each band's runs merged, a run joining the same run of the band above, so
// that a frame redoes several lights' areas and nothing between them. With
// `gap` > 0, two runs of a band at most `gap` pixels apart are joined with
// the pixels between them (for a pass that may redo pixels: fewer, longer
// rows cost less than the pixels they add).
std::vector<Rect> disjoint_union(std::vector<Rect> parts, int gap = 0);

// `region` less `keep` (a rectangle inside it): the rows above and below
// keep, then the columns left and right of it; the empty ones left out.
std::vector<Rect> outside(Rect region, Rect keep);

// A row-major grid of values per pixel over `from` made the grid over `to`
// (a pan, or a region grown or cut): the values of the pixels both hold are
// kept, the others are `fill`, or stale when the sizes match. With the same
// size the values move in place, each row by one offset, in the order that
// reads a row before it is overwritten.
template <class T>
void move_grid(std::vector<T>& grid, Rect from, Rect to, const T& fill = T{}) {
    const Rect keep = intersect(from, to);
    if (from.w != to.w || from.h != to.h) {
        std::vector<T> moved(std::size_t(to.w) * std::size_t(to.h), fill);
        for (int y = keep.y; y < keep.y + keep.h; ++y)
            std::memcpy(&moved[std::size_t(y - to.y) * to.w + std::size_t(keep.x - to.x)],
                        &grid[std::size_t(y - from.y) * from.w + std::size_t(keep.x - from.x)], std::size_t(keep.w) * sizeof(T));
        grid = std::move(moved);
        return;
    }
    if (keep.empty()) return;
    const std::ptrdiff_t w = from.w, offset = std::ptrdiff_t(to.y - from.y) * w + (to.x - from.x);
    auto move_row = [&](int y) {
        const std::ptrdiff_t at = std::ptrdiff_t(y - from.y) * w + (keep.x - from.x);
        std::memmove(grid.data() + (at - offset), grid.data() + at, std::size_t(keep.w) * sizeof(T));
    };
    if (offset > 0)
        for (int y = keep.y; y < keep.y + keep.h; ++y) move_row(y);
    else
        for (int y = keep.y + keep.h - 1; y >= keep.y; --y) move_row(y);
}

// An 8-bit RGBA image, row-major, straight (not premultiplied) alpha.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4
    // Alpha at 16 bits when the source had more than 8 (empty otherwise), so
    // opacity thresholds compare the source's precision.
    std::vector<std::uint16_t> alpha16;

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * h * 4, 0) {}
    std::uint8_t* at(int x, int y) { return &rgba[(std::size_t(y) * width + x) * 4]; }
    const std::uint8_t* at(int x, int y) const { return &rgba[(std::size_t(y) * width + x) * 4]; }
};

// A boolean raster placed at (x0, y0) in its parent's pixels (world pixels for
// the obstacle map, sprite pixels for a sprite's own masks). One byte a pixel,
// 0 or 1. Reading outside the rectangle gives false.
struct Mask {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    std::vector<std::uint8_t> bits;

    Mask() = default;
    Mask(Rect r) : x0(r.x), y0(r.y), width(r.w), height(r.h), bits(std::size_t(r.w) * r.h, 0) {}
    Rect rect() const { return {x0, y0, width, height}; }
    bool get(int x, int y) const {
        x -= x0;
        y -= y0;
        return x >= 0 && y >= 0 && x < width && y < height && bits[std::size_t(y) * width + x];
    }
    void set(int x, int y, bool v = true) {
        x -= x0;
        y -= y0;
        if (x >= 0 && y >= 0 && x < width && y < height) bits[std::size_t(y) * width + x] = v;
    }
    long count() const;
};

// Paints `rgba` over every pixel of `image` where `mask` is set. The image
// shows the world rectangle `image_rect`; the mask's pixel (x, y) lies at world
// (x + dx, y + dy) (0, 0 for a world-placed mask such as the obstacle map, a
// sprite instance's position for its opacity map).
void paint_mask(Image& image, Rect image_rect, const Mask& mask, int dx, int dy, const std::uint8_t rgba[4]);

// An opaque black image of `region`, white where the mask is set.
Image mask_image(const Mask& mask, Rect region);

}  // namespace isolux
