// A body's read-only data from its definition.
#include "bodies.h"

namespace engine::detail {

namespace {

// Drag coefficients of a long cylinder and a square bar across a flow (textbook values).
constexpr double kCircleDrag = 0.47;
constexpr double kBoxDrag = 1.05;

}  // namespace

double BodyMass(const BodyDef& def) {
  return def.mass > 0.0 ? def.mass : def.density * ShapeArea(def.shape);
}

BodyInfo MakeBodyInfo(const BodyDef& def, bool rotation) {
  BodyInfo info;
  info.shape = def.shape;
  info.restitution = def.restitution;
  info.friction = def.friction;
  info.is_static = def.is_static;
  info.fixed_rotation = def.fixed_rotation;
  info.bullet = def.bullet;
  info.linear_damping = def.linear_damping;
  info.angular_damping = def.angular_damping;
  info.drag_coefficient = def.drag_coefficient >= 0.0                  ? def.drag_coefficient
                          : def.shape.type == ShapeType::kCircle ? kCircleDrag
                                                                 : kBoxDrag;
  if (def.is_static) return info;  // infinite mass and inertia: every inverse 0
  info.mass = BodyMass(def);
  info.inv_mass = 1.0 / info.mass;
  info.inertia = ShapeInertia(def.shape, info.mass);
  // Without rotation (world or body) nothing can turn the body: infinite inertia.
  info.inv_inertia = rotation && !def.fixed_rotation ? 1.0 / info.inertia : 0.0;
  return info;
}

}  // namespace engine::detail
