// Hard cases: Algorithm 1 and the noise filter on extreme sprites and windows.
#include "isolux/obstacle_map.hpp"
#include "isolux/opacity_map.hpp"
#include "stability.hpp"

using namespace isolux;
using test::sprite_from;

TEST(StabilityObstacleMap, fullyTransparentSprite) {
    Mask m = sprite_obstacle(opacity_map(sprite_from({"....", "...."}), 0.5), 25);
    EXPECT_EQ(m.count(), 0);
    EXPECT_EQ(noise_filter(m, 3).count(), 0);
}

TEST(StabilityObstacleMap, fullyOpaqueSprite) {
    Image im(64, 64);
    for (std::size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 255;
    SpriteObstacleTrace t;
    Mask m = sprite_obstacle(opacity_map(im, 0.5), 25, &t);
    EXPECT_EQ(t.chosen_line, 63);
    EXPECT_EQ(t.run_length, 64);
    EXPECT_EQ(m.count(), 64 + 2 * 16);  // the run plus arms of 64/4 above and below
}

TEST(StabilityObstacleMap, onePixelSprite) {
    Mask m = sprite_obstacle(opacity_map(sprite_from({"#"}), 0.5), 25);
    EXPECT_EQ(m.count(), 1);
    EXPECT_EQ(noise_filter(m, 2).count(), 0);  // one pixel in a 2x2 window: noise
}

TEST(StabilityObstacleMap, alphaExactlyAtTheThreshold) {
    Image im = sprite_from({"++++", "++++"});  // alpha 128 everywhere
    EXPECT_EQ(sprite_obstacle(opacity_map(im, 128 / 255.0), 25).count(), 0);
    EXPECT_GT(sprite_obstacle(opacity_map(im, 127 / 255.0), 25).count(), 0);
}

TEST(StabilityObstacleMap, deltaYLargerThanTheSprite) {
    Mask op = opacity_map(sprite_from({"##..", ".##.", "..##"}), 0.5);
    SpriteObstacleTrace t;
    sprite_obstacle(op, 1000000, &t);
    EXPECT_EQ(t.first_line, 0);
    EXPECT_EQ(t.last_line, 2);
}

TEST(StabilityObstacleMap, windowsOfOneEvenAndLargerThanTheMap) {
    Mask m(Rect{0, 0, 6, 5});
    for (int x = 0; x < 6; ++x) m.set(x, 2);
    EXPECT_EQ(noise_filter(m, 1).bits, m.bits);
    EXPECT_EQ(noise_filter(m, 2).count(), 5);   // each window of 2 holds 2 but the last (1)
    EXPECT_EQ(noise_filter(m, 4).count(), 3);   // windows of 4 need 4: the first 3 keep
    EXPECT_EQ(noise_filter(m, 7).count(), 0);   // 6 < 7 everywhere
    EXPECT_EQ(noise_filter(m, 255).count(), 0);
    Scene s = stability::with_light(300, 200);
    for (int n : {1, 2, 64, 255}) {
        s.params.noise_window = n;
        stability::stable_frame(s);
    }
}
