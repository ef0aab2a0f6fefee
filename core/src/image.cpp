#include "isolux/image.hpp"

#include <algorithm>
#include <numeric>

namespace isolux {

Rect intersect(const Rect& a, const Rect& b) {
    int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
    int x1 = std::min(a.x + a.w, b.x + b.w), y1 = std::min(a.y + a.h, b.y + b.h);
    if (x1 <= x0 || y1 <= y0) return {x0, y0, 0, 0};
    return {x0, y0, x1 - x0, y1 - y0};
}

long Mask::count() const { return std::accumulate(bits.begin(), bits.end(), 0L); }

}  // namespace isolux
