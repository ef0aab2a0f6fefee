#include <gtest/gtest.h>

#include <set>

#include "isolux/hash.hpp"

using namespace isolux;

TEST(Hash, seedHashIsFnv1aThenSplitMix64) {
    // FNV-1a 64 of "" is the offset basis; of "a" it is 0xaf63dc4c8601ec8c
    // (the published test vector).
    EXPECT_EQ(hash_seed(""), mix64(0xCBF29CE484222325ull));
    EXPECT_EQ(hash_seed("a"), mix64(0xAF63DC4C8601EC8Cull));
    EXPECT_NE(hash_seed("a"), hash_seed("b"));
}

TEST(Hash, pcg32MatchesTheReferenceSequence) {
    // pcg32_srandom_r(&rng, 42, 54) from the PCG reference demo.
    Pcg32 rng(42, 54);
    const std::uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
    for (std::uint32_t e : expected) EXPECT_EQ(rng.next(), e);
}

TEST(Hash, belowStaysInRangeAndCoversIt) {
    Pcg32 rng(7);
    std::set<std::uint32_t> seen;
    for (int i = 0; i < 2000; ++i) {
        std::uint32_t v = rng.below(10);
        ASSERT_LT(v, 10u);
        seen.insert(v);
    }
    EXPECT_EQ(seen.size(), 10u);
    EXPECT_EQ(rng.below(0), 0u);
    EXPECT_EQ(rng.below(1), 0u);
    for (int i = 0; i < 1000; ++i) {
        double u = rng.unit();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
    }
}

TEST(Hash, valueNoiseIsBoundedContinuousAndDeterministic) {
    for (int i = 0; i < 200; ++i) {
        double x = i * 0.37 - 30, y = i * 0.11 + 5;
        double v = value_noise(99, x, y);
        ASSERT_GE(v, 0.0);
        ASSERT_LE(v, 1.0);
        EXPECT_EQ(v, value_noise(99, x, y));
        // Continuity: a tiny step changes the value a little.
        EXPECT_NEAR(v, value_noise(99, x + 1e-6, y), 1e-4);
    }
    EXPECT_NE(value_noise(1, 0.5, 0.5), value_noise(2, 0.5, 0.5));
    double f = fractal_noise(3, 1.3, 2.7, 4);
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
}
