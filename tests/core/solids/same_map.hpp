// Two occluder maps held equal field by field (the solids tests' shared check).
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "isolux/occluder_map.hpp"

namespace isolux::test {

// Every field of two occluder maps, equal.
inline void expect_same_map(const OccluderMap& a, const OccluderMap& b, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(a.rect, b.rect);
    EXPECT_TRUE(a.spans == b.spans);
    EXPECT_EQ(a.surface.instance, b.surface.instance);
    EXPECT_EQ(a.surface.height, b.surface.height);
    // The sprite points by ground pixel: the same lists in the same order
    // (an edit's padding, rows = unlisted, left out and counted).
    auto lists = [](const OccluderMap& m, std::size_t& padding) {
        std::vector<std::vector<OccluderMap::Shown>> out;
        padding = 0;
        for (std::size_t g = 0; g + 1 < m.shown_start.size(); ++g) {
            out.emplace_back();
            for (std::uint32_t k = m.shown_start[g]; k < m.shown_start[g + 1]; ++k)
                if (m.shown[k].rows == OccluderMap::unlisted) ++padding;
                else out.back().push_back(m.shown[k]);
        }
        EXPECT_EQ(m.shown_start.empty() ? 0 : m.shown_start.back(), m.shown.size());
        return out;
    };
    std::size_t padding_a = 0, padding_b = 0;
    EXPECT_TRUE(lists(a, padding_a) == lists(b, padding_b));
    EXPECT_EQ(padding_a, a.padding);
    EXPECT_EQ(padding_b, b.padding);
    EXPECT_EQ(a.flags, b.flags);
    EXPECT_EQ(a.tallest, b.tallest);
}

}  // namespace isolux::test
