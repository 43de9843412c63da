// Contacts between bodies: what the narrow phase found and what the solver accumulates on them.
#pragma once

#include <cstdint>

#include "engine/collide.h"

namespace engine {

/// A body's index in creation (scene) order.
using BodyId = std::uint32_t;

struct Contact {
  BodyId a;  ///< a < b
  BodyId b;
  Manifold manifold;   ///< normal points from a to b
  double restitution;  ///< the larger of the pair's
  double friction;     ///< the geometric mean of the pair's
};

struct PointConstraint {
  double target_normal_velocity;  ///< after the solve: the restitution bounce, or 0 (rest)
  double normal_impulse;          ///< accumulated this step, N·s, never negative
  double tangent_impulse;         ///< accumulated this step, |.| ≤ friction · normal_impulse
};

/// The solver's working state for one contact.
struct ContactConstraint {
  BodyId a;
  BodyId b;
  Vec2 normal;
  double inv_mass_sum;
  double friction;
  int point_count;
  PointConstraint points[2];
};

}  // namespace engine
