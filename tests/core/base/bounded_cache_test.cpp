// The tracers' tree caches (core/src/base/bounded_cache.hpp): what they keep stays
// within their budget, the least recently used dropped first, and a value a
// caller holds outlives its drop.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/bounded_cache.hpp"

using namespace isolux;

namespace {
// A value of `n` bytes, counting its builds.
struct Counted {
    std::vector<char> bytes;
};
std::shared_ptr<const Counted> sized(std::size_t n, int& builds) {
    ++builds;
    return std::make_shared<Counted>(Counted{std::vector<char>(n)});
}
std::size_t size_of(const Counted& c) { return c.bytes.size(); }
}  // namespace

TEST(BoundedCache, keepsWithinItsBudgetDroppingTheLeastRecentlyUsedFirst) {
    BoundedCache<int, Counted> cache(250);
    int builds = 0;
    auto get = [&](int key) { return cache.get(key, [&] { return sized(100, builds); }, size_of); };
    get(1), get(2);
    EXPECT_EQ(builds, 2);
    EXPECT_EQ(cache.bytes_held(), 200u);
    get(1);  // kept: no build, and now the most recently used
    EXPECT_EQ(builds, 2);
    get(3);  // 300 > 250: 2, the least recently used, goes
    EXPECT_EQ(builds, 3);
    EXPECT_EQ(cache.size(), 2u);
    EXPECT_LE(cache.bytes_held(), 250u);
    get(1);
    EXPECT_EQ(builds, 3) << "1 was used after 2, so 2 went, not 1";
    get(2);
    EXPECT_EQ(builds, 4) << "2 was dropped: built again";
    for (int k = 10; k < 100; ++k) {
        get(k);
        EXPECT_LE(cache.bytes_held(), 250u) << "after key " << k;
    }
}

TEST(BoundedCache, aValueOverTheBudgetIsKeptAloneAndAHeldValueOutlivesItsDrop) {
    BoundedCache<std::string, Counted> cache(50);
    int builds = 0;
    const auto small = cache.get("small", [&] { return sized(40, builds); }, size_of);
    const auto big = cache.get("big", [&] { return sized(80, builds); }, size_of);
    EXPECT_EQ(cache.size(), 1u) << "the newest stays even alone over budget; the rest go";
    EXPECT_EQ(cache.bytes_held(), 80u);
    EXPECT_EQ(small->bytes.size(), 40u) << "dropped from the cache, still held here";
    cache.get("big", [&] { return sized(80, builds); }, size_of);
    EXPECT_EQ(builds, 2);
}
