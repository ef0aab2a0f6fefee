// Large buffers backed by the kernel's transparent huge pages where it
// offers them on request (Linux's "madvise" mode, Debian's default): a
// buffer of tens of megabytes (a light of a thousand pixels' ray tree) is
// otherwise faulted in 4 KiB at a time, which on a virtual machine costs
// more than filling it, and read through a TLB that holds a sliver of it.
#pragma once
#include <cstddef>
#include <vector>

namespace isolux {

// Below this a buffer is left to the allocator as it is.
inline constexpr std::size_t huge_page_bytes = std::size_t(2) << 20;

// Asks the kernel to back [p, p + bytes) with huge pages where whole ones
// fit in it. Call before the memory is first written: pages already touched
// stay as they are. A no-op where the kernel has no such request.
void advise_huge_pages(void* p, std::size_t bytes);

// reserve(n), with the reserved buffer advised as above when it is large
// enough to hold a huge page. The vector's contents are kept.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
    if (n <= v.capacity()) return;
    v.reserve(n);
    if (v.capacity() * sizeof(T) >= 2 * huge_page_bytes) advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

// resize(n) of an empty vector through reserve_huge: zero-filled (or
// value-filled) after the advice, so its pages come in huge.
template <class T>
void assign_huge(std::vector<T>& v, std::size_t n, const T& value = T{}) {
    v.clear();
    reserve_huge(v, n);
    v.assign(n, value);
}

}  // namespace isolux
