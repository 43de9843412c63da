// Explicit and semi-implicit Euler, velocity Verlet, midpoint and RK4 over the whole system:
// springs and gravitation couple bodies, so every stage evaluates the forces on all of them.
#include "integrate.h"

#include <algorithm>

namespace engine::detail {

namespace {

void Offset(std::span<const BodyState> base, std::span<const std::uint8_t> moving, bool rotation, double c,
            std::span<const Vec2> k_velocity, std::span<const double> k_angular_velocity,
            std::span<const Vec2> k_linear, std::span<const double> k_angular,
            std::vector<BodyState>* stage) {
  stage->assign(base.begin(), base.end());
  for (std::size_t i = 0; i < base.size(); ++i) {
    if (!moving[i]) continue;
    BodyState& s = (*stage)[i];
    s.position += c * k_velocity[i];
    s.velocity += c * k_linear[i];
    if (!rotation) continue;
    s.angle += c * k_angular_velocity[i];
    s.angular_velocity += c * k_angular[i];
  }
}

// Sizes the free motion and the stages' scratch for n bodies, and takes the first stage's k from
// the step's start: the velocities, and the accelerations the forces give.
void StartFreeStep(const ForceModel& forces, std::span<const BodyState> states, FreeMotion* m) {
  const std::size_t n = states.size();
  m->velocity.resize(n);
  m->drift.resize(n);
  m->angular_velocity.resize(n);
  m->angular_drift.resize(n);
  for (int k = 0; k < 4; ++k) {
    m->stage_velocity[k].resize(n);
    m->stage_angular_velocity[k].resize(n);
    m->linear[k].resize(n);
    m->angular[k].resize(n);
  }
  for (std::size_t i = 0; i < n; ++i) {
    m->stage_velocity[0][i] = states[i].velocity, m->stage_angular_velocity[0][i] = states[i].angular_velocity;
  }
  forces.Evaluate(states, m->linear[0], m->angular[0]);
}

// Both end at v₀ + h·a₀; explicit Euler moves with v₀, semi-implicit Euler with the end velocity.
void EulerStep(bool semi_implicit, std::span<const BodyState> states, double h, FreeMotion* m) {
  const std::vector<Vec2>& v0 = m->stage_velocity[0];
  const std::vector<double>& w0 = m->stage_angular_velocity[0];
  const std::vector<Vec2>& a0 = m->linear[0];
  const std::vector<double>& alpha0 = m->angular[0];
  for (std::size_t i = 0; i < states.size(); ++i) {
    m->velocity[i] = states[i].velocity + a0[i] * h;
    m->angular_velocity[i] = states[i].angular_velocity + alpha0[i] * h;
    m->drift[i] = semi_implicit ? m->velocity[i] : v0[i];
    m->angular_drift[i] = semi_implicit ? m->angular_velocity[i] : w0[i];
  }
}

// x₁ = x₀ + h·v₀ + ½h²·a₀; a₁ at x₁ (and a predicted v₀ + h·a₀, for velocity-dependent forces);
// v₁ = v₀ + ½h·(a₀ + a₁).
void VelocityVerletStep(const ForceModel& forces, std::span<const BodyState> states, double h, FreeMotion* m) {
  const std::vector<Vec2>& v0 = m->stage_velocity[0];
  const std::vector<double>& w0 = m->stage_angular_velocity[0];
  std::vector<Vec2>* a = m->linear;
  std::vector<double>* alpha = m->angular;
  Offset(states, forces.moving, forces.rotation, h, v0, w0, a[0], alpha[0], &m->stage);
  for (std::size_t i = 0; i < states.size(); ++i) {
    m->stage[i].position = states[i].position + h * (v0[i] + 0.5 * h * a[0][i]);
    if (forces.rotation) m->stage[i].angle = states[i].angle + h * (w0[i] + 0.5 * h * alpha[0][i]);
  }
  forces.Evaluate(m->stage, a[1], alpha[1]);
  for (std::size_t i = 0; i < states.size(); ++i) {
    m->drift[i] = v0[i] + 0.5 * h * a[0][i];
    m->angular_drift[i] = w0[i] + 0.5 * h * alpha[0][i];
    m->velocity[i] = v0[i] + 0.5 * h * (a[0][i] + a[1][i]);
    m->angular_velocity[i] = w0[i] + 0.5 * h * (alpha[0][i] + alpha[1][i]);
  }
}

// The accelerations at the half step set the velocity; the velocity there, the drift.
void MidpointStep(const ForceModel& forces, std::span<const BodyState> states, double h, FreeMotion* m) {
  const std::vector<Vec2>& v0 = m->stage_velocity[0];
  const std::vector<double>& w0 = m->stage_angular_velocity[0];
  std::vector<Vec2>* a = m->linear;
  std::vector<double>* alpha = m->angular;
  Offset(states, forces.moving, forces.rotation, 0.5 * h, v0, w0, a[0], alpha[0], &m->stage);
  forces.Evaluate(m->stage, a[1], alpha[1]);
  for (std::size_t i = 0; i < states.size(); ++i) {
    m->drift[i] = m->stage[i].velocity;
    m->angular_drift[i] = m->stage[i].angular_velocity;
    m->velocity[i] = v0[i] + h * a[1][i];
    m->angular_velocity[i] = w0[i] + h * alpha[1][i];
  }
}

// k_i = (velocity, acceleration) at each stage, the next stage offset by c·k_i; the drift and
// the velocity change are their weighted means.
void RungeKutta4Step(const ForceModel& forces, std::span<const BodyState> states, double h, FreeMotion* m) {
  std::vector<Vec2>* v = m->stage_velocity;
  std::vector<double>* w = m->stage_angular_velocity;
  std::vector<Vec2>* a = m->linear;
  std::vector<double>* alpha = m->angular;
  const std::vector<Vec2>& v0 = v[0];
  const std::vector<double>& w0 = w[0];
  const double c[3] = {0.5 * h, 0.5 * h, h};
  for (int k = 1; k < 4; ++k) {
    Offset(states, forces.moving, forces.rotation, c[k - 1], v[k - 1], w[k - 1], a[k - 1], alpha[k - 1], &m->stage);
    forces.Evaluate(m->stage, a[k], alpha[k]);
    for (std::size_t i = 0; i < states.size(); ++i) v[k][i] = m->stage[i].velocity, w[k][i] = m->stage[i].angular_velocity;
  }
  for (std::size_t i = 0; i < states.size(); ++i) {
    m->drift[i] = (v[0][i] + 2.0 * v[1][i] + 2.0 * v[2][i] + v[3][i]) / 6.0;
    m->angular_drift[i] = (w[0][i] + 2.0 * w[1][i] + 2.0 * w[2][i] + w[3][i]) / 6.0;
    m->velocity[i] = v0[i] + h * ((a[0][i] + 2.0 * a[1][i] + 2.0 * a[2][i] + a[3][i]) / 6.0);
    m->angular_velocity[i] = w0[i] + h * ((alpha[0][i] + 2.0 * alpha[1][i] + 2.0 * alpha[2][i] + alpha[3][i]) / 6.0);
  }
}

// Drag stiffer than the step (h·rate > ½) would overshoot, in any explicit method: such a body
// takes an implicit Euler step with the rate from the step's start instead,
// v' = (v + h·a_other) / (1 + h·rate), stable at any h and at rest exactly at terminal speed.
// Gravity alone under an Euler step: the general path's arithmetic (StartFreeStep, EulerStep and
// the copy back), body by body in one loop, the bodies shared among threads. Five passes over
// the bodies became one.
void GravityEulerStep(bool semi_implicit, const ForceModel& forces, std::span<BodyState> states, double h,
                      FreeMotion* m, WorkerPool* pool, const PushVelocities* carried, const MoveMeasure* measure) {
  const std::size_t n = states.size();
  const double alpha = 0.0;
  if (semi_implicit) {
    // MoveBodies moves a body by its velocity alone under semi-implicit Euler: the free motion
    // is left unwritten (four stores a body each substep).
    const bool push_carried = carried != nullptr, rotation = forces.rotation;
    const PushVelocities push = push_carried ? *carried : PushVelocities{};
    const std::span<const std::uint8_t> moving = forces.moving;
    const Vec2 gravity = forces.def.gravity;
    const bool measuring = measure != nullptr;
    const MoveMeasure moves = measuring ? *measure : MoveMeasure{};
    ForEachIndex(pool, n, kMinSharedBodies, [=](std::uint32_t i) {  // by value: see ForEachIndex
      if (push_carried) MoveBodyByPush(states, push, rotation, h, i);
      if (measuring) moves.At(states, i);
      if (!moving[i]) return;
      const Vec2 a = moving[i] == kAwake ? gravity : Vec2{};
      states[i].velocity = states[i].velocity + a * h;
      if (rotation) states[i].angular_velocity = states[i].angular_velocity + alpha * h;
    });
    return;
  }
  m->velocity.resize(n);
  m->drift.resize(n);
  m->angular_velocity.resize(n);
  m->angular_drift.resize(n);
  const auto step = [&](std::uint32_t i) {
    if (carried) MoveBodyByPush(states, *carried, forces.rotation, h, i);
    if (measure) measure->At(states, i);
    const Vec2 a = forces.moving[i] == kAwake ? forces.def.gravity : Vec2{};
    const Vec2 v0 = states[i].velocity;
    const double w0 = states[i].angular_velocity;
    m->velocity[i] = v0 + a * h;
    m->angular_velocity[i] = w0 + alpha * h;
    m->drift[i] = v0;  // explicit Euler moves by the velocity the step began with
    m->angular_drift[i] = w0;
    if (!forces.moving[i]) return;
    states[i].velocity = m->velocity[i];
    if (forces.rotation) states[i].angular_velocity = m->angular_velocity[i];
  };
  ForEachIndex(pool, n, kMinSharedBodies, step);
}

void DampStiffDrag(const ForceModel& forces, std::span<const BodyState> states, double h, FreeMotion* m) {
  constexpr double kStiffDrag = 0.5;
  const std::vector<Vec2>& v0 = m->stage_velocity[0];
  const std::vector<Vec2>& a0 = m->linear[0];
  for (std::size_t i = 0; i < states.size() && (forces.damping || forces.def.fluid_density != 0.0); ++i) {
    if (!forces.moving[i]) continue;
    if (forces.def.fluid_density == 0.0 && forces.infos[i].linear_damping == 0.0) continue;  // no drag
    // Judged at the start and after one kick: a body at rest gains speed within the step.
    BodyState kicked = states[i];
    kicked.velocity = v0[i] + h * a0[i];
    const double rate = std::max(forces.DragRate(states[i], i), forces.DragRate(kicked, i));
    if (h * rate <= kStiffDrag) continue;
    const Vec2 other = a0[i] + rate * v0[i];  // every acceleration but the drag's
    m->velocity[i] = (v0[i] + h * other) / (1.0 + h * rate);
    m->drift[i] = m->velocity[i];
  }
}

}  // namespace

void FreeStep(Integrator integrator, const ForceModel& forces, std::span<BodyState> states,
              double h, FreeMotion* m, WorkerPool* pool, const PushVelocities* carried, const MoveMeasure* measure) {
  const bool euler = integrator == Integrator::kSemiImplicitEuler || integrator == Integrator::kExplicitEuler;
  if (euler && !forces.BeyondGravity()) {
    GravityEulerStep(integrator == Integrator::kSemiImplicitEuler, forces, states, h, m, pool, carried, measure);
    return;
  }
  // Forces read positions: every body moves first (the steps below change velocities alone).
  if (carried || measure) {
    ForEachIndex(pool, states.size(), kMinSharedBodies, [&](std::uint32_t i) {
      if (carried) MoveBodyByPush(states, *carried, forces.rotation, h, i);
      if (measure) measure->At(states, i);
    });
  }
  StartFreeStep(forces, states, m);
  switch (integrator) {
    case Integrator::kSemiImplicitEuler:
    case Integrator::kExplicitEuler:
      EulerStep(integrator == Integrator::kSemiImplicitEuler, states, h, m);
      break;
    case Integrator::kVelocityVerlet:
      VelocityVerletStep(forces, states, h, m);
      break;
    case Integrator::kMidpoint:
      MidpointStep(forces, states, h, m);
      break;
    case Integrator::kRungeKutta4:
      RungeKutta4Step(forces, states, h, m);
      break;
  }
  DampStiffDrag(forces, states, h, m);
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (!forces.moving[i]) continue;
    states[i].velocity = m->velocity[i];
    if (forces.rotation) states[i].angular_velocity = m->angular_velocity[i];
  }
}

namespace {

void MoveBody(Integrator integrator, std::span<BodyState> states, std::span<const std::uint8_t> moving,
              std::span<const std::uint8_t> pushed, bool rotation, const FreeMotion& m, double h, std::uint32_t i) {
  if (!moving[i]) return;
  BodyState& s = states[i];
  if (integrator == Integrator::kSemiImplicitEuler || (!pushed.empty() && pushed[i])) {
    s.position += s.velocity * h;
    if (rotation) s.angle += s.angular_velocity * h;
  } else {
    s.position += (m.drift[i] + (s.velocity - m.velocity[i])) * h;
    if (rotation) s.angle += (m.angular_drift[i] + (s.angular_velocity - m.angular_velocity[i])) * h;
  }
}

}  // namespace

void MoveBodies(Integrator integrator, std::span<BodyState> states,
                std::span<const std::uint8_t> moving, std::span<const std::uint8_t> pushed,
                bool rotation, const FreeMotion& m, double h, WorkerPool* pool, const MoveMeasure* measure) {
  const bool measuring = measure != nullptr;
  const MoveMeasure moves = measuring ? *measure : MoveMeasure{};
  ForEachIndex(pool, states.size(), kMinSharedBodies, [=, &m](std::uint32_t i) {  // by value: see ForEachIndex
    MoveBody(integrator, states, moving, pushed, rotation, m, h, i);
    if (measuring) moves.At(states, i);
  });
}

void MoveBodiesIn(Integrator integrator, std::span<BodyState> states, std::span<const std::uint8_t> moving,
                  std::span<const std::uint8_t> pushed, bool rotation, const FreeMotion& m, double h,
                  std::uint32_t begin, std::uint32_t end, const MoveMeasure* measure) {
  for (std::uint32_t i = begin; i < end; ++i) {
    MoveBody(integrator, states, moving, pushed, rotation, m, h, i);
    if (measure) measure->At(states, i);
  }
}

}  // namespace engine::detail
