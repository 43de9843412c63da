// World's body calls: creating and destroying bodies, and what an embedder changes between
// steps (placement, velocities, forces, enabling, filters, user data, springs).
#include <algorithm>
#include <cmath>

#include "engine/world.h"
#include "require.h"
#include "world_impl.h"

namespace engine {

namespace {

using detail::IsNonNegativeFinite;
using detail::IsPositiveFinite;
using detail::Require;

void RequireValid(const BodyDef& def) {
  const Shape& shape = def.shape;
  if (def.parts.empty()) {
    Require(shape.type == ShapeType::kCircle ? IsPositiveFinite(shape.radius)
            : shape.type == ShapeType::kBox  ? IsPositiveFinite(shape.half_extents.x) &&
                                                  IsPositiveFinite(shape.half_extents.y)
                                             : false,
            "BodyDef::shape must be a circle or box of positive finite size (other shapes go in parts)");
  }
  for (const ShapePart& part : def.parts) {
    if (const std::optional<PartProblem> problem = CheckShapePart(part, def.is_static)) {
      std::fprintf(stderr, "engine precondition failed: BodyDef::parts: %s %s\n", problem->key.c_str(),
                   problem->message.c_str());
      std::abort();
    }
  }
  Require(IsFinite(def.position) && IsFinite(def.velocity) && std::isfinite(def.angle) &&
              std::isfinite(def.angular_velocity),
          "BodyDef state must be finite");
  Require(IsNonNegativeFinite(def.restitution) && IsNonNegativeFinite(def.friction),
          "BodyDef restitution and friction must be finite and >= 0");
  Require(IsNonNegativeFinite(def.linear_damping) && IsNonNegativeFinite(def.angular_damping) &&
              std::isfinite(def.drag_coefficient),
          "BodyDef damping must be finite and >= 0, the drag coefficient finite");
  Require(!(def.is_static && def.is_kinematic), "BodyDef cannot be both static and kinematic");
  Require(def.is_static || def.is_kinematic || !def.parts.empty() || IsPositiveFinite(detail::BodyMass(def)),
          "BodyDef mass (or density) must be positive and finite");
}



}  // namespace

BodyIndex World::Impl::Slot(BodyId id, const char* call) const {
  if (!bodies.IsLive(id)) {
    std::fprintf(stderr, "engine precondition failed: %s: body id {%u, %u} is %s\n", call, id.index,
                 id.generation, id.index < bodies.alive.size() ? "stale (its body was destroyed)" : "unknown");
    std::abort();
  }
  return id.index;
}

void World::Impl::WakeAround(BodyIndex index) {
  if (HasInfiniteMass(bodies.infos[index])) return WakeTouching(index);
  detail::WakeIsland(index, bodies.infos, sleep.View());
}

void World::Impl::WakeTouching(BodyIndex index) {
  detail::WakeIsland(index, bodies.infos, sleep.View());
  if (!bodies.enabled[index]) return;  // it meets nothing
  // A sleeping pair has no contact to follow (the step drops pairs where nothing moves), so the
  // sleepers are found by their bounds: within the reach at which two resting bodies get a
  // contact (candidate_pairs.cpp), so whatever rests on the body or under it.
  const double reach = detail::kSpeculativeSlops * def.linear_slop;
  const AABB b = detail::BoundsOf(bodies, index);
  const AABB near{b.lower - Vec2{reach, reach}, b.upper + Vec2{reach, reach}};
  const detail::SleepState view = sleep.View();
  for (BodyIndex i = 0; i < bodies.states.size(); ++i) {
    if (view.awake[i] || view.island[i] == kNoBody || HasInfiniteMass(bodies.infos[i])) continue;
    if (Overlaps(near, detail::BoundsOf(bodies, i))) {
      detail::WakeIsland(i, bodies.infos, view);
    }
  }
}

void World::Impl::Withdraw(BodyIndex index) {
  WakeTouching(index);
  narrow_phase.RemoveBody(index);
  contact_events.RemoveBody(index, bodies);
  sensors.RemoveBody(index, bodies);
  sleep.Place(index, detail::kResting, false);
}

void World::Impl::RebuildActingSprings() {
  springs.acting.clear();
  auto enabled = [&](BodyId id) { return bodies.enabled[id.index] != 0; };
  for (const SpringDef& s : springs.all) {
    if (s.stiffness == 0.0 && s.damping == 0.0) continue;
    if (!enabled(s.body_a) || (s.body_b && !enabled(*s.body_b))) continue;
    std::optional<BodyIndex> b;
    if (s.body_b) b = s.body_b->index;
    // The attachments are given in each body's frame; the step works from its centre of mass.
    const Vec2 local_b = s.body_b ? bodies.FromCenter(*b, s.local_b) : s.local_b;
    springs.acting.push_back({s.body_a.index, bodies.FromCenter(s.body_a.index, s.local_a), b, local_b,
                              s.rest_length, s.stiffness, s.damping});
  }
}

BodyId World::CreateBody(const BodyDef& def) {
  RequireValid(def);
  detail::Bodies& bodies = impl_->bodies;
  std::shared_ptr<const detail::BodyGeometry> geometry;
  if (!def.parts.empty()) {
    geometry = detail::MakeBodyGeometry(def);
    Require(def.is_static || def.is_kinematic || IsPositiveFinite(geometry->mass),
            "BodyDef mass (or the parts' density) must be positive and finite");
  }
  const BodyIndex index = bodies.Allocate();
  bodies.geometries[index] = geometry;
  BodyInfo& info = bodies.infos[index] = detail::MakeBodyInfo(def, geometry.get(), impl_->def.rotation);
  BodyState& state = bodies.states[index] = {};
  state.position = def.position;
  state.angle = def.angle;
  if (geometry) bodies.PlaceOrigin(index, def.position, def.angle);
  if (!def.is_static) {
    state.velocity = def.velocity;
    state.angular_velocity = def.angular_velocity;
  }
  bodies.enabled[index] = def.enabled ? 1 : 0;
  bodies.filters[index] = def.filter;
  bodies.user_data[index] = def.user_data;
  bodies.Count(index, +1);
  impl_->sleep.Place(index, detail::WakefulnessOf(info, state), def.enabled);
  impl_->candidates.Place(index, detail::QuotaShape(bodies, index), def.is_static);
  return bodies.IdOf(index);
}

void World::DestroyBody(BodyId id) {
  Impl& w = *impl_;
  const BodyIndex index = w.Slot(id, "DestroyBody");
  const bool had_springs = std::erase_if(w.springs.all, [&](const SpringDef& s) {
                             return s.body_a == id || (s.body_b && *s.body_b == id);
                           }) > 0;
  w.DestroyJointsOf(index);
  w.particles.DetachFrom(index);  // soft bodies fastened to it come free
  w.effects.BodyGone(index);      // emitters riding on it stop
  if (w.bodies.enabled[index]) w.Withdraw(index);
  w.bodies.Count(index, -1);
  w.bodies.Free(index);
  if (had_springs) w.RebuildActingSprings();
}

bool World::IsValid(BodyId id) const { return impl_->bodies.IsLive(id); }

void World::SetEnabled(BodyId id, bool enabled) {
  Impl& w = *impl_;
  const BodyIndex index = w.Slot(id, "SetEnabled");
  if ((w.bodies.enabled[index] != 0) == enabled) return;
  w.bodies.Count(index, -1);
  if (!enabled) w.Withdraw(index);
  w.bodies.enabled[index] = enabled ? 1 : 0;
  w.bodies.Count(index, +1);
  if (enabled) {
    w.sleep.Place(index, detail::WakefulnessOf(w.bodies.infos[index], w.bodies.states[index]), true);
    w.WakeTouching(index);  // sleepers where it reappears: nothing else would push them
  }
  w.RebuildActingSprings();
  if (!w.joints.joints.empty()) w.RebuildJoints();
}

bool World::IsEnabled(BodyId id) const { return impl_->bodies.enabled[impl_->Slot(id, "IsEnabled")] != 0; }

void World::SetFilter(BodyId id, const Filter& filter) {
  detail::Bodies& bodies = impl_->bodies;
  const BodyIndex index = impl_->Slot(id, "SetFilter");
  bodies.Count(index, -1);
  bodies.filters[index] = filter;
  bodies.Count(index, +1);
  impl_->WakeTouching(index);  // what it rested on, or what rested on it, may now fall through
}

const Filter& World::GetFilter(BodyId id) const { return impl_->bodies.filters[impl_->Slot(id, "GetFilter")]; }

void World::SetUserData(BodyId id, std::uint64_t user_data) {
  impl_->bodies.user_data[impl_->Slot(id, "SetUserData")] = user_data;
}

std::uint64_t World::UserData(BodyId id) const { return impl_->bodies.user_data[impl_->Slot(id, "UserData")]; }

void World::SetPosition(BodyId id, Vec2 position) {
  const BodyIndex index = impl_->Slot(id, "SetPosition");
  Require(IsFinite(position), "SetPosition: position must be finite");
  impl_->WakeTouching(index);  // what rested on it, or under it, where it was
  detail::Bodies& bodies = impl_->bodies;
  if (bodies.geometries[index]) {
    bodies.PlaceOrigin(index, position, bodies.states[index].angle);
  } else {
    bodies.states[index].position = position;
  }
  impl_->WakeTouching(index);  // what it lands on or in
}

void World::SetAngle(BodyId id, double angle) {
  const BodyIndex index = impl_->Slot(id, "SetAngle");
  Require(std::isfinite(angle), "SetAngle: angle must be finite");
  impl_->WakeTouching(index);
  // A body made of parts turns about its frame's origin, which stays where it is.
  detail::Bodies& bodies = impl_->bodies;
  if (bodies.geometries[index]) {
    bodies.PlaceOrigin(index, bodies.Origin(index), angle);
  } else {
    bodies.states[index].angle = angle;
  }
  impl_->WakeTouching(index);
}

void World::Impl::UpdateKinematicMotion(BodyIndex index) {
  if (!bodies.enabled[index]) return;
  sleep.awake[index] = detail::WakefulnessOf(bodies.infos[index], bodies.states[index]);
  WakeAround(index);
}

void World::SetLinearVelocity(BodyId id, Vec2 velocity) {
  const BodyIndex index = impl_->Slot(id, "SetLinearVelocity");
  Require(IsFinite(velocity), "SetLinearVelocity: velocity must be finite");
  const BodyInfo& info = impl_->bodies.infos[index];
  if (info.is_static) return;
  impl_->bodies.states[index].velocity = velocity;
  if (info.is_kinematic) return impl_->UpdateKinematicMotion(index);
  impl_->WakeAround(index);
}

void World::SetAngularVelocity(BodyId id, double angular_velocity) {
  const BodyIndex index = impl_->Slot(id, "SetAngularVelocity");
  Require(std::isfinite(angular_velocity), "SetAngularVelocity: angular velocity must be finite");
  const BodyInfo& info = impl_->bodies.infos[index];
  if (info.is_static || (!info.is_kinematic && info.inv_inertia == 0.0)) return;  // cannot turn
  impl_->bodies.states[index].angular_velocity = angular_velocity;
  if (info.is_kinematic) return impl_->UpdateKinematicMotion(index);
  impl_->WakeAround(index);
}

void World::ApplyForce(BodyId id, Vec2 force, Vec2 point) {
  const BodyIndex index = impl_->Slot(id, "ApplyForce");
  Require(IsFinite(force) && IsFinite(point), "ApplyForce: force and point must be finite");
  detail::Bodies& bodies = impl_->bodies;
  if (HasInfiniteMass(bodies.infos[index])) return;
  bodies.applied_forces[index] += force;
  bodies.applied_torques[index] += Cross(point - bodies.states[index].position, force);
  bodies.forces_applied = true;
  impl_->WakeAround(index);
}

void World::ApplyForceToCenter(BodyId id, Vec2 force) {
  const BodyIndex index = impl_->Slot(id, "ApplyForceToCenter");
  ApplyForce(id, force, impl_->bodies.states[index].position);
}

void World::ApplyTorque(BodyId id, double torque) {
  const BodyIndex index = impl_->Slot(id, "ApplyTorque");
  Require(std::isfinite(torque), "ApplyTorque: torque must be finite");
  detail::Bodies& bodies = impl_->bodies;
  if (HasInfiniteMass(bodies.infos[index])) return;
  bodies.applied_torques[index] += torque;
  bodies.forces_applied = true;
  impl_->WakeAround(index);
}

void World::ApplyLinearImpulse(BodyId id, Vec2 impulse, Vec2 point) {
  const BodyIndex index = impl_->Slot(id, "ApplyLinearImpulse");
  Require(IsFinite(impulse) && IsFinite(point), "ApplyLinearImpulse: impulse and point must be finite");
  const BodyInfo& info = impl_->bodies.infos[index];
  if (HasInfiniteMass(info) || !impl_->bodies.enabled[index]) return;
  impl_->WakeAround(index);
  BodyState& state = impl_->bodies.states[index];
  state.velocity += impulse / info.mass;
  state.angular_velocity += info.inv_inertia * Cross(point - state.position, impulse);
}

void World::ApplyLinearImpulseToCenter(BodyId id, Vec2 impulse) {
  const BodyIndex index = impl_->Slot(id, "ApplyLinearImpulseToCenter");
  Require(IsFinite(impulse), "ApplyLinearImpulseToCenter: impulse must be finite");
  const BodyInfo& info = impl_->bodies.infos[index];
  if (HasInfiniteMass(info) || !impl_->bodies.enabled[index]) return;
  impl_->WakeAround(index);
  impl_->bodies.states[index].velocity += impulse / info.mass;
}

void World::ApplyAngularImpulse(BodyId id, double impulse) {
  const BodyIndex index = impl_->Slot(id, "ApplyAngularImpulse");
  Require(std::isfinite(impulse), "ApplyAngularImpulse: impulse must be finite");
  const BodyInfo& info = impl_->bodies.infos[index];
  if (HasInfiniteMass(info) || !impl_->bodies.enabled[index]) return;
  impl_->WakeAround(index);
  impl_->bodies.states[index].angular_velocity += info.inv_inertia * impulse;
}

void World::AddSpring(const SpringDef& def) {
  impl_->Slot(def.body_a, "AddSpring");
  if (def.body_b) impl_->Slot(*def.body_b, "AddSpring");
  Require(IsFinite(def.local_a) && IsFinite(def.local_b), "AddSpring: attachment points must be finite");
  Require(IsNonNegativeFinite(def.rest_length) && IsNonNegativeFinite(def.stiffness) &&
              IsNonNegativeFinite(def.damping),
          "AddSpring: rest length, stiffness and damping must be finite and >= 0");
  impl_->springs.all.push_back(def);
  impl_->RebuildActingSprings();
}

}  // namespace engine
