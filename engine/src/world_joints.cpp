// World's joint calls: making and destroying joints, reading where they stand, and what an
// embedder (or the mouse) changes between steps.
#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/world.h"
#include "require.h"
#include "world_impl.h"

namespace engine {

namespace {

using detail::IsNonNegativeFinite;
using detail::IsPositiveFinite;
using detail::Require;

void RequireValidSpring(const std::optional<JointSpring>& spring) {
  if (!spring) return;
  Require(IsPositiveFinite(spring->hertz) && IsNonNegativeFinite(spring->damping_ratio),
          "JointDef::spring needs hertz > 0 and damping_ratio >= 0, finite");
}

void RequireValid(const JointDef& def) {
  Require(IsFinite(def.anchor) && IsFinite(def.anchor_b) && IsFinite(def.axis) && IsFinite(def.target),
          "JointDef points must be finite");
  RequireValidSpring(def.spring);
  if (def.limits) {
    Require(std::isfinite(def.limits->lower) && std::isfinite(def.limits->upper) &&
                def.limits->lower <= def.limits->upper,
            "JointDef::limits must be finite with lower <= upper");
  }
  if (def.motor) {
    Require(std::isfinite(def.motor->speed) && IsNonNegativeFinite(def.motor->max_force),
            "JointDef::motor needs a finite speed and a cap >= 0");
  }
  switch (def.type) {
    case JointType::kPrismatic:
      Require(Length(def.axis) > 0.0, "JointDef::axis of a prismatic joint must not be zero");
      break;
    case JointType::kDistance: {
      for (const std::optional<double>& v : {def.length, def.min_length, def.max_length}) {
        Require(!v || IsNonNegativeFinite(*v), "JointDef lengths must be finite and >= 0");
      }
      Require(def.min_length.value_or(0.0) <= def.max_length.value_or(std::numeric_limits<double>::infinity()),
              "JointDef::min_length must not exceed max_length");
      break;
    }
    case JointType::kTarget:
      Require(def.spring.has_value() && IsPositiveFinite(def.max_force),
              "a target JointDef needs a spring and max_force > 0");
      break;
    default: break;
  }
  if (def.type != JointType::kRevolute && def.type != JointType::kPrismatic) {
    Require(!def.limits && !def.motor, "only revolute and prismatic joints take limits and a motor");
  }
}

// The point a joint is fixed to on a body, from the body's centre of mass in its frame.
Vec2 LocalPoint(const BodyState& s, Vec2 world) { return InvRotate(MakeRot(s.angle), world - s.position); }

}  // namespace

std::uint32_t World::Impl::JointSlot(JointId id, const char* call) const {
  if (!joints.IsLive(id)) {
    std::fprintf(stderr, "engine precondition failed: %s: joint id {%u, %u} is %s\n", call, id.index,
                 id.generation, id.index < joints.alive.size() ? "stale (its joint was destroyed)" : "unknown");
    std::abort();
  }
  return id.index;
}

void World::Impl::RebuildJoints() { joints.stale = true; }

JointId World::CreateJoint(const JointDef& def) {
  Impl& w = *impl_;
  RequireValid(def);
  const bool target = def.type == JointType::kTarget;
  const BodyIndex b = w.Slot(def.body_b, "CreateJoint");
  const BodyIndex a = target ? kNoBody : w.Slot(def.body_a, "CreateJoint");
  Require(a != b, "CreateJoint: a joint joins two different bodies");
  Require(!HasInfiniteMass(w.bodies.infos[b]) || (!target && !HasInfiniteMass(w.bodies.infos[a])),
          "CreateJoint: at least one of the bodies must be dynamic");
  detail::Joint j;
  j.def = def;
  j.a = a;
  j.b = b;
  const BodyState& sb = w.bodies.states[b];
  j.local_b = LocalPoint(sb, def.type == JointType::kDistance ? def.anchor_b : def.anchor);
  double angle_a = 0.0;
  if (!target) {
    const BodyState& sa = w.bodies.states[a];
    j.local_a = LocalPoint(sa, def.anchor);
    angle_a = sa.angle;
    j.local_axis = InvRotate(MakeRot(sa.angle), def.axis / Length(def.axis));
  }
  j.reference_angle = sb.angle - angle_a;
  if (def.type == JointType::kDistance) {
    constexpr double kUnbounded = std::numeric_limits<double>::infinity();
    j.length = def.length.value_or(Length(def.anchor_b - def.anchor));
    const bool range = def.min_length || def.max_length;
    j.min_length = def.min_length.value_or(0.0);
    j.max_length = def.max_length.value_or(kUnbounded);
    j.rigid_length = !range && !def.spring;
    // A length under the slop is held at the slop (as Box2D does): at 0 the anchors' line has no
    // direction to pull along, and a rigid joint there diverged.
    j.length = std::max(j.length, w.def.linear_slop);
    if (def.max_length) j.max_length = std::max(j.max_length, w.def.linear_slop);
    if (j.rigid_length) j.min_length = j.max_length = j.length;
  }
  const std::uint32_t slot = w.joints.Allocate();
  w.joints.joints[slot] = j;
  w.RebuildJoints();
  w.WakeAround(b);
  if (!target) w.WakeAround(a);
  return {slot, w.joints.generations[slot]};
}

void World::DestroyJoint(JointId id) {
  Impl& w = *impl_;
  const std::uint32_t slot = w.JointSlot(id, "DestroyJoint");
  const detail::Joint& j = w.joints.joints[slot];
  if (w.bodies.enabled[j.b]) w.WakeAround(j.b);
  if (j.a != kNoBody && w.bodies.enabled[j.a]) w.WakeAround(j.a);
  w.joints.Free(slot);
  w.RebuildJoints();
}

void World::Impl::DestroyJointsOf(BodyIndex body) {
  bool any = false;
  for (std::uint32_t slot = 0; slot < joints.joints.size(); ++slot) {
    if (!joints.alive[slot]) continue;
    const detail::Joint& j = joints.joints[slot];
    if (j.a != body && j.b != body) continue;
    const BodyIndex other = j.a == body ? j.b : j.a;
    if (other != kNoBody && bodies.enabled[other]) WakeAround(other);
    joints.Free(slot);
    any = true;
  }
  if (any) RebuildJoints();
}

bool World::IsValid(JointId id) const { return impl_->joints.IsLive(id); }
std::span<const JointId> World::JointIds() const { return impl_->joints.live_ids; }

const JointDef& World::GetJointDef(JointId id) const {
  return impl_->joints.joints[impl_->JointSlot(id, "GetJointDef")].def;
}

JointFrame World::Joint(JointId id) const {
  const Impl& w = *impl_;
  const detail::Joint& j = w.joints.joints[w.JointSlot(id, "Joint")];
  const BodyState& b = w.bodies.states[j.b];
  JointFrame frame;
  frame.anchor_b = b.position + Rotate(MakeRot(b.angle), j.local_b);
  frame.anchor_a = j.def.target;
  double angle_a = 0.0;
  Rot qa;
  if (j.a != kNoBody) {
    const BodyState& a = w.bodies.states[j.a];
    qa = MakeRot(a.angle);
    frame.anchor_a = a.position + Rotate(qa, j.local_a);
    angle_a = a.angle;
  }
  frame.angle = b.angle - angle_a - j.reference_angle;
  const Vec2 separation = frame.anchor_b - frame.anchor_a;
  if (j.def.type == JointType::kPrismatic) frame.translation = Dot(Rotate(qa, j.local_axis), separation);
  if (j.def.type == JointType::kDistance) frame.translation = Length(separation);
  return frame;
}

void World::SetJointTarget(JointId id, Vec2 target) {
  Impl& w = *impl_;
  detail::Joint& j = w.joints.joints[w.JointSlot(id, "SetJointTarget")];
  Require(j.def.type == JointType::kTarget, "SetJointTarget: not a target joint");
  Require(IsFinite(target), "SetJointTarget: the target must be finite");
  j.def.target = target;
  if (w.bodies.enabled[j.b]) w.WakeAround(j.b);
}

void World::SetMotorSpeed(JointId id, double speed) {
  Impl& w = *impl_;
  detail::Joint& j = w.joints.joints[w.JointSlot(id, "SetMotorSpeed")];
  Require(j.def.motor.has_value(), "SetMotorSpeed: the joint has no motor");
  Require(std::isfinite(speed), "SetMotorSpeed: the speed must be finite");
  j.def.motor->speed = speed;
  if (w.bodies.enabled[j.b]) w.WakeAround(j.b);
  if (j.a != kNoBody && w.bodies.enabled[j.a]) w.WakeAround(j.a);
}

}  // namespace engine
