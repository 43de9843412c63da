// Sweeps of a point against circles and boxes (Ericson, Real-Time Collision Detection, §5.3.2
// ray-sphere, §5.3.3 ray-slab, §5.5.7 moving sphere against box), and of a box against a box by
// the separating axes (§5.5.8's moving AABBs, with the boxes' face normals as the axes).
#include "queries/sweep.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace engine::detail {

namespace {

// Narrows `crossing` to the span where the mover's coordinate along `axis`, start + t·speed,
// lies within [−half, half]. An entry later than the others makes this slab's face the one
// entered; on a tie the earlier axis keeps it, so the answer depends on the numbers alone.
void ClipToSlab(double start, double speed, double half, Vec2 axis, Crossing* crossing) {
  crossing->starts_inside = crossing->starts_inside && std::abs(start) < half;
  if (speed == 0.0) {
    if (std::abs(start) > half) *crossing = Crossing{};  // parallel, outside: never inside
    return;
  }
  double near = (-half - start) / speed, far = (half - start) / speed;
  Vec2 face = -axis;
  if (near > far) std::swap(near, far), face = axis;
  if (near > crossing->enter) crossing->enter = near, crossing->normal = face;
  crossing->leave = std::min(crossing->leave, far);
}

// How far a box reaches from its centre along a unit axis.
double ProjectedRadius(const OrientedBox& box, Vec2 axis) {
  const Vec2 x_axis = Rotate(box.rotation, {1.0, 0.0}), y_axis = Rotate(box.rotation, {0.0, 1.0});
  return box.half_extents.x * std::abs(Dot(axis, x_axis)) + box.half_extents.y * std::abs(Dot(axis, y_axis));
}

}  // namespace

Crossing CircleCrossing(Vec2 p, Vec2 d, Vec2 center, double radius) {
  const Vec2 m = p - center;
  const double a = Dot(d, d), b = Dot(m, d), k = Dot(m, m) - radius * radius;
  if (a == 0.0) {
    if (k > 0.0) return {};
    Crossing still = Crossing::Always();
    still.starts_inside = k < 0.0;
    return still;
  }
  const double discriminant = b * b - a * k;
  if (discriminant < 0.0) return {};
  const double root = std::sqrt(discriminant);
  const double enter = (-b - root) / a;
  return {enter, (-b + root) / a, (m + enter * d) / radius, k < 0.0};
}

Crossing BoxCrossing(Vec2 p, Vec2 d, Vec2 half) {
  Crossing crossing = Crossing::Always();
  ClipToSlab(p.x, d.x, half.x, {1.0, 0.0}, &crossing);
  ClipToSlab(p.y, d.y, half.y, {0.0, 1.0}, &crossing);
  return crossing;
}

Crossing RoundedBoxCrossing(Vec2 p, Vec2 d, Vec2 half, double radius) {
  const Crossing grown = BoxCrossing(p, d, half + Vec2{radius, radius});
  if (radius == 0.0 || !grown.Meets()) return grown;
  // Where the mover is first within the grown box: beyond the box on both axes it is in a
  // corner's square, whose inner sides lie within that corner's circle, so the circle decides.
  const Vec2 first = p + std::max(grown.enter, 0.0) * d;
  if (std::abs(first.x) <= half.x || std::abs(first.y) <= half.y) return grown;
  const Vec2 corner{std::copysign(half.x, first.x), std::copysign(half.y, first.y)};
  return CircleCrossing(p, d, corner, radius);
}

Crossing BoxesCrossing(const OrientedBox& moving, Vec2 d, const OrientedBox& still) {
  // Two convex polygons overlap exactly when their shadows overlap on every face normal of
  // either (the separating axis theorem), so the span of overlap is the four slabs' in common.
  const Vec2 axes[4] = {Rotate(moving.rotation, {1.0, 0.0}), Rotate(moving.rotation, {0.0, 1.0}),
                        Rotate(still.rotation, {1.0, 0.0}), Rotate(still.rotation, {0.0, 1.0})};
  const Vec2 offset = moving.center - still.center;
  Crossing crossing = Crossing::Always();
  for (const Vec2 axis : axes) {
    const double reach = ProjectedRadius(moving, axis) + ProjectedRadius(still, axis);
    ClipToSlab(Dot(offset, axis), Dot(d, axis), reach, axis, &crossing);
  }
  return crossing;
}

std::optional<double> FirstTouch(const Crossing& crossing, bool starts_inside_counts) {
  if (!crossing.Meets()) return std::nullopt;
  // A touch exactly at the start computes as −0 when the mover is already on the outline.
  if (crossing.enter >= 0.0) return crossing.enter <= 1.0 ? std::optional(crossing.enter + 0.0) : std::nullopt;
  if (starts_inside_counts && crossing.starts_inside) return 0.0;
  return std::nullopt;
}

}  // namespace engine::detail
