// What a step reports besides the bodies' new states.
#pragma once

#include <cstdint>

#include "engine/ids.h"

namespace engine {

/// The first non-finite number the simulation produced: which body, in which step, and which
/// part of its state. Inputs are checked when they enter, so this means the numbers overflowed.
struct NumericFault {
  std::int64_t step;  ///< the step that produced it (StepCount() before that step)
  BodyId body;
  const char* what;   ///< "position", "velocity", "angle" or "angular velocity"
};

}  // namespace engine
