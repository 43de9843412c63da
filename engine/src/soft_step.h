// The soft-step contact solver (after Erin Catto's Solver2D study, 2024): per substep integrate
// velocities, warm start, solve soft constraints, integrate positions, relax. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/world.h"

namespace engine::detail {

/// Soft constraint parameters for a spring of `hertz` with `damping_ratio`, stepped at `h`.
Softness MakeSoftness(double hertz, double damping_ratio, double h);

/// One constraint per contact, with the impulses carried over from the last step.
void PrepareSoftConstraints(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                            const WorldDef& def, std::vector<SoftConstraint>* constraints);

/// Applies the accumulated impulses again, so the solve starts from last step's answer.
void WarmStart(std::span<const SoftConstraint> constraints, std::span<BodyState> states);

/// One Gauss-Seidel pass over all contacts. With `use_bias`, overlap is pushed out softly;
/// without (the relax pass), only velocities are made consistent, which removes the push-out
/// velocity so it does not turn into bounce.
void SolveSoftConstraints(std::span<SoftConstraint> constraints, std::span<BodyState> states,
                          std::span<const Vec2> step_start_positions, double inv_h,
                          double max_push_out_speed, double linear_slop, bool use_bias);

/// Moves each pair of bodies apart by what the impact pass asked for.
void ApplyImpactLags(std::span<const SoftConstraint> constraints, std::span<BodyState> states);

/// Stores the accumulated impulses back on the contacts for the next step's warm start.
void StoreImpulses(std::span<const SoftConstraint> constraints, std::span<Contact> contacts);

}  // namespace engine::detail
