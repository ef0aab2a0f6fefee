// Images (image_file.cpp): sixteen-bit alpha at its own precision.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <sys/stat.h>

#include "isolux/error.hpp"
#include "isolux/isolux.hpp"
#include "isolux/tiled.hpp"
#include "isolux/opacity_map.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/world.hpp"
#include "test_util.hpp"

using namespace isolux;
using isolux::test::error_of;
using isolux::test::TempDir;
namespace fs = std::filesystem;

TEST(Image, sixteenBitAlphaIsComparedAtItsOwnPrecision) {
    // Alpha 32750 / 65535 = 0.49973: above a threshold of 0.4995, though its
    // 8-bit rounding (127 / 255 = 0.49804) is below it.
    TempDir d;
    auto out = OIIO::ImageOutput::create("png");
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(2, 1, 4, OIIO::TypeDesc::UINT16);
    spec.attribute("oiio:UnassociatedAlpha", 1);
    const std::uint16_t px[8] = {60000, 60000, 60000, 32750, 60000, 60000, 60000, 32700};
    ASSERT_TRUE(out->open((d.path / "a16.png").string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT16, px));
    ASSERT_TRUE(out->close());
    const Image im = load_image(d.path / "a16.png");
    ASSERT_EQ(im.alpha16.size(), 2u);
    EXPECT_EQ(im.alpha16[0], 32750);
    EXPECT_EQ(im.at(0, 0)[3], 127);
    const Mask m = opacity_map(im, 0.4995);
    EXPECT_TRUE(m.get(0, 0));   // 0.49973 > 0.4995
    EXPECT_FALSE(m.get(1, 0));  // 32700 / 65535 = 0.49897 < 0.4995
}
