// The shuffle that packs the kept pairs of four candidates to the front, for the AVX2 loops that
// keep some of four pairs (PairsWithin, the grid's neighbour search). Internal.
#pragma once

#include <cstdint>

namespace engine::detail {

/// For each 4-bit mask of pairs kept, the 32-bit lanes that move the kept pairs (two 32-bit
/// halves each) to the front, in order.
struct KeepTable {
  alignas(32) std::int32_t lanes[16][8];
  constexpr KeepTable() : lanes{} {
    for (int mask = 0; mask < 16; ++mask) {
      int at = 0;
      for (int q = 0; q < 4; ++q) {
        if (mask & (1 << q)) lanes[mask][2 * at] = 2 * q, lanes[mask][2 * at + 1] = 2 * q + 1, ++at;
      }
    }
  }
};
inline constexpr KeepTable kKeep;

}  // namespace engine::detail
