// The drag rule (docs/play.md, "Dragging"): the right button grabs the topmost dynamic body under
// the cursor with a target joint (Box2D's mouse joint) that pulls the grabbed point towards the
// cursor; moving the cursor moves the target, letting go destroys the joint.
#pragma once

#include <optional>

#include "engine/math.h"
#include "engine/world.h"

namespace game {

/// The pull's spring and strength: 5 Hz with damping ratio 0.7, capped at 1000 times the body's
/// weight (under at least Earth's gravity, so a body can be dragged in a weightless scene too).
inline constexpr double kGrabHertz = 5.0;
inline constexpr double kGrabDampingRatio = 0.7;
inline constexpr double kGrabForcePerWeight = 1000.0;
inline constexpr double kGrabLeastGravity = 9.8;  ///< m/s²

/// The dynamic body whose shape holds p (touching counts): the last in slot order when several
/// do, the one drawn on top. Static, kinematic and disabled bodies are never grabbed.
std::optional<engine::BodyId> GrabbableAt(const engine::World& world, engine::Vec2 p);

/// The target joint that grabs `body` at world point p and pulls that point towards p.
engine::JointDef GrabJoint(const engine::World& world, engine::BodyId body, engine::Vec2 p);

/// The world's grab: its target joint, if one is live. Only the drag rule makes target joints
/// (a scene's joints are of the other types), so a restored snapshot brings its grab back too.
std::optional<engine::JointId> CurrentGrab(const engine::World& world);

/// `grab`: lets go of any grab, then grabs the body under p. Returns the body, or nothing when
/// p is on no dynamic body (then nothing is held).
std::optional<engine::BodyId> Grab(engine::World& world, engine::Vec2 p);
/// `drag`: moves the grab's target to p. Returns whether a body was held.
bool Drag(engine::World& world, engine::Vec2 p);
/// `release`: destroys the grab. Returns whether a body was held.
bool Release(engine::World& world);

}  // namespace game
