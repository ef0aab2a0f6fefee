// Paper 3.2, Figures 6 and 7: "the opacity maps of the sprites are subtracted
// or added to the light texture. If the iterated sprite is at a higher
// position than the center of the light in the vertical direction, the
// opacity map of the same is added ... Otherwise ... subtracted."
#include "isolux/opacity_correction.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace isolux {

int correct_with_opacity_maps(LightMask& mask, const PlacedMap& placed, const std::vector<Mask>& opacity) {
    int touched = 0;
    const Rect clip = mask.clip;
    // The falloff by distance, tabulated for the clip's extent.
    const std::int64_t dmax = std::max<std::int64_t>({std::llabs(clip.x - mask.cx), std::llabs(clip.x + clip.w - 1 - mask.cx),
                                                      std::llabs(clip.y - mask.cy), std::llabs(clip.y + clip.h - 1 - mask.cy)});
    std::vector<std::uint8_t> table(std::size_t(std::max<std::int64_t>(0, dmax)) + 1);
    for (std::size_t d = 0; d < table.size(); ++d) table[d] = falloff(std::int64_t(d), mask.falloff_scale);
    std::vector<std::uint32_t> near;
    instances_in(placed, clip, true, near);
    for (std::uint32_t k : near) {
        const SpriteInstance& in = placed.instances[k];
        const Mask& op = opacity[in.sprite];
        const Rect r = intersect({in.x, in.y, op.width, op.height}, clip);
        if (r.empty()) continue;
        ++touched;
        const bool added = opacity_map_added(in, mask.cy);
        for (int y = r.y; y < r.y + r.h; ++y) {
            const std::uint8_t* src = &op.bits[std::size_t(y - in.y) * op.width + (r.x - in.x)];
            std::uint8_t* dst = &mask.value[std::size_t(y - clip.y) * clip.w + (r.x - clip.x)];
            const std::int64_t dy = std::llabs(y - mask.cy);
            for (int x = 0; x < r.w; ++x)
                if (src[x])
                    dst[x] = added ? table[std::size_t(std::max<std::int64_t>(std::llabs(r.x + x - mask.cx), dy))] : 0;
        }
        // In shadow mode the corrected pixels count as reached, so an
        // unlit (subtracted) sprite pixel joins the shadow.
        if (!mask.reached.empty())
            for (int y = r.y; y < r.y + r.h; ++y) {
                const std::uint8_t* src = &op.bits[std::size_t(y - in.y) * op.width + (r.x - in.x)];
                std::uint8_t* dst = &mask.reached[std::size_t(y - clip.y) * clip.w + (r.x - clip.x)];
                for (int x = 0; x < r.w; ++x)
                    if (src[x]) dst[x] = 1;
            }
    }
    return touched;
}

}  // namespace isolux
