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
  /// Impulses accumulated on each point last step (N·s), carried over to warm-start the next.
  double normal_impulse[2] = {0.0, 0.0};
  double tangent_impulse[2] = {0.0, 0.0};
};

/// Seed solver: one point of a contact.
struct PointConstraint {
  double target_normal_velocity;  ///< after the solve: the restitution bounce, or 0 (rest)
  double normal_impulse;          ///< accumulated this step, N·s, never negative
  double tangent_impulse;         ///< accumulated this step, |.| ≤ friction · normal_impulse
};

/// Seed solver: its working state for one contact.
struct ContactConstraint {
  BodyId a;
  BodyId b;
  Vec2 normal;
  double inv_mass_sum;
  double friction;
  int point_count;
  PointConstraint points[2];
};

/// Substep solver: one point of a contact. Pairs that cannot turn use a single point at the
/// centres (anchors zero): every point of their manifold has the same Jacobian.
struct SubstepPoint {
  /// Separation at the step's start less Dot(anchor_b − anchor_a, normal), so that adding the
  /// anchors' current offset gives the separation now.
  double base_separation;
  double normal_mass;      ///< 1 / effective mass along the normal
  double tangent_mass;
  double normal_impulse;   ///< accumulated per substep, warm-started from the last step
  double tangent_impulse;
  double push_impulse;     ///< accumulated this substep by the push-out (split impulse)
  Vec2 anchor_a;           ///< from A's centre at the step's start, m (zero without turning)
  Vec2 anchor_b;
};

/// Substep solver: its working state for one contact. Laid out for the passes over pairs that
/// cannot turn, most of a large scene: all they read lies in the first two cache lines (the
/// header and the first point's scalars); the angular and impact-pass fields come last.
struct alignas(64) SubstepConstraint {
  BodyId a;
  BodyId b;
  std::uint32_t contact;  ///< index into the world's contacts, to store impulses back
  int point_count;
  bool angular;           ///< either body can turn: points carry anchors and angular terms
  Vec2 normal;
  double inv_mass_a;
  double inv_mass_b;
  double friction;
  SubstepPoint points[2];
  double restitution;
  double impact_lag;       ///< m the impact pass asks the bodies to be moved apart after the step
  double inv_inertia_a;
  double inv_inertia_b;
};

}  // namespace engine
