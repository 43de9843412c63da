// A ray, circle or box cast against bodies. A circle against a body is a point against the body
// grown by the radius (their Minkowski sum: a bigger circle, or a rounded box); a box against a
// circle is the circle cast the other way; a box against a box is swept by separating axes
// (queries/sweep.cpp). Each is exact up to rounding: no iteration, no tolerance.
#include "queries/cast.h"

#include <algorithm>

#include "queries/cast_pieces.h"
#include "queries/query.h"
#include "queries/sweep.h"

namespace engine::detail {

namespace {

// Box against box, at the touch the sweep found: the manifold is looked for this far apart, m
// (anything above rounding will do, as only the deepest points are kept), and points within
// kSameDepth of the deepest touch together (two faces lying flat on each other).
constexpr double kTouchMargin = 1e-6;
constexpr double kSameDepth = 1e-9;

// A point moving p + t·d against the body's shape grown by `radius` all round.
Crossing GrownCrossing(Vec2 p, Vec2 d, double radius, const Shape& shape, const BodyState& state) {
  if (shape.type == ShapeType::kCircle) return CircleCrossing(p, d, state.position, shape.radius + radius);
  const Rot rotation = RotationOf(state.angle);
  Crossing crossing = RoundedBoxCrossing(InvRotate(rotation, p - state.position), InvRotate(rotation, d),
                                         shape.half_extents, radius);
  crossing.normal = Rotate(rotation, crossing.normal);
  return crossing;
}

// Where two touching boxes meet: the middle of their deepest manifold points.
Vec2 TouchPoint(const OrientedBox& a, const OrientedBox& b) {
  Manifold m;
  // The sweep found them touching; only rounding beyond the margin could make this fail.
  if (!CollideOrientedBoxes(a, b, &m, kTouchMargin)) return 0.5 * (a.center + b.center);
  double deepest = m.points[0].depth;
  for (int i = 1; i < m.point_count; ++i) deepest = std::max(deepest, m.points[i].depth);
  Vec2 sum;
  int count = 0;
  for (int i = 0; i < m.point_count; ++i) {
    if (m.points[i].depth < deepest - kSameDepth) continue;
    sum += m.points[i].point;
    ++count;
  }
  return sum / count;
}

// The hit `crossing` makes, if any; `point_at(t, normal)` places the touch. A mover that starts
// inside has no direction to report: normal {0, 0}, at its own position.
template <class PointAt>
std::optional<RayHit> Touch(const Cast& cast, const Crossing& crossing, PointAt point_at) {
  const std::optional<double> t = FirstTouch(crossing, cast.starts_inside_counts);
  if (!t) return std::nullopt;
  if (crossing.enter < 0.0) return RayHit{{}, cast.position, {}, 0.0};
  return RayHit{{}, point_at(*t, crossing.normal), crossing.normal, *t};
}

// Calls `on_hit(hit)` for each body the mover meets, in slot order.
template <class OnHit>
void ForEachHit(const Bodies& bodies, const Cast& cast, const std::optional<Filter>& filter, OnHit on_hit) {
  for (BodyIndex slot = 0; slot < bodies.states.size(); ++slot) {
    if (!IsQueried(bodies, slot, filter)) continue;
    const BodyGeometry* geometry = bodies.geometries[slot].get();
    std::optional<RayHit> hit = geometry ? CastAgainstPieces(cast, *geometry, bodies.states[slot])
                                         : CastAgainst(cast, bodies.infos[slot].shape, bodies.states[slot]);
    if (!hit) continue;
    hit->body = bodies.IdOf(slot);
    on_hit(*hit);
  }
}

}  // namespace

Cast Ray(Vec2 from, Vec2 to) {
  Cast ray;
  ray.shape = {ShapeType::kCircle, 0.0, {}};
  ray.position = from;
  ray.translation = to - from;
  return ray;
}

std::optional<RayHit> CastAgainst(const Cast& cast, const Shape& shape, const BodyState& state) {
  const Vec2 p = cast.position, d = cast.translation;
  if (cast.shape.type == ShapeType::kCircle) {
    const double r = cast.shape.radius;
    return Touch(cast, GrownCrossing(p, d, r, shape, state), [&](double t, Vec2 n) { return p + t * d - r * n; });
  }
  if (shape.type == ShapeType::kCircle) {
    // Seen from the box, the circle comes the other way: the same fraction, the normal reversed.
    Crossing crossing = GrownCrossing(state.position, -d, shape.radius, cast.shape, {p, {}, cast.angle, 0.0});
    crossing.normal = -crossing.normal;
    return Touch(cast, crossing, [&](double, Vec2 n) { return state.position + shape.radius * n; });
  }
  const OrientedBox moving{p, cast.shape.half_extents, RotationOf(cast.angle)};
  const OrientedBox still{state.position, shape.half_extents, RotationOf(state.angle)};
  return Touch(cast, BoxesCrossing(moving, d, still), [&](double t, Vec2) {
    return TouchPoint({p + t * d, moving.half_extents, moving.rotation}, still);
  });
}

std::optional<RayHit> FirstHit(const Bodies& bodies, const Cast& cast, const std::optional<Filter>& filter) {
  std::optional<RayHit> first;
  ForEachHit(bodies, cast, filter, [&](const RayHit& hit) {
    if (!first || hit.fraction < first->fraction) first = hit;
  });
  return first;
}

std::vector<RayHit> AllHits(const Bodies& bodies, const Cast& cast, const std::optional<Filter>& filter) {
  std::vector<RayHit> hits;
  ForEachHit(bodies, cast, filter, [&](const RayHit& hit) { hits.push_back(hit); });
  // Found in slot order; a stable sort keeps it among equal fractions.
  std::stable_sort(hits.begin(), hits.end(), [](const RayHit& a, const RayHit& b) { return a.fraction < b.fraction; });
  return hits;
}

}  // namespace engine::detail
