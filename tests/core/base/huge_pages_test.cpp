// Large buffers in huge pages (huge_pages.cpp): the contents are kept, and
// where the kernel hands out transparent huge pages on request, a large
// buffer advised before it is written is backed by them.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "base/huge_pages.hpp"

using namespace isolux;

namespace {

// The kernel's transparent huge page mode: "always", "madvise" or "never"
// (the bracketed word of /sys/kernel/mm/transparent_hugepage/enabled), ""
// where there is no such file.
std::string thp_mode() {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(f, line);
    const auto open = line.find('['), close = line.find(']');
    return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

// The kilobytes of huge pages backing the mapping that holds `p`
// (/proc/self/smaps' AnonHugePages), -1 when no mapping holds it.
long anon_huge_kb_at(const void* p) {
    std::ifstream f("/proc/self/smaps");
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    bool inside = false;
    for (std::string line; std::getline(f, line);) {
        std::uintptr_t lo = 0, hi = 0;
        char dash = 0;
        std::istringstream s(line);
        if (s >> std::hex >> lo >> dash >> hi && dash == '-') {
            inside = lo <= at && at < hi;
        } else if (inside && line.rfind("AnonHugePages:", 0) == 0) {
            return std::stol(line.substr(14));
        }
    }
    return -1;
}

}  // namespace

TEST(HugePages, reserveKeepsTheContentsAndAssignFillsWithTheValue) {
    std::vector<std::int32_t> v = {1, 2, 3};
    reserve_huge(v, std::size_t(4) << 20);
    EXPECT_GE(v.capacity(), std::size_t(4) << 20);
    EXPECT_EQ(v, (std::vector<std::int32_t>{1, 2, 3}));
    reserve_huge(v, 2);  // smaller: nothing changes
    EXPECT_EQ(v.size(), 3u);
    assign_huge(v, std::size_t(1) << 20, std::int32_t(7));
    ASSERT_EQ(v.size(), std::size_t(1) << 20);
    EXPECT_EQ(v.front(), 7);
    EXPECT_EQ(v.back(), 7);
    std::vector<std::uint8_t> small;
    assign_huge(small, 10);  // below a huge page: left to the allocator
    EXPECT_EQ(small, std::vector<std::uint8_t>(10, 0));
}

TEST(HugePages, aLargeAdvisedBufferIsBackedByHugePagesWhereTheKernelOffersThem) {
    const std::string mode = thp_mode();
    std::vector<std::uint8_t> v;
    assign_huge(v, std::size_t(32) << 20, std::uint8_t(1));
    const long kb = anon_huge_kb_at(v.data() + v.size() / 2);
    ASSERT_GE(kb, 0) << "no mapping in /proc/self/smaps holds the buffer";
    if (mode == "always" || mode == "madvise")
        EXPECT_GT(kb, 0) << "transparent huge pages are '" << mode << "', yet the advised 32 MiB buffer has none";
    else
        EXPECT_EQ(kb, 0) << "transparent huge pages are '" << mode << "': none can back the buffer";
    RecordProperty("thp_mode", mode);
    RecordProperty("anon_huge_kb", std::to_string(kb));
}
