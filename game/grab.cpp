// The drag rule: finding the body under the cursor, and the target joint that holds it.
#include "game/grab.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace game {

namespace {

// The cursor as a query shape: a disc a micrometre across, since a query needs a positive size.
constexpr double kCursorRadius = 1e-6;

}  // namespace

std::optional<engine::BodyId> GrabbableAt(const engine::World& world, engine::Vec2 p) {
  engine::Shape cursor;
  cursor.type = engine::ShapeType::kCircle;
  cursor.radius = kCursorRadius;
  const std::vector<engine::BodyId> under = world.OverlapShape(cursor, p, 0.0);
  // Slot order: from the back, the first dynamic one is on top.
  for (auto it = under.rbegin(); it != under.rend(); ++it) {
    if (!engine::HasInfiniteMass(world.Info(*it))) return *it;
  }
  return std::nullopt;
}

engine::JointDef GrabJoint(const engine::World& world, engine::BodyId body, engine::Vec2 p) {
  engine::JointDef def;
  def.type = engine::JointType::kTarget;
  def.body_b = body;
  def.anchor = p;
  def.target = p;
  def.spring = engine::JointSpring{kGrabHertz, kGrabDampingRatio};
  const double gravity = std::max(engine::Length(world.Def().gravity), kGrabLeastGravity);
  def.max_force = kGrabForcePerWeight * world.Info(body).mass * gravity;
  return def;
}

std::optional<engine::JointId> CurrentGrab(const engine::World& world) {
  for (const engine::JointId id : world.JointIds()) {
    if (world.GetJointDef(id).type == engine::JointType::kTarget) return id;
  }
  return std::nullopt;
}

std::optional<engine::BodyId> Grab(engine::World& world, engine::Vec2 p) {
  Release(world);
  const std::optional<engine::BodyId> body = GrabbableAt(world, p);
  if (body) world.CreateJoint(GrabJoint(world, *body, p));
  return body;
}

bool Drag(engine::World& world, engine::Vec2 p) {
  const std::optional<engine::JointId> grab = CurrentGrab(world);
  if (grab) world.SetJointTarget(*grab, p);
  return grab.has_value();
}

bool Release(engine::World& world) {
  const std::optional<engine::JointId> grab = CurrentGrab(world);
  if (grab) world.DestroyJoint(*grab);
  return grab.has_value();
}

}  // namespace game
