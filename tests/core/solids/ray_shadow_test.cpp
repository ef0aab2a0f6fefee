// The sprite pass's per-ray state (core/src/solids/solids_pass_tree.hpp): what the
// spans a ray passed block, against the exact union of their intervals.
#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "isolux/hash.hpp"
#include "solids/solids_pass_tree.hpp"

using namespace isolux;

namespace {

// Whether descent u lies in one of the (from, to] intervals, or above the
// standing spans' least (H - hi) / s.
bool exactly_blocked(const std::vector<std::pair<double, double>>& crowns, double standing, double u) {
    if (u > standing) return true;
    return std::any_of(crowns.begin(), crowns.end(), [u](const auto& c) { return c.first < u && u <= c.second; });
}

}  // namespace

// Crowns drawn at random distances and heights: while the ray keeps every
// one apart, it blocks exactly their union; past `most`, it blocks all of
// it and more (the gaps it closed), never less.
TEST(RayShadow, blocksTheUnionOfTheSpansItPassed) {
    constexpr double H = 32;
    int exact_rays = 0, capped_rays = 0;
    for (std::uint64_t ray = 0; ray < 400; ++ray) {
        Pcg32 rng(ray + 1);
        RayShadow r;
        std::vector<std::pair<double, double>> crowns;
        double standing = RayShadow::inf;
        const int spans = 1 + int(rng.below(120));
        for (int s = 1; s <= spans; ++s) {
            Spans sp;
            const float low = float(rng.below(256)), high = low + 0.5f + float(rng.below(4));
            sp.add(rng.below(8) == 0 ? 0.f : low, high);
            r.pass(sp, s, H);
            if (sp.lower.low <= 0) standing = std::min(standing, (H - sp.lower.high) / s);
            else crowns.push_back({(H - sp.lower.high) / s, (H - sp.lower.low) / s});
        }
        // The union's disjoint pieces: how many a ray would have to keep.
        std::vector<std::pair<double, double>> merged = crowns;
        std::sort(merged.begin(), merged.end());
        std::vector<std::pair<double, double>> pieces;
        for (const auto& c : merged)
            if (!pieces.empty() && c.first <= pieces.back().second) pieces.back().second = std::max(pieces.back().second, c.second);
            else pieces.push_back(c);
        const bool kept_apart = int(pieces.size()) <= RayShadow::most;
        (kept_apart ? exact_rays : capped_rays)++;
        for (int i = 0; i <= 4000; ++i) {
            const double u = -8 + i * 0.004;
            const bool exact = exactly_blocked(crowns, standing, u);
            if (kept_apart) {
                ASSERT_EQ(r.blocks(u), exact) << "ray " << ray << " descent " << u;
            } else if (exact) {
                ASSERT_TRUE(r.blocks(u)) << "ray " << ray << " descent " << u;
            }
        }
    }
    // Both cases were met.
    EXPECT_GT(exact_rays, 50);
    EXPECT_GT(capped_rays, 10);
}

// A light inside a solid (a span at step 0 holding its height) is hidden
// from every point; one standing above it is not.
TEST(RayShadow, aLightInsideASolidIsHiddenFromAll) {
    Spans inside, below;
    inside.add(0, 40);
    below.add(0, 10);
    RayShadow hidden, seen;
    hidden.pass(inside, 0, 32);
    seen.pass(below, 0, 32);
    EXPECT_TRUE(hidden.hidden());
    EXPECT_TRUE(hidden.blocks(-1e9));
    EXPECT_FALSE(seen.hidden());
    EXPECT_FALSE(seen.blocks(1.0));
}
