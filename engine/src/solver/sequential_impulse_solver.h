// The sequential-impulse contact solver (the course's seed method, the baseline): rounds of normal
// and friction impulses per contact point, then a projection that removes overlap beyond the
// slop. Internal to the engine.
#pragma once

#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "snapshot/byte_stream.h"
#include "step_context.h"
#include "solver/substep_passes.h"

namespace engine {

/// One point of a contact.
struct ImpulsePoint {
  double target_normal_velocity;  ///< after the solve: the restitution bounce, or 0 (rest)
  double normal_impulse;          ///< accumulated this step, N·s, never negative
  double tangent_impulse;         ///< accumulated this step, |.| ≤ friction · normal_impulse
};

/// The solver's working state for one contact.
struct ImpulseConstraint {
  BodyIndex a;
  BodyIndex b;
  Vec2 normal;
  double inv_mass_sum;
  double friction;
  int point_count;
  ImpulsePoint points[2];
};

}  // namespace engine

namespace engine::detail {

/// Sets up one constraint per contact from the velocities before the solve.
void PrepareContacts(std::span<const Contact> contacts, std::span<const BodyState> states,
                     std::span<const BodyInfo> infos, double restitution_threshold,
                     std::vector<ImpulseConstraint>* constraints);

/// Gauss-Seidel passes over all contact points, friction before the normal impulse so that
/// non-penetration has the last word in every pass.
void SolveVelocities(std::span<ImpulseConstraint> constraints, std::span<BodyState> states,
                     std::span<const BodyInfo> infos, int iterations);

/// Moves overlapping bodies apart along the normal, in proportion to inverse mass.
/// `positions_before` are the positions the contacts were measured at.
void CorrectPositions(std::span<const Contact> contacts, std::span<const Vec2> positions_before,
                      std::span<BodyState> states, std::span<const BodyInfo> infos,
                      double linear_slop, double correction_fraction);

class SequentialImpulseSolver {
 public:
  /// Its contacts are the bodies' real overlap only: no speculative margin.
  static constexpr bool kSpeculative = false;
  /// Fills in the automatic settings (0 passes: 10 per step).
  static void FillAutomaticSettings(WorldDef* def);

  /// One step: free motion, impulses, then the projection of what overlap is left.
  void Step(StepContext& context);
  /// Nothing carries over from step to step but the contacts' impulses (the world saves those).
  void Save(ByteWriter&) const {}
  bool Load(ByteReader&, std::size_t) { return true; }

 private:
  std::vector<ImpulseConstraint> constraints_;
  std::vector<std::uint8_t> pushed_;
  std::vector<Vec2> push_linear_;  ///< the joints' push-out (JointSolver::PushOut)
  std::vector<double> push_angular_;
};

}  // namespace engine::detail
