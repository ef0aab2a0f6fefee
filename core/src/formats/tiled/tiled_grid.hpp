// Inside core: a Tiled map's geometry, shared by the TMX reader and writer.
// It follows Tiled 1.8's own renderers (libtiled's isometricrenderer.cpp and
// hexagonalrenderer.cpp), so that tmxrasterizer draws an exported map as
// isolux does and isolux places an imported map's sprites where Tiled does.
#pragma once
#include <sstream>
#include <string>

namespace isolux {

// How a Tiled map turns tiles and object pixels into screen pixels.
struct Grid {
    bool isometric = true;  // else staggered, axis y
    bool stagger_even = false;
    int tw = 0, th = 0, w = 0, h = 0;  // w x h: the cells isolux holds
    // An infinite map's cells are its chunks' bounding box: cell (x, y) is
    // Tiled's (x + x0, y + y0), and Tiled's projection keeps the map's
    // declared height (map_h). A finite map: 0, 0 and its height.
    int x0 = 0, y0 = 0, map_h = -1;
    bool infinite = false;

    double projection_h() const { return map_h >= 0 ? map_h : h; }
    // The bottom-left of cell (x, y)'s box: where Tiled draws its image from.
    void cell_bottom_left(int x, int y, double& sx, double& sy) const {
        x += x0, y += y0;
        // In doubles: an infinite map's far chunks (x0 near 1e9) overflow an int's products.
        const double dx = x, dy = y;
        if (isometric) {
            const double origin_x = projection_h() * tw / 2;
            sx = (dx - dy) * tw / 2.0 + origin_x - tw / 2.0;
            sy = (dx + dy) * th / 2.0 + th;
        } else {
            const bool shifted = ((y & 1) != 0) != stagger_even;
            sx = dx * tw + (shifted ? tw / 2.0 : 0.0);
            sy = dy * (th / 2) + th;
        }
    }
    // An object's pixel coordinates to screen pixels, and back.
    void object_to_screen(double px, double py, double& sx, double& sy) const {
        if (!isometric) {
            sx = px, sy = py;
            return;
        }
        const double tx = px / th, ty = py / th;
        sx = (tx - ty) * tw / 2.0 + projection_h() * tw / 2;
        sy = (tx + ty) * th / 2.0;
    }
    void screen_to_object(double sx, double sy, double& px, double& py) const {
        if (!isometric) {
            px = sx, py = sy;
            return;
        }
        const double a = (sx - projection_h() * tw / 2) / (tw / 2.0), b = sy / (th / 2.0);
        px = (a + b) / 2 * th;
        py = (b - a) / 2 * th;
    }
};

// A coordinate as TMX writes it: every digit a double holds.
inline std::string number(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

}  // namespace isolux
