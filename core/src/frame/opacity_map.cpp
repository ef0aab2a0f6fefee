// Paper 3.2: opacity maps, "a boolean matrix that indicates if a certain pixel
// of the sprite is transparent or not, given a certain threshold".
#include "isolux/opacity_map.hpp"

#include <cassert>
namespace isolux {

Mask opacity_map(const Image& sprite, double threshold) {
    assert(threshold >= 0 && threshold <= 1 && sprite.rgba.size() == std::size_t(sprite.width) * sprite.height * 4);
    Mask m(Rect{0, 0, sprite.width, sprite.height});
    if (!sprite.alpha16.empty()) {
        // A 16-bit source: 0.49973 is above 0.4995 here, though both round to 127/255.
        for (std::size_t i = 0; i < m.bits.size(); ++i) m.bits[i] = sprite.alpha16[i] / 65535.0 > threshold;
        return m;
    }
    for (int y = 0; y < sprite.height; ++y)
        for (int x = 0; x < sprite.width; ++x)
            // Same expression on both sides of the comparison, so an alpha of
            // exactly threshold * 255 is never "above" it by rounding.
            m.bits[std::size_t(y) * sprite.width + x] = sprite.at(x, y)[3] / 255.0 > threshold;
    return m;
}

double sprite_threshold(const Sprite& s, double preset_threshold) {
    return s.opacity_threshold ? *s.opacity_threshold : preset_threshold;
}

}  // namespace isolux
