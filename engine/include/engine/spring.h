// Springs between bodies or to fixed points (the other force generators, damping, air drag and
// gravitation, are settings of bodies and the world).
#pragma once

#include <optional>

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

/// A damped spring from a point fixed on body A to a point fixed on body B, or to a fixed world
/// point when there is no body B. Attached off the centre, it makes torque.
struct SpringDef {
  BodyId body_a;
  Vec2 local_a;                   ///< attachment in A's frame, m
  std::optional<BodyId> body_b;   ///< none: anchored to the world
  Vec2 local_b;                   ///< attachment in B's frame, or the world anchor point, m
  double rest_length = 0.0;       ///< m, ≥ 0
  double stiffness = 0.0;         ///< N/m, ≥ 0
  double damping = 0.0;           ///< N·s/m along the spring, ≥ 0
};

}  // namespace engine
