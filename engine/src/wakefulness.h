// What the per-body `awake` (or `moving`) mask holds. Internal to the engine.
#pragma once

#include <cstdint>

namespace engine::detail {

/// Dynamic bodies sleep or are awake; a kinematic body moves while it has a velocity (integrated,
/// but no force acts on it); static and disabled bodies rest. Integrators move every body that
/// is not resting; forces act on awake ones only.
enum Wakefulness : std::uint8_t { kResting = 0, kAwake = 1, kKinematicMoving = 2 };

}  // namespace engine::detail
