// The contact planes between a particle and a rigid body, from the narrow phase's colliders.
#include "particles/body_contact.h"

#include "geometry/manifold.h"
#include "narrow_phase/collide.h"

namespace engine::detail {

namespace {

// A manifold with the body as A (its normal from the body to the particle) as a plane: the
// body's surface lies half the depth beyond the manifold's midway point.
BodyPlane PlaneOf(const Manifold& m, Vec2 normal, double friction) {
  const ContactPoint& p = m.points[0];
  return {normal, p.point + (0.5 * p.depth) * normal, friction};
}

}  // namespace

int AppendBodyPlanes(const Bodies& bodies, BodyIndex body, Vec2 center, double radius, double margin,
                     std::vector<BodyPlane>* out) {
  const BodyInfo& info = bodies.infos[body];
  const BodyState& state = bodies.states[body];
  Manifold m;
  if (!bodies.geometries[body]) {
    if (info.shape.type == ShapeType::kCircle) {
      if (!CollideCircles(state.position, info.shape.radius, center, radius, &m, margin)) return 0;
      out->push_back(PlaneOf(m, m.normal, info.friction));
      return 1;
    }
    const OrientedBox box{state.position, info.shape.half_extents, MakeRot(state.angle)};
    if (!CollideCircleOrientedBox(center, radius, box, &m, margin)) return 0;
    out->push_back(PlaneOf(m, -m.normal, info.friction));  // the collider's normal points into the box
    return 1;
  }
  const BodyGeometry& g = *bodies.geometries[body];
  const geometry::Transform frame = FrameOf(state);
  int count = 0;
  for (const Piece& piece : g.pieces) {
    const Vec2 piece_center = geometry::TransformPoint(frame, piece.center);
    const double reach = piece.reach + radius + margin;
    if (LengthSquared(center - piece_center) > reach * reach) continue;
    bool hit = false;
    Vec2 normal;
    switch (piece.kind) {
      case Piece::Kind::kCircle:
        hit = CollideCircles(piece_center, piece.radius, center, radius, &m, margin);
        normal = m.normal;
        break;
      case Piece::Kind::kPolygon:
      case Piece::Kind::kCapsule:
        hit = geometry::CollideCirclePolygon(center, radius, g.polygons[piece.index], frame, &m, margin);
        normal = -m.normal;
        break;
      case Piece::Kind::kSegment:
        hit = geometry::CollideChainCircle(g.segments[piece.index], frame, center, radius, &m, margin);
        normal = m.normal;
        break;
    }
    if (!hit) continue;
    out->push_back(PlaneOf(m, normal, piece.friction));
    ++count;
  }
  return count;
}

}  // namespace engine::detail
