// Narrow phase for circles and axis-aligned boxes. Touching counts as contact (depth 0), so a
// body resting exactly on another is held from its first step; within the margin, a gap gives a
// speculative contact (negative depth) that lets the solver stop bodies exactly at contact.
#include "narrow_phase/collide.h"

#include <cmath>

namespace engine {

namespace {

// The face of a box (centre c, half extents h) nearest to an interior point p, as the outward
// normal and the distance from p to that face. Ties go to the first of +y, −y, +x, −x, so the
// answer never depends on anything but the numbers.
void NearestFace(Vec2 p, Vec2 c, Vec2 h, Vec2* outward, double* distance) {
  const Vec2 local = p - c;
  const double to_face[4] = {h.y - local.y, h.y + local.y, h.x - local.x, h.x + local.x};
  const Vec2 normals[4] = {{0.0, 1.0}, {0.0, -1.0}, {1.0, 0.0}, {-1.0, 0.0}};
  int best = 0;
  for (int i = 1; i < 4; ++i) {
    if (to_face[i] < to_face[best]) best = i;
  }
  *outward = normals[best];
  *distance = to_face[best];
}

}  // namespace

bool CollideCircleBox(Vec2 center_a, double radius_a, Vec2 center_b, Vec2 half_b, Manifold* out,
                      double margin) {
  const Vec2 lower = center_b - half_b;
  const Vec2 upper = center_b + half_b;
  const Vec2 closest = {Clamp(center_a.x, lower.x, upper.x), Clamp(center_a.y, lower.y, upper.y)};
  const Vec2 d = closest - center_a;
  const double distance_squared = LengthSquared(d);
  const double reach = radius_a + margin;
  if (distance_squared > reach * reach) return false;

  if (distance_squared > 0.0) {
    // Centre outside the box: the contact is at the box's closest point.
    const double distance = std::sqrt(distance_squared);
    const Vec2 normal = d / distance;
    const Vec2 surface_a = center_a + radius_a * normal;
    out->normal = normal;
    out->points[0] = {0.5 * (surface_a + closest), radius_a - distance};
  } else {
    // Centre inside (or on the boundary of) the box: leave through the nearest face.
    Vec2 outward;
    double to_face;
    NearestFace(center_a, center_b, half_b, &outward, &to_face);
    const Vec2 face_point = center_a + to_face * outward;
    const Vec2 surface_a = center_a - radius_a * outward;
    out->normal = -outward;
    out->points[0] = {0.5 * (surface_a + face_point), radius_a + to_face};
  }
  out->point_count = 1;
  return true;
}


}  // namespace engine
