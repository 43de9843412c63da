// The debug-draw interface: World::Draw describes its bodies, bounds, springs and contacts
// through it, so an embedder can draw them with any graphics library.
#pragma once

#include <cstdint>
#include <span>

#include "engine/ids.h"
#include "engine/joint.h"
#include "engine/math.h"

namespace engine {

/// What a body is, for choosing its colour: the first of these that applies.
enum class BodyKind : std::uint8_t {
  kDisabled,   ///< World::SetEnabled(id, false): kept, not simulated
  kSensor,
  kStatic,
  kKinematic,
  kAwake,      ///< dynamic and awake
  kAsleep,     ///< dynamic and asleep
};

/// What World::Draw describes, in this order: shapes, springs, joints, bounds, contacts.
struct DrawOptions {
  bool shapes = true;
  bool springs = true;
  bool joints = true;
  bool bounds = false;    ///< each body's bounding box (World::BodyBounds)
  bool contacts = false;  ///< the contact points of the last step (World::Contacts)
};

/// Override the calls you draw; the others do nothing. A class with virtual functions rather
/// than a struct of callbacks (Box2D v3's b2DebugDraw holds function pointers and a context
/// pointer because its API is C): the object that overrides them holds its own canvas, an
/// embedder leaves out what it does not draw, and a test records the calls in a subclass.
/// Positions are world metres, angles radians.
class DebugDraw {
 public:
  virtual ~DebugDraw() = default;
  /// `angle` lets a line from the centre show the circle turning.
  virtual void DrawCircle(BodyId body, Vec2 center, double radius, double angle, BodyKind kind);
  virtual void DrawBox(BodyId body, Vec2 center, Vec2 half_extents, double angle, BodyKind kind);
  // The pieces of a body made of parts (World::Pieces), in the world: a circle piece comes
  // through DrawCircle, the others through these.
  /// A convex polygon, counter-clockwise, every corner rounded by `radius` (0: sharp).
  virtual void DrawPolygon(BodyId body, std::span<const Vec2> vertices, double radius, BodyKind kind);
  virtual void DrawCapsule(BodyId body, Vec2 center1, Vec2 center2, double radius, BodyKind kind);
  /// One segment of a polyline.
  virtual void DrawSegment(BodyId body, Vec2 a, Vec2 b, BodyKind kind);
  /// A spring from anchor `a` on its first body to `b`, on its second body or fixed in the world.
  virtual void DrawSpring(Vec2 a, Vec2 b);
  /// A joint: its bodies' centres of mass and its points on them (World::Joint). A target
  /// joint has no body A: `center_a` and `anchor_a` are then its target.
  virtual void DrawJoint(JointType type, Vec2 center_a, Vec2 anchor_a, Vec2 anchor_b, Vec2 center_b);
  virtual void DrawBounds(BodyId body, const AABB& bounds, BodyKind kind);
  /// A contact point of World::Contacts: `normal` points from the lower slot's body to the
  /// other, `depth` is the overlap (m; negative: a speculative contact, still that far apart),
  /// `normal_impulse` the one the solver left on the point (Contact::normal_impulse, N·s).
  virtual void DrawContact(Vec2 point, Vec2 normal, double depth, double normal_impulse);
};

}  // namespace engine
