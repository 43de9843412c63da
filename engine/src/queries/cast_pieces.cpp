// A ray, circle or box cast against a body's pieces.
#include "queries/cast_pieces.h"

#include "geometry/gjk.h"
#include "geometry/ray_cast.h"
#include "geometry/time_of_impact.h"
#include "queries/query.h"
#include "queries/sweep.h"

namespace engine::detail {

namespace {

using geometry::Transform;

// The mover as a proxy in its own frame (centred at the origin).
geometry::ShapeProxy MoverProxy(const Shape& shape) {
  if (shape.type == ShapeType::kCircle) {
    const Vec2 center[1] = {{0.0, 0.0}};
    return geometry::MakeProxy(center, shape.radius);
  }
  return geometry::MakeProxy(geometry::MakeBox(shape.half_extents.x, shape.half_extents.y));
}

// A point moving p + t·d against the piece grown by `r`: the geometry layer's ray casts (not
// for circle pieces, which the caller crosses as circles).
geometry::CastOutput GrownRayCast(const BodyGeometry& g, const Piece& piece, const Transform& xf, Vec2 p, Vec2 d,
                                  double r) {
  const geometry::RayCastInput ray{p, d, 1.0};
  switch (piece.kind) {
    case Piece::Kind::kCircle:
      return {};  // cast as a circle crossing by the caller
    case Piece::Kind::kSegment: {
      const geometry::ChainSegment& s = g.segments[piece.index];
      if (r == 0.0) return geometry::RayCastSegment(s.point1, s.point2, xf, ray);
      return geometry::RayCastCapsule({s.point1, s.point2, r}, xf, ray);
    }
    default: {
      geometry::Polygon grown = g.polygons[piece.index];
      grown.radius += r;
      return geometry::RayCastPolygon(grown, xf, ray);
    }
  }
}

}  // namespace

std::optional<RayHit> CastAgainstPieces(const Cast& cast, const BodyGeometry& g, const BodyState& state) {
  const Transform xf = FrameOf(state);
  const Transform mover{cast.position, RotationOf(cast.angle)};
  // GJK's proxies serve shape casts only (the start's overlap, a box's advance); rays and
  // circles are crossed exactly without them.
  const bool gjk = cast.starts_inside_counts || cast.shape.type != ShapeType::kCircle;
  const geometry::ShapeProxy mover_proxy = gjk ? MoverProxy(cast.shape) : geometry::ShapeProxy{};
  const Vec2 p = cast.position, d = cast.translation;
  std::optional<RayHit> first;
  auto offer = [&](double fraction, Vec2 point, Vec2 normal) {
    if (!first || fraction < first->fraction) first = RayHit{{}, point, normal, fraction};
  };
  for (const Piece& piece : g.pieces) {
    const geometry::ShapeProxy proxy = gjk ? ProxyOf(g, piece) : geometry::ShapeProxy{};
    if (cast.starts_inside_counts) {
      // A shape cast meets a piece it starts overlapping at once.
      const geometry::DistanceOutput start = geometry::ShapeDistance(proxy, xf, mover_proxy, mover);
      if (start.separation < 0.0) {
        offer(0.0, cast.position, {});
        continue;
      }
    }
    if (cast.shape.type == ShapeType::kCircle) {
      const double r = cast.shape.radius;
      if (piece.kind == Piece::Kind::kCircle) {
        const Crossing crossing = CircleCrossing(p, d, geometry::TransformPoint(xf, piece.center), piece.radius + r);
        if (crossing.Meets() && !crossing.starts_inside && crossing.enter >= 0.0 && crossing.enter <= 1.0) {
          offer(crossing.enter, p + crossing.enter * d - r * crossing.normal, crossing.normal);
        }
        continue;
      }
      const geometry::CastOutput out = GrownRayCast(g, piece, xf, p, d, r);
      if (out.hit) offer(out.fraction, out.point - r * out.normal, out.normal);
      continue;
    }
    // A box: advance until it comes within the tolerance of the piece.
    const geometry::Sweep still{{}, state.position, state.position, xf.rotation, xf.rotation};
    const geometry::Sweep moving{{}, p, p + d, mover.rotation, mover.rotation};
    const geometry::ToiSettings settings{.target = kBoxCastTolerance, .tolerance = 0.5 * kBoxCastTolerance,
                                         .max_iterations = 100};
    const geometry::ToiOutput toi = geometry::TimeOfImpact(proxy, still, mover_proxy, moving, settings);
    if (toi.state != geometry::ToiState::kHit) continue;
    const Transform at{p + toi.fraction * d, mover.rotation};
    const geometry::DistanceOutput touch = geometry::ShapeDistance(proxy, xf, mover_proxy, at);
    // The touch point on the piece's surface; the normal from the body towards the box.
    const Vec2 point = touch.point_a + proxy.radius * touch.normal;
    offer(toi.fraction, point, touch.normal);
  }
  return first;
}

}  // namespace engine::detail
