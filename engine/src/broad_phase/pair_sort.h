// The linear sort that puts a list of pairs in the one pair order, (a, b), shared by the pair
// collector and the AABB tree's candidate list. Internal to the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"

namespace engine::detail {

/// Sorts pairs into BodyPair's order (by a, then b) in linear time: a counting sort by b, then a
/// stable counting sort by a.
/// Both keys are body indices below `body_count`; `scratch` and `counts` are reused buffers.
void SortPairs(std::size_t body_count, std::vector<BodyPair>* pairs, std::vector<BodyPair>* scratch,
               std::vector<std::uint32_t>* counts);

/// The same sort from `parts`, joined, into `out` (room for all their pairs), where every a lies
/// in [a_begin, a_end) and every b below `body_count`: a thread can sort the pairs of its own
/// range of a. `out` may hold the parts (the second pass reads `scratch` only).
void SortPairsInto(std::span<const std::span<const BodyPair>> parts, std::uint32_t a_begin, std::uint32_t a_end,
                   std::size_t body_count, BodyPair* out, std::vector<BodyPair>* scratch,
                   std::vector<std::uint32_t>* counts);

}  // namespace engine::detail
