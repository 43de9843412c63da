// A body's read-only data from its definition.
#include "bodies.h"

#include <algorithm>

namespace engine::detail {

namespace {

// Drag coefficients of a long cylinder and a square bar across a flow (textbook values).
constexpr double kCircleDrag = 0.47;
constexpr double kBoxDrag = 1.05;

}  // namespace

double BodyMass(const BodyDef& def) {
  return def.mass > 0.0 ? def.mass : def.density * ShapeArea(def.shape);
}

BodyInfo MakeBodyInfo(const BodyDef& def, const BodyGeometry* geometry, bool rotation) {
  BodyInfo info;
  info.shape = def.shape;
  if (geometry) {
    info.shape = Shape{};
    info.shape.type = geometry->parts.size() == 1 ? geometry->parts[0].type : ShapeType::kCompound;
  }
  info.restitution = def.restitution;
  info.friction = def.friction;
  info.is_static = def.is_static;
  info.is_kinematic = def.is_kinematic;
  info.is_sensor = def.is_sensor;
  info.fixed_rotation = def.fixed_rotation;
  info.bullet = def.bullet;
  info.linear_damping = def.linear_damping;
  info.angular_damping = def.angular_damping;
  info.drag_coefficient = def.drag_coefficient >= 0.0                  ? def.drag_coefficient
                          : info.shape.type == ShapeType::kCircle || info.shape.type == ShapeType::kCapsule
                              ? kCircleDrag
                              : kBoxDrag;
  if (def.is_static || def.is_kinematic) return info;  // infinite mass and inertia: every inverse 0
  info.mass = geometry ? geometry->mass : BodyMass(def);
  info.inv_mass = 1.0 / info.mass;
  info.inertia = geometry ? geometry->inertia : ShapeInertia(def.shape, info.mass);
  // Without rotation (world or body) nothing can turn the body: infinite inertia.
  info.inv_inertia = rotation && !def.fixed_rotation ? 1.0 / info.inertia : 0.0;
  return info;
}

}  // namespace engine::detail

namespace engine::detail {

BodyIndex Bodies::Allocate() {
  if (!free_slots.empty()) {
    const BodyIndex index = free_slots.back();
    free_slots.pop_back();
    alive[index] = 1;
    --inactive;  // counted again by Count if the new body is disabled
    const auto at = std::lower_bound(live_ids.begin(), live_ids.end(), index,
                                     [](BodyId id, BodyIndex i) { return id.index < i; });
    live_ids.insert(at, IdOf(index));
    return index;
  }
  return AppendSlot();
}

BodyIndex Bodies::AppendSlot() {
  const auto index = static_cast<BodyIndex>(states.size());
  states.emplace_back();
  infos.emplace_back();
  geometries.emplace_back();
  generations.push_back(0);
  alive.push_back(1);
  enabled.push_back(1);
  filters.emplace_back();
  user_data.push_back(0);
  applied_forces.emplace_back();
  applied_torques.push_back(0.0);
  live_ids.push_back(IdOf(index));
  return index;
}

void Bodies::Free(BodyIndex index) {
  alive[index] = 0;
  enabled[index] = 0;
  ++generations[index];
  ++inactive;
  // A free slot holds nothing that acts: no mass to attract with, nothing to step (and the same
  // in a world restored from a snapshot, which stores no more of the slot than its generation).
  states[index] = BodyState{};
  infos[index] = BodyInfo{};
  infos[index].is_static = true;
  geometries[index].reset();
  applied_forces[index] = {};
  applied_torques[index] = 0.0;
  free_slots.push_back(index);
  std::erase_if(live_ids, [&](BodyId id) { return id.index == index; });
}

void Bodies::Count(BodyIndex index, int sign) {
  const BodyInfo& info = infos[index];
  auto add = [&](std::size_t& count, bool counts) {
    if (counts) count += static_cast<std::size_t>(static_cast<std::ptrdiff_t>(sign));
  };
  add(damped, info.linear_damping != 0.0 || info.angular_damping != 0.0);
  add(turnable, info.inv_inertia != 0.0);
  add(inactive, !enabled[index]);
  add(filtered, !(filters[index] == Filter{}));
  add(sensors, info.is_sensor);
  add(kinematic, info.is_kinematic);
  add(with_parts, geometries[index] != nullptr);
}

void Bodies::ClearAppliedForces() {
  if (!forces_applied) return;
  std::fill(applied_forces.begin(), applied_forces.end(), Vec2{});
  std::fill(applied_torques.begin(), applied_torques.end(), 0.0);
  forces_applied = false;
}

}  // namespace engine::detail
