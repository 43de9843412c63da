// Which pairs of a list lie within a distance, kept in list order: the fluid's pairs within its
// kernel, found each substep from the pairs listed once a step. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <utility>

#include "engine/math.h"

namespace engine::detail {

using ParticlePair = std::pair<std::uint32_t, std::uint32_t>;

/// Copies to `out`, in order, the pairs (i, j) of `pairs` with |x[i] − x[j]|² < `r2`, the
/// squared distance worked out as LengthSquared(x[i] − x[j]); returns how many. Writes only
/// within out[0, pairs.size()).
std::uint32_t PairsWithin(const Vec2* x, std::span<const ParticlePair> pairs, double r2, ParticlePair* out);

}  // namespace engine::detail
