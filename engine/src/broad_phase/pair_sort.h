// Helpers the broad phases share so that every one of them emits the same sorted pair list.
// Internal to the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "broad_phase/broad_phase.h"

namespace engine::detail {

/// Sorts pairs by (a, b) in linear time: a counting sort by b, then a stable counting sort by a.
/// Both keys are body indices below `body_count`; `scratch` and `counts` are reused buffers.
void SortPairs(std::size_t body_count, std::vector<BodyPair>* pairs, std::vector<BodyPair>* scratch,
               std::vector<std::uint32_t>* counts);

}  // namespace engine::detail
