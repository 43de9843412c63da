// Time integration of free motion (forces and velocities to positions). Internal to the engine.
#pragma once

#include <cstdint>
#include <span>

#include "engine/world.h"

namespace engine::detail {

/// v += g·dt for every moving (awake, dynamic) body. Saves each body's velocity from before the
/// kick in `start_velocities` (explicit Euler moves bodies with it).
void IntegrateVelocities(std::span<BodyState> states, std::span<const std::uint8_t> moving,
                         Vec2 gravity, double dt, std::span<Vec2> start_velocities);

/// Moves every dynamic body by its velocity. Semi-implicit Euler uses the velocity after the kick
/// and the contact impulses; explicit Euler the velocity from before the kick, plus the change
/// the contact impulses made (without it, bodies would sink into what they rest on).
void IntegratePositions(Integrator integrator, std::span<BodyState> states,
                        std::span<const std::uint8_t> moving, std::span<const Vec2> start_velocities,
                        Vec2 gravity, double dt);

}  // namespace engine::detail
