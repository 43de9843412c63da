// Narrow phase for turned boxes: separating axes and edge clipping, in the manner of
// Box2D's polygon collider (Catto, "Contact Manifolds", GDC 2007), written for two boxes.
#include <cmath>

#include "narrow_phase/collide.h"
#include "engine/portable_math.h"

namespace engine {

bool CollideCircleOrientedBox(Vec2 center_a, double radius_a, const OrientedBox& b, Manifold* out,
                              double margin) {
  const Vec2 local = InvRotate(b.rotation, center_a - b.center);
  Manifold m;
  if (!CollideCircleBox(local, radius_a, {0.0, 0.0}, b.half_extents, &m, margin)) return false;
  out->normal = Rotate(b.rotation, m.normal);
  out->points[0] = {b.center + Rotate(b.rotation, m.points[0].point), m.points[0].depth, 0};
  out->point_count = 1;
  return true;
}

namespace {

// Corners counter-clockwise from the lower left; face i runs from corner i to corner i + 1, with
// outward normals down, right, up, left.
struct BoxFrame {
  Vec2 corners[4];
  Vec2 normals[4];
};

BoxFrame Frame(const OrientedBox& box) {
  const Vec2 h = box.half_extents;
  // Each corner and normal made from its coordinates in registers: from an array of the local
  // corners, each was stored as two halves and loaded whole, the load waiting for both stores
  // (45 % of the samples here in the turning pyramid of base 40).
  const auto corner = [&](double x, double y) { return box.center + Rotate(box.rotation, Vec2{x, y}); };
  const auto normal = [&](double x, double y) { return Rotate(box.rotation, Vec2{x, y}); };
  BoxFrame f;
  f.corners[0] = corner(-h.x, -h.y);
  f.corners[1] = corner(h.x, -h.y);
  f.corners[2] = corner(h.x, h.y);
  f.corners[3] = corner(-h.x, h.y);
  f.normals[0] = normal(0, -1);
  f.normals[1] = normal(1, 0);
  f.normals[2] = normal(0, 1);
  f.normals[3] = normal(-1, 0);
  return f;
}

// The face of `reference` that `other` is farthest in front of: the largest separation along
// a face normal (negative when overlapping). Ties keep the lower face index.
double MaxSeparation(const BoxFrame& reference, const BoxFrame& other, int* face) {
  double best = -INFINITY;
  for (int i = 0; i < 4; ++i) {
    double deepest = INFINITY;
    for (const Vec2& corner : other.corners) {
      deepest = Smaller(deepest, Dot(reference.normals[i], corner - reference.corners[i]));
    }
    if (deepest > best) best = deepest, *face = i;
  }
  return best;
}

}  // namespace

bool CollideOrientedBoxes(const OrientedBox& a, const OrientedBox& b, Manifold* out, double margin) {
  const BoxFrame fa = Frame(a), fb = Frame(b);
  int face_a = 0, face_b = 0;
  const double separation_a = MaxSeparation(fa, fb, &face_a);
  if (separation_a > margin) return false;
  const double separation_b = MaxSeparation(fb, fa, &face_b);
  if (separation_b > margin) return false;

  // Prefer A's face unless B's is clearly better, so the choice does not flicker between
  // nearly equal faces from step to step (which would defeat warm starting).
  constexpr double kFaceTolerance = 5e-4;
  const bool flip = separation_b > separation_a + kFaceTolerance;
  const BoxFrame& ref = flip ? fb : fa;
  const BoxFrame& inc = flip ? fa : fb;
  const int ref_face = flip ? face_b : face_a;
  const Vec2 n = ref.normals[ref_face];

  // The incident face: the other box's face most against the reference normal.
  int inc_face = 0;
  double most_against = INFINITY;
  for (int i = 0; i < 4; ++i) {
    const double d = Dot(inc.normals[i], n);
    if (d < most_against) most_against = d, inc_face = i;
  }
  // Each point is named by the end of the incident edge it comes from, clipped or not (Box2D v3
  // names its clipped points the same way): when two boxes of the same width are stacked, a
  // rounding error decides whether an end is clipped, and an id that changed with it would lose
  // that point's warm-start impulse at random.
  Vec2 clipped[2] = {inc.corners[inc_face], inc.corners[(inc_face + 1) % 4]};

  // Clip the incident edge to the reference face's extent along its tangent.
  const Vec2 v1 = ref.corners[ref_face];
  const Vec2 v2 = ref.corners[(ref_face + 1) % 4];
  const Vec2 tangent = v2 - v1;
  const double face_length = Length(tangent);
  const Vec2 t = tangent / face_length;
  const double lower = 0.0, upper = face_length;
  for (int side = 0; side < 2; ++side) {
    // side 0 keeps Dot(t, p − v1) ≥ lower; side 1 keeps it ≤ upper.
    const double d0 = side == 0 ? Dot(t, clipped[0] - v1) - lower : upper - Dot(t, clipped[0] - v1);
    const double d1 = side == 0 ? Dot(t, clipped[1] - v1) - lower : upper - Dot(t, clipped[1] - v1);
    if (d0 < 0.0 && d1 < 0.0) return false;  // the edge misses the face (only within the margin)
    if (d0 < 0.0) {
      clipped[0] = clipped[0] + (d0 / (d0 - d1)) * (clipped[1] - clipped[0]);
    } else if (d1 < 0.0) {
      clipped[1] = clipped[1] + (d1 / (d1 - d0)) * (clipped[0] - clipped[1]);
    }
  }

  out->normal = flip ? -n : n;
  out->point_count = 0;
  for (int i = 0; i < 2; ++i) {
    const double separation = Dot(n, clipped[i] - v1);
    if (separation > margin) continue;
    // Midway between the incident point and its projection on the reference face.
    const Vec2 point = clipped[i] - (0.5 * separation) * n;
    const auto id = static_cast<std::uint8_t>((flip ? 0x80 : 0) | (ref_face << 4) | (inc_face << 2) | i);
    // Field by field: a point built whole was copied with a 16-byte load over its depth's and
    // id's stores, which waited for them.
    ContactPoint& kept = out->points[out->point_count++];
    kept.point = point;
    kept.depth = -separation;
    kept.id = id;
  }
  return out->point_count > 0;
}

}  // namespace engine
