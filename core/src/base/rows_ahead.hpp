// Inside core: asking for the rows of a world-wide array ahead of a pass.
//
// A light's area is a short piece of each row of a world-wide array (the
// obstacle map, the ground lines), each piece on another page: the hardware
// fetches none of it ahead. In a whole frame those rows have left every cache
// (the blur and the composite stream tens of MB between two traces), so each
// is a trip to memory; asking for the row `rows_ahead` below while working on
// this one overlaps the trips.
#pragma once
#include <cstddef>
#include <cstdint>

namespace isolux {

// Enough rows to cover a trip to memory (~100+ ns in a VM) at the passes'
// ~10-20 ns per row of a 257-pixel area.
constexpr int rows_ahead = 8;

// Asks for the `bytes` from `row` (each of their cache lines).
inline void ask_for_row(const std::uint8_t* row, std::size_t bytes) {
    if (bytes == 0) return;
    for (std::size_t x = 0; x < bytes; x += 64) __builtin_prefetch(row + x);
    __builtin_prefetch(row + bytes - 1);
}

}  // namespace isolux
