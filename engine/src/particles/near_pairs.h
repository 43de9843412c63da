// Which pairs of a list lie within a distance, kept in list order: the fluid's pairs within its
// kernel, found each substep from the pairs listed once a step. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <utility>

#include "engine/math.h"

namespace engine::detail {

using ParticlePair = std::pair<std::uint32_t, std::uint32_t>;

/// Where PairsWithin leaves each kept pair's offset x[i] − x[j] and its squared length.
struct PairOffsets {
  double* dx;
  double* dy;
  double* r2;
};

/// Copies to `out`, in order, the pairs (i, j) of `pairs` with |x[i] − x[j]|² < `r2`, the
/// squared distance worked out as LengthSquared(x[i] − x[j]), and their offsets to `offsets`;
/// returns how many. Writes only within [0, pairs.size()) of each. `lanes`: 0 for the widest
/// the processor has (eight with AVX-512), 4 for four (AVX2), 1 for one at a time.
std::uint32_t PairsWithin(const Vec2* x, std::span<const ParticlePair> pairs, double r2, ParticlePair* out,
                          const PairOffsets& offsets, int lanes = 0);

}  // namespace engine::detail
