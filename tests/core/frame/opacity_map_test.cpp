// Opacity maps (paper 3.2): a pixel is opaque strictly above the threshold.
#include <gtest/gtest.h>

#include "isolux/hash.hpp"
#include "isolux/footprint.hpp"
#include "isolux/image_file.hpp"

#include <cmath>
#include <cstdint>
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include "test_util.hpp"

using namespace isolux;
using test::mask_from;
using test::set_pixels;
using test::sprite_from;
using V = std::vector<std::string>;

TEST(OpacityMap, alphaExactlyAtTheThresholdIsTransparent) {
    Image im = sprite_from({"#+."});
    Mask m = opacity_map(im, 128 / 255.0);
    EXPECT_EQ(set_pixels(m), V({"0,0"}));
    EXPECT_EQ(set_pixels(opacity_map(im, 0.5)), V({"0,0", "1,0"}));  // 128/255 > 0.5
    EXPECT_EQ(set_pixels(opacity_map(im, 1.0)), V{});
}
