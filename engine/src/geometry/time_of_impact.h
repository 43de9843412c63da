// The first time two moving convex shapes come within a target separation, by conservative
// advancement on the GJK distance (Mirtich, "Impulse-based dynamic simulation of rigid body
// systems", 1996; Catto, "Continuous Collision", GDC 2013).
#pragma once

#include <cstdint>

#include "engine/math.h"
#include "geometry/gjk.h"
#include "geometry/manifold.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// A body's motion over one step: its centre of mass moves in a straight line from center1 to
/// center2 while its rotation goes from rotation1 to rotation2. The rotation in between is the
/// normalised linear blend of the two (cosine, sine) pairs, as Box2D v3 sweeps, so no sine or
/// cosine is needed; the turn within a step must be less than half a turn (π).
struct Sweep {
  Vec2 local_center;  ///< the centre of mass in the shape's frame
  Vec2 center1;       ///< world, at the step's start
  Vec2 center2;       ///< world, at its end
  Rot rotation1;
  Rot rotation2;
};

/// Where the shape's frame stands at fraction t ∈ [0, 1] of the step.
Transform SweepTransform(const Sweep& sweep, double t);

enum class ToiState : std::uint8_t {
  kHit,         ///< the shapes come within target ± tolerance at `fraction`
  kSeparated,   ///< they stay farther apart than that for the whole step
  kOverlapped,  ///< they are already closer than target − tolerance at the start
  kFailed,      ///< the iteration cap ran out; `fraction` is safe (no contact before it)
};

struct ToiOutput {
  ToiState state = ToiState::kSeparated;
  double fraction = 1.0;    ///< of the step
  double separation = 0.0;  ///< between the surfaces at `fraction`
  int iterations = 0;
};

struct ToiSettings {
  double target = kLinearSlop;            ///< separation to stop at, m
  double tolerance = 0.25 * kLinearSlop;  ///< how near the target counts as reaching it, m
  int max_iterations = 50;
};

/// Advances t by the separation over a bound on how fast the shapes can approach (the relative
/// velocity along the current normal plus each shape's turn rate times its reach from its
/// centre), which can never step past the first contact.
ToiOutput TimeOfImpact(const ShapeProxy& a, const Sweep& sweep_a, const ShapeProxy& b,
                       const Sweep& sweep_b, const ToiSettings& settings = {});

}  // namespace engine::geometry
