// Ray casts against circles and (turned) boxes: the nearest hit over all bodies, in id order so
// that equal distances resolve to the lower id.
#include <cmath>
#include <limits>

#include "world_impl.h"

namespace engine {

namespace {

// Entry fraction of the ray p + t·d (t ∈ [0, 1]) into a circle at c of radius r, and its normal.
bool RayCircle(Vec2 p, Vec2 d, Vec2 c, double r, double* t, Vec2* normal) {
  const Vec2 m = p - c;
  const double a = Dot(d, d), b = Dot(m, d), k = Dot(m, m) - r * r;
  if (a == 0.0) return false;
  const double discriminant = b * b - a * k;
  if (discriminant < 0.0) return false;
  const double entry = (-b - std::sqrt(discriminant)) / a;
  if (entry < 0.0 || entry > 1.0) return false;  // starting inside counts as no hit
  *t = entry;
  *normal = (m + entry * d) / r;
  return true;
}

// Slab test in the box's frame (half extents h): the entry fraction and the entered face.
bool RayBox(Vec2 p, Vec2 d, Vec2 h, double* t, Vec2* normal) {
  double enter = 0.0, leave = 1.0;
  Vec2 face;
  const double start[2] = {p.x, p.y}, dir[2] = {d.x, d.y}, half[2] = {h.x, h.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (dir[axis] == 0.0) {
      if (std::abs(start[axis]) > half[axis]) return false;
      continue;
    }
    double near = (-half[axis] - start[axis]) / dir[axis];
    double far = (half[axis] - start[axis]) / dir[axis];
    double sign = -1.0;
    if (near > far) std::swap(near, far), sign = 1.0;
    if (near > enter) {
      enter = near;
      face = axis == 0 ? Vec2{sign, 0.0} : Vec2{0.0, sign};
    }
    leave = std::min(leave, far);
    if (enter > leave) return false;
  }
  if (face == Vec2{}) return false;  // starting inside counts as no hit
  *t = enter;
  *normal = face;
  return true;
}

}  // namespace

std::optional<RayHit> World::RayCast(Vec2 from, Vec2 to) const {
  std::optional<RayHit> best;
  double best_t = std::numeric_limits<double>::infinity();
  const Vec2 d = to - from;
  for (BodyIndex id = 0; id < impl_->bodies.states.size(); ++id) {
    if (!impl_->bodies.enabled[id]) continue;
    const Shape& shape = impl_->bodies.infos[id].shape;
    const BodyState& s = impl_->bodies.states[id];
    double t;
    Vec2 normal;
    bool hit;
    if (shape.type == ShapeType::kCircle) {
      hit = RayCircle(from, d, s.position, shape.radius, &t, &normal);
    } else {
      const Rot q = MakeRot(s.angle);
      hit = RayBox(InvRotate(q, from - s.position), InvRotate(q, d), shape.half_extents, &t, &normal);
      normal = Rotate(q, normal);
    }
    if (hit && t < best_t) {
      best_t = t;
      best = RayHit{impl_->bodies.IdOf(id), from + t * d, normal, t};
    }
  }
  return best;
}

}  // namespace engine
