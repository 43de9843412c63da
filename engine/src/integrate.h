// Time integration of free motion, for every integrator the engine offers. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "engine/spring.h"
#include "engine/world_def.h"
#include "forces/force_model.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

/// One free step of every moving body, as velocities: where the integrator would leave the
/// velocity (`velocity`), and the mean velocity it would move the body with over the step
/// (`drift`, so that x_{n+1} = x_n + h·drift). Contacts then change the velocity, and the body
/// moves by that change too (MoveBodies). Under semi-implicit Euler, which moves a body by its
/// velocity alone, the step with gravity alone (the usual one) leaves it unwritten.
struct FreeMotion {
  std::vector<Vec2> velocity;
  std::vector<Vec2> drift;
  std::vector<double> angular_velocity;
  std::vector<double> angular_drift;
  // Scratch for the stages: each stage's state, and its velocities and accelerations (k).
  std::vector<BodyState> stage;
  std::vector<Vec2> stage_velocity[4];
  std::vector<double> stage_angular_velocity[4];
  std::vector<Vec2> linear[4];
  std::vector<double> angular[4];
};

/// Push velocities of the split impulse, linear and angular: how fast the contacts' push-out
/// moves each body, apart from its velocity.
struct PushVelocities {
  std::span<Vec2> linear;
  std::span<double> angular;
};

/// Each body's move since the step's start, `moved[i]` = position − start: the separations the
/// wide passes and shock propagation measure follow from it (one Vec2 a body read, where the
/// position and the start had been two; the same subtraction, so the same bits). Made by the
/// passes that move the bodies (FreeStep, MoveBodies), each body's as soon as it has moved: a
/// pass of its own over every body cost a second sweep of the states and, on several threads,
/// a hand-off each time.
struct MoveMeasure {
  std::span<const Vec2> start_positions;
  std::span<Vec2> moved;
  void At(std::span<const BodyState> states, std::size_t i) const { moved[i] = states[i].position - start_positions[i]; }
};

/// Moves body i by h times its push velocity and zeroes the push (angles only with rotation).
inline void MoveBodyByPush(std::span<BodyState> states, PushVelocities push, bool rotation, double h,
                           std::size_t i) {
  states[i].position += push.linear[i] * h;
  push.linear[i] = {};
  if (i < push.angular.size()) {
    if (rotation) states[i].angle += push.angular[i] * h;
    push.angular[i] = 0.0;
  }
}

/// Computes the free step of length h from `states` and sets each moving body's velocity to its
/// end-of-step value (positions stay, for the contact solver to see).
/// `pool`: threads to share the bodies among where gravity alone acts under an Euler step (each
/// body's step is then its own); the bits are the same either way.
/// `carried`: push velocities the last substep left to move by (MoveBodyByPush with this h,
/// `forces.rotation`), applied to every body before the free step: in the same pass over the
/// bodies where gravity alone acts under an Euler step, which reads no position.
/// `measure`: each body's move measured after the step (MoveMeasure).
void FreeStep(Integrator integrator, const ForceModel& forces, std::span<BodyState> states,
              double h, FreeMotion* motion, WorkerPool* pool = nullptr, const PushVelocities* carried = nullptr,
              const MoveMeasure* measure = nullptr);

/// Moves every moving body: by h·drift, plus h times whatever the contacts changed its velocity
/// by since FreeStep. Semi-implicit Euler moves by h·v exactly, and so does a body a contact
/// pushed this step (`pushed`; empty means none): a contact's impulse acts at the start of the
/// step, so h·v is where it leaves the body. The higher-order drift would move a body held at
/// rest by its contacts by −½·a·h² a step (Verlet, midpoint, RK4; −a·h² for explicit Euler):
/// hovering over the floor and creeping against a push that friction holds.
/// `pool`: threads to share the bodies among (each body's move is its own). `measure`: each
/// body's move measured after it (MoveMeasure).
void MoveBodies(Integrator integrator, std::span<BodyState> states,
                std::span<const std::uint8_t> moving, std::span<const std::uint8_t> pushed,
                bool rotation, const FreeMotion& motion, double h, WorkerPool* pool = nullptr,
                const MoveMeasure* measure = nullptr);
/// MoveBodies for the bodies [begin, end) alone, on the calling thread.
void MoveBodiesIn(Integrator integrator, std::span<BodyState> states, std::span<const std::uint8_t> moving,
                  std::span<const std::uint8_t> pushed, bool rotation, const FreeMotion& motion, double h,
                  std::uint32_t begin, std::uint32_t end, const MoveMeasure* measure = nullptr);

}  // namespace engine::detail
