// The solids' geometry (solid.cpp): segments against boxes, empty solids.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "isolux/hash.hpp"
#include "isolux/height_rays.hpp"
#include "isolux/light_trace.hpp"
#include "isolux/tileset_generator.hpp"
#include "isolux/truth.hpp"
#include "test_util.hpp"
#include "frame/trace_hooks.hpp"

using namespace isolux;

TEST(Solid, aSegmentThroughABoxHitsItAndOneAboveMisses) {
    const Solid box{SolidKind::box, {0, 0, 0}, {10, 10, 10}};
    EXPECT_TRUE(segment_hits(box, {-5, 5, 5}, {15, 5, 5}, 1));
    EXPECT_FALSE(segment_hits(box, {-5, 5, 15}, {15, 5, 15}, 1));
    EXPECT_FALSE(segment_hits(box, {-5, 5, 5}, {15, 5, 5}, 0.2));  // stops before reaching it
    const Solid ball{SolidKind::ellipsoid, {0, 0, 10}, {4, 4, 4}};
    EXPECT_TRUE(segment_hits(ball, {-10, 0, 10}, {10, 0, 10}, 1));
    EXPECT_FALSE(segment_hits(ball, {-10, 5, 10}, {10, 5, 10}, 1));
    const Solid post{SolidKind::cylinder, {0, 0, 0}, {2, 2, 20}};
    EXPECT_TRUE(segment_hits(post, {-5, 0, 19}, {5, 0, 19}, 1));
    EXPECT_FALSE(segment_hits(post, {-5, 0, 21}, {5, 0, 21}, 1));
    const Solid cone{SolidKind::cone, {0, 0, 0}, {10, 10, 20}};
    EXPECT_TRUE(segment_hits(cone, {-20, 0, 1}, {20, 0, 1}, 1));
    EXPECT_FALSE(segment_hits(cone, {-20, 6, 10}, {20, 6, 10}, 1));  // radius 5 at z = 10
    EXPECT_TRUE(segment_hits(cone, {-20, 4, 10}, {20, 4, 10}, 1));
}

TEST(Solid, aSolidOfZeroSizeCastsNothing) {
    for (const Solid& s : {Solid{SolidKind::box, {0, 0, 0}, {10, 0, 10}}, Solid{SolidKind::cylinder, {0, 0, 0}, {0, 0, 10}},
                           Solid{SolidKind::cone, {0, 0, 0}, {5, 5, 0}}, Solid{SolidKind::ellipsoid, {0, 0, 0}, {5, 0, 5}}})
        EXPECT_FALSE(segment_hits(s, {-20, 0, 0}, {20, 0, 0}, 1)) << to_string(s.kind);
}
