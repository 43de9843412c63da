// Each body's move since the step's start, made for the passes under test as the solver's passes
// that move the bodies make it (engine::detail::MoveMeasure).
#pragma once

#include <cstddef>
#include <span>

#include "engine/body.h"
#include "integrate.h"

namespace testing {

/// MoveMeasure for the bodies [begin, end).
inline void MeasureMovesIn(std::span<const engine::BodyState> states, std::span<const engine::Vec2> start,
                           std::span<engine::Vec2> moved, std::size_t begin, std::size_t end) {
  const engine::detail::MoveMeasure measure{start, moved};
  for (std::size_t i = begin; i < end; ++i) measure.At(states, i);
}

/// MoveMeasure for every body.
inline void MeasureMoves(std::span<const engine::BodyState> states, std::span<const engine::Vec2> start,
                         std::span<engine::Vec2> moved) {
  MeasureMovesIn(states, start, moved, 0, states.size());
}

}  // namespace testing
