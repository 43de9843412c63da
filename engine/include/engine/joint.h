// Joints: constraints between two bodies (either may be static), solved with the contacts in
// the same substeps, so a joint is as stiff as a contact (docs/joints.md).
#pragma once

#include <cstdint>
#include <optional>

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

enum class JointType : std::uint8_t {
  /// The bodies share a point and turn freely about it (a hinge, a pendulum's pivot); optional
  /// angle limits and a motor.
  kRevolute,
  /// B slides along an axis fixed in A and does not turn relative to A; optional translation
  /// limits and a motor.
  kPrismatic,
  /// A point on each body kept at a length, within a range [min, max] (a rope: max alone), or
  /// pulled to the length by a spring.
  kDistance,
  /// The bodies held together as one, rigidly or through a spring.
  kWeld,
  /// A point of body B pulled towards a target point by a spring with a force cap: dragging a
  /// body with the mouse (Box2D's mouse joint). Body A is not read.
  kTarget,
};

/// A spring that makes a joint soft: `hertz` > 0 is its natural frequency (for the effective mass
/// the joint sees), `damping_ratio` ≥ 0 (1: critical). Its stiffness does not depend on the step.
struct JointSpring {
  double hertz = 0.0;
  double damping_ratio = 0.0;
};

/// Drives a revolute joint's relative angular speed (rad/s, torque cap N·m) or a prismatic
/// joint's relative speed along its axis (m/s, force cap N).
struct JointMotor {
  double speed = 0.0;
  double max_force = 0.0;  ///< ≥ 0: the most torque (revolute) or force (prismatic) it applies
};

/// Lower ≤ upper: a revolute joint's relative angle (rad, from the start), a prismatic joint's
/// translation along its axis (m, from the start).
struct JointLimits {
  double lower = 0.0;
  double upper = 0.0;
};

/// Everything a joint is made from. Points and directions are world ones, at the moment the
/// joint is made; the joint keeps them in its bodies' frames from then on.
struct JointDef {
  JointType type = JointType::kRevolute;
  BodyId body_a;                      ///< unused by kTarget
  BodyId body_b;
  /// The shared point (revolute, weld), the slider's point (prismatic), the anchor on A
  /// (distance), or the point of B that is grabbed (target).
  Vec2 anchor;
  Vec2 anchor_b;                      ///< distance: the anchor on B
  Vec2 axis{1.0, 0.0};                ///< prismatic: the direction B slides along (any length > 0)
  std::optional<JointLimits> limits;  ///< revolute, prismatic
  std::optional<JointMotor> motor;    ///< revolute, prismatic
  /// distance: the length becomes soft; weld: the weld becomes soft; target: required.
  std::optional<JointSpring> spring;
  /// distance: the length the joint holds (or its spring pulls to); none: the anchors' distance.
  std::optional<double> length;
  /// distance: with either one the joint is a range instead of a fixed length (the other then
  /// defaults to 0 or unbounded); with a spring, the spring acts inside the range.
  std::optional<double> min_length;
  std::optional<double> max_length;
  Vec2 target;                        ///< target: where the grabbed point is pulled to
  double max_force = 0.0;             ///< target: the most force the pull applies, N (> 0)
  bool collide = false;               ///< whether the two bodies still collide with each other
};

/// A joint as it stands now, in the world (World::Joint).
struct JointFrame {
  Vec2 anchor_a;        ///< the joint's point on A, where A is now (the target point for kTarget)
  Vec2 anchor_b;        ///< its point on B
  double angle = 0.0;   ///< B's angle relative to A, less the relative angle at the start
  /// prismatic: B's offset along the axis from the start (m); distance: the anchors' distance
  double translation = 0.0;
};

}  // namespace engine
