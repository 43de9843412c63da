// World::Draw: the world described through the debug-draw interface, and the interface's empty
// defaults (an embedder overrides only what it draws).
#include "engine/debug_draw.h"

#include "candidate_pairs.h"
#include "world_impl.h"

namespace engine {

void DebugDraw::DrawCircle(BodyId, Vec2, double, double, BodyKind) {}
void DebugDraw::DrawBox(BodyId, Vec2, Vec2, double, BodyKind) {}
void DebugDraw::DrawPolygon(BodyId, std::span<const Vec2>, double, BodyKind) {}
void DebugDraw::DrawCapsule(BodyId, Vec2, Vec2, double, BodyKind) {}
void DebugDraw::DrawSegment(BodyId, Vec2, Vec2, BodyKind) {}
void DebugDraw::DrawSpring(Vec2, Vec2) {}
void DebugDraw::DrawJoint(JointType, Vec2, Vec2, Vec2, Vec2) {}
void DebugDraw::DrawBounds(BodyId, const AABB&, BodyKind) {}
void DebugDraw::DrawContact(Vec2, Vec2, double, double) {}

namespace {

// The first kind that applies to the live body in `slot`.
BodyKind KindOf(const detail::Bodies& bodies, std::span<const std::uint8_t> awake, BodyIndex slot) {
  const BodyInfo& info = bodies.infos[slot];
  if (!bodies.enabled[slot]) return BodyKind::kDisabled;
  if (info.is_sensor) return BodyKind::kSensor;
  if (info.is_static) return BodyKind::kStatic;
  if (info.is_kinematic) return BodyKind::kKinematic;
  return awake[slot] ? BodyKind::kAwake : BodyKind::kAsleep;
}

// A point fixed on a body, in world coordinates.
Vec2 Anchor(const BodyState& state, Vec2 local) { return state.position + Rotate(MakeRot(state.angle), local); }

// A body's pieces in the world: each drawn by the call for its kind.
void DrawPieces(BodyId id, const detail::BodyGeometry& geometry, const BodyState& state, BodyKind kind,
                DebugDraw& draw) {
  const Vec2 origin = detail::OriginOf(geometry, state);
  const Rot rotation = MakeRot(state.angle);
  auto world = [&](Vec2 local) { return origin + Rotate(rotation, local); };
  for (const ConvexPiece& piece : geometry.public_pieces) {
    std::vector<Vec2> points;
    for (const Vec2 v : piece.vertices) points.push_back(world(v));
    switch (piece.type) {
      case ShapeType::kCircle: draw.DrawCircle(id, points[0], piece.radius, state.angle, kind); break;
      case ShapeType::kCapsule: draw.DrawCapsule(id, points[0], points[1], piece.radius, kind); break;
      case ShapeType::kSegments: draw.DrawSegment(id, points[0], points[1], kind); break;
      default: draw.DrawPolygon(id, points, piece.radius, kind);
    }
  }
}

void DrawShapes(const detail::Bodies& bodies, std::span<const std::uint8_t> awake, DebugDraw& draw) {
  for (BodyIndex slot = 0; slot < bodies.states.size(); ++slot) {
    if (!bodies.alive[slot]) continue;
    const Shape& shape = bodies.infos[slot].shape;
    const BodyState& state = bodies.states[slot];
    const BodyKind kind = KindOf(bodies, awake, slot);
    if (const detail::BodyGeometry* geometry = bodies.geometries[slot].get()) {
      DrawPieces(bodies.IdOf(slot), *geometry, state, kind, draw);
    } else if (shape.type == ShapeType::kCircle) {
      draw.DrawCircle(bodies.IdOf(slot), state.position, shape.radius, state.angle, kind);
    } else {
      draw.DrawBox(bodies.IdOf(slot), state.position, shape.half_extents, state.angle, kind);
    }
  }
}

void DrawSprings(const detail::Bodies& bodies, std::span<const SpringDef> springs, DebugDraw& draw) {
  for (const SpringDef& spring : springs) {
    const Vec2 a = Anchor(bodies.states[spring.body_a.index], bodies.FromCenter(spring.body_a.index, spring.local_a));
    const Vec2 b = spring.body_b ? Anchor(bodies.states[spring.body_b->index],
                                          bodies.FromCenter(spring.body_b->index, spring.local_b))
                                 : spring.local_b;
    draw.DrawSpring(a, b);
  }
}

void DrawJoints(const World& world, const detail::Bodies& bodies, const detail::JointTable& joints,
                DebugDraw& draw) {
  for (const JointId id : joints.live_ids) {
    const detail::Joint& j = joints.joints[id.index];
    const JointFrame frame = world.Joint(id);
    const Vec2 center_a = j.a == kNoBody ? frame.anchor_a : bodies.states[j.a].position;
    draw.DrawJoint(j.def.type, center_a, frame.anchor_a, frame.anchor_b, bodies.states[j.b].position);
  }
}

void DrawBounds(const detail::Bodies& bodies, std::span<const std::uint8_t> awake, DebugDraw& draw) {
  for (BodyIndex slot = 0; slot < bodies.states.size(); ++slot) {
    if (!bodies.alive[slot]) continue;
    const AABB bounds = detail::BoundsOf(bodies, slot);
    draw.DrawBounds(bodies.IdOf(slot), bounds, KindOf(bodies, awake, slot));
  }
}

void DrawContacts(std::span<const Contact> contacts, DebugDraw& draw) {
  for (const Contact& contact : contacts) {
    const Manifold& m = contact.manifold;
    for (int i = 0; i < m.point_count; ++i) {
      draw.DrawContact(m.points[i].point, m.normal, m.points[i].depth, contact.normal_impulse[i]);
    }
  }
}

}  // namespace

void World::Draw(DebugDraw& draw, const DrawOptions& options) const {
  const detail::Bodies& bodies = impl_->bodies;
  // Shapes first and contacts last, so that what is drawn later lies on top.
  if (options.shapes) DrawShapes(bodies, impl_->sleep.awake, draw);
  if (options.springs) DrawSprings(bodies, impl_->springs.all, draw);
  if (options.joints) DrawJoints(*this, bodies, impl_->joints, draw);
  if (options.bounds) DrawBounds(bodies, impl_->sleep.awake, draw);
  if (options.contacts) DrawContacts(impl_->narrow_phase.Contacts(), draw);
}

}  // namespace engine
