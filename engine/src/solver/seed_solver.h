// The seed contact solver: sequential normal and friction impulses per contact point,
// then a projection that removes overlap beyond the slop. Internal to the engine.
#pragma once

#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"

namespace engine {

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

}  // namespace engine

namespace engine::detail {

/// Sets up one constraint per contact from the velocities before the solve.
void PrepareContacts(std::span<const Contact> contacts, std::span<const BodyState> states,
                     std::span<const BodyInfo> infos, double restitution_threshold,
                     std::vector<ContactConstraint>* constraints);

/// Gauss-Seidel passes over all contact points, friction before the normal impulse so that
/// non-penetration has the last word in every pass.
void SolveVelocities(std::span<ContactConstraint> constraints, std::span<BodyState> states,
                     std::span<const BodyInfo> infos, int iterations);

/// Moves overlapping bodies apart along the normal, in proportion to inverse mass.
/// `positions_before` are the positions the contacts were measured at.
void CorrectPositions(std::span<const Contact> contacts, std::span<const Vec2> positions_before,
                      std::span<BodyState> states, std::span<const BodyInfo> infos,
                      double linear_slop, double correction_fraction);

}  // namespace engine::detail
