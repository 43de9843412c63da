// Bodies: what a body is made from (BodyDef), what every step writes (BodyState) and what it only
// reads (BodyInfo).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/filter.h"
#include "engine/math.h"
#include "engine/shape.h"

namespace engine {

struct BodyDef {
  Shape shape;                    ///< a circle or a box, when `parts` is empty
  /// The body's parts, when it is made of them (then `shape` is not read): polygons, capsules,
  /// segment polylines, circles and boxes, each placed in the body's frame. Mass, centre of mass
  /// and inertia add up over them.
  std::vector<ShapePart> parts;
  /// m: a circle's or box's centre; for a body made of parts, the origin of the body's frame
  /// (the centre of mass follows from the parts, World::LocalCenter).
  Vec2 position;
  Vec2 velocity;                  ///< m/s
  double angle = 0.0;             ///< rad (kept, not integrated, while rotation is off)
  double angular_velocity = 0.0;  ///< rad/s
  double mass = 0.0;              ///< kg; 0 means density × area
  double density = 1.0;           ///< kg/m², used when mass is 0
  bool is_static = false;         ///< infinite mass: never moves
  /// Infinite mass, but moves at its own velocity (set here or with the World setters): it
  /// pushes dynamic bodies and is never pushed, feels no force. Not static at the same time.
  bool is_kinematic = false;
  /// Reports overlaps (World::Events().sensor_begin/end) and collides with nothing.
  bool is_sensor = false;
  bool enabled = true;            ///< a disabled body stays where it is and meets nothing
  Filter filter;                  ///< which bodies it collides with
  std::uint64_t user_data = 0;    ///< the embedder's own, never read by the engine
  double restitution = 0.2;
  double friction = 0.3;
  bool fixed_rotation = false;
  bool bullet = false;
  double linear_damping = 0.0;    ///< 1/s: a force −c·m·v
  double angular_damping = 0.0;   ///< 1/s: a torque −c·I·ω
  /// Quadratic drag coefficient C_d in a fluid; negative means the shape's usual value
  /// (0.47 for a circle or capsule, 1.05 for a box or anything else).
  double drag_coefficient = -1.0;
};

/// What every step writes.
struct BodyState {
  Vec2 position;  ///< of the centre of mass (World::Origin gives the body frame's origin)
  Vec2 velocity;
  double angle = 0.0;
  double angular_velocity = 0.0;
};

/// What a step only reads.
struct BodyInfo {
  Shape shape;
  double mass = 0.0;      ///< kg; 0 for static and kinematic bodies
  double inv_mass = 0.0;  ///< 1/kg; 0 for static and kinematic bodies, so impulses never move them
  double inertia = 0.0;      ///< kg·m² about the centre; 0 for static and kinematic bodies
  double inv_inertia = 0.0;  ///< 0 for static and kinematic bodies, fixed rotation, or no rotation
  double linear_damping = 0.0;
  double angular_damping = 0.0;
  double drag_coefficient = 0.0;
  double restitution = 0.0;
  double friction = 0.0;
  bool is_static = false;
  bool is_kinematic = false;
  bool is_sensor = false;
  bool fixed_rotation = false;
  bool bullet = false;
};

/// Static and kinematic bodies: no impulse or force moves them.
constexpr bool HasInfiniteMass(const BodyInfo& info) { return info.is_static || info.is_kinematic; }

}  // namespace engine
