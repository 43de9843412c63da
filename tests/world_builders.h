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

inline engine::BodyDef WithMass(engine::BodyDef def, double mass) {
  def.mass = mass;
  return def;
}

inline engine::BodyDef WithMaterial(engine::BodyDef def, double restitution, double friction) {
  def.restitution = restitution;
  def.friction = friction;
  return def;
}

inline engine::WorldDef NoGravity() {
  engine::WorldDef def;
  def.gravity = {0, 0};
  return def;
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
