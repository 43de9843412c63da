// The substep solver's working state for one contact: SubstepConstraint where something can turn,
// LinearConstraint where nothing can. Internal to the engine.
#pragma once

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

/// One point of a contact. Pairs that cannot turn use a single point at the centres (anchors
/// zero): every point of their manifold has the same Jacobian.
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

/// One contact in a world where something can turn. Laid out for the passes over the pairs in
/// it that cannot: all they read lies in the first two cache lines (the header and the first
/// point's scalars); the angular fields come last.
struct alignas(64) SubstepConstraint {
  BodyIndex a;
  BodyIndex b;
  int point_count;
  bool angular;           ///< either body can turn: points carry anchors and angular terms
  Vec2 normal;
  double inv_mass_a;
  double inv_mass_b;
  double friction;
  SubstepPoint points[2];
  double inv_inertia_a;
  double inv_inertia_b;
};

/// One contact in a world where nothing can turn (the axis-aligned game): one row at the
/// centres, as every point of such a pair's manifold has the same Jacobian. 80 bytes against
/// SubstepConstraint's 256: the passes stream all the constraints of a pile several times a
/// substep, and the bytes they read are most of their time. The field names are SubstepPoint's,
/// so the passes read either alike.
struct LinearConstraint {
  BodyIndex a;
  BodyIndex b;
  Vec2 normal;
  double inv_mass_a;
  double inv_mass_b;
  double normal_mass;      ///< 1 / (inv_mass_a + inv_mass_b): the effective mass in any direction
  double base_separation;  ///< the separation at the step's start
  double normal_impulse;   ///< accumulated per substep, warm-started from the last step
  double tangent_impulse;
  double friction;
};

}  // namespace engine
