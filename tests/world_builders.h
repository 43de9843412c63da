// Small helpers to build test worlds in a line each.
#pragma once

#include "engine/world.h"
#include "print_ids.h"

namespace testing {

inline engine::BodyDef Circle(engine::Vec2 position, double radius, engine::Vec2 velocity = {}) {
  engine::BodyDef def;
  def.shape.type = engine::ShapeType::kCircle;
  def.shape.radius = radius;
  def.position = position;
  def.velocity = velocity;
  return def;
}

inline engine::BodyDef Box(engine::Vec2 position, engine::Vec2 size, engine::Vec2 velocity = {}) {
  engine::BodyDef def;
  def.shape.type = engine::ShapeType::kBox;
  def.shape.half_extents = 0.5 * size;
  def.position = position;
  def.velocity = velocity;
  return def;
}

inline engine::BodyDef Static(engine::BodyDef def) {
  def.is_static = true;
  def.velocity = {};
  return def;
}

inline engine::BodyDef Kinematic(engine::BodyDef def, engine::Vec2 velocity = {}) {
  def.is_kinematic = true;
  def.velocity = velocity;
  return def;
}

inline engine::BodyDef Sensor(engine::BodyDef def) {
  def.is_sensor = true;
  return def;
}

inline engine::BodyDef WithMass(engine::BodyDef def, double mass) {
  def.mass = mass;
  return def;
}

inline engine::BodyDef WithMaterial(engine::BodyDef def, double restitution, double friction) {
  def.restitution = restitution;
  def.friction = friction;
  return def;
}

/// Both contact solvers, for tests that hold for each.
inline constexpr engine::ContactSolver kBothSolvers[] = {engine::ContactSolver::kSubstep,
                                                         engine::ContactSolver::kSequentialImpulse};

/// A static floor `width` m wide and 1 m thick whose top is y = 0.
inline engine::BodyDef Floor(double width = 20.0) { return Static(Box({0, -0.5}, {width, 1})); }

/// A spring between two bodies' centres.
inline engine::SpringDef Spring(engine::BodyId a, engine::BodyId b, double rest_length, double stiffness,
                                double damping = 0.0) {
  engine::SpringDef spring;
  spring.body_a = a;
  spring.body_b = b;
  spring.rest_length = rest_length;
  spring.stiffness = stiffness;
  spring.damping = damping;
  return spring;
}

inline engine::WorldDef NoGravity() {
  engine::WorldDef def;
  def.gravity = {0, 0};
  return def;
}

inline void StepTimes(engine::World& world, int steps) {
  for (int i = 0; i < steps; ++i) world.Step();
}

/// Semi-implicit Euler's free fall after n steps of h from rest-or-v0 under acceleration g, in
/// closed form: v_n = v0 + n·g·h, x_n = x0 + n·v0·h + g·h²·n(n+1)/2 (the exact parabola's
/// x0 + v0·t + g·t²/2 plus g·t·h/2, since each step moves with the velocity at its end).
struct FreeFall {
  double position;
  double velocity;
};
inline FreeFall SemiImplicitFall(double x0, double v0, double g, double h, long long n) {
  const double nn = static_cast<double>(n);
  return {x0 + nn * v0 * h + g * h * h * nn * (nn + 1.0) / 2.0, v0 + nn * g * h};
}

/// J, of the bodies' motion along (rotation not counted).
inline double LinearKineticEnergy(const engine::World& world) {
  double e = 0;
  for (const engine::BodyId id : world.BodyIds()) {
    e += 0.5 * world.Info(id).mass * engine::LengthSquared(world.State(id).velocity);
  }
  return e;
}

}  // namespace testing
