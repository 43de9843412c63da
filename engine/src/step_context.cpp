// Numeric faults: the first non-finite number the simulation produced.
#include "step_context.h"

#include <cmath>

namespace engine::detail {

std::optional<NumericFault> FindNonFinite(std::span<const BodyState> states, std::int64_t step) {
  for (BodyIndex id = 0; id < states.size(); ++id) {
    const BodyState& s = states[id];
    const char* what = !IsFinite(s.position)                ? "position"
                       : !IsFinite(s.velocity)              ? "velocity"
                       : !std::isfinite(s.angle)            ? "angle"
                       : !std::isfinite(s.angular_velocity) ? "angular velocity"
                                                            : nullptr;
    if (what) return NumericFault{step, id, what};
  }
  return std::nullopt;
}

}  // namespace engine::detail
