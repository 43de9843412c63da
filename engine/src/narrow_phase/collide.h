// Narrow phase: exact contact manifolds between circles and boxes, axis-aligned or turned.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/contact.h"
#include "engine/math.h"
#include "engine/portable_math.h"

namespace engine {

/// Each function returns false (and leaves `out` alone) when the shapes are farther apart than
/// `margin`; touching shapes collide with depth 0, and shapes up to `margin` apart give a
/// speculative contact with negative depth. Boxes are given by centre and half extents.
/// (CollideCircles and CollideBoxes inline: the narrow phase of a circle pour is mostly the
/// one, and a call that passes the centres in registers costs more than the test, measured; a
/// box pile's manifolds, written by a call, were read back by wider loads than stored them, a
/// stall on each.)
inline bool CollideCircles(Vec2 center_a, double radius_a, Vec2 center_b, double radius_b,
                           Manifold* out, double margin = 0.0);
bool CollideCircleBox(Vec2 center_a, double radius_a, Vec2 center_b, Vec2 half_b, Manifold* out,
                      double margin = 0.0);
inline bool CollideBoxes(Vec2 center_a, Vec2 half_a, Vec2 center_b, Vec2 half_b, Manifold* out,
                         double margin = 0.0);

/// A box turned by `rotation` about its centre.
struct OrientedBox {
  Vec2 center;
  Vec2 half_extents;
  Rot rotation;
};

/// A circle against a turned box: the axis-aligned test in the box's own frame.
bool CollideCircleOrientedBox(Vec2 center_a, double radius_a, const OrientedBox& b, Manifold* out,
                              double margin = 0.0);
/// Two turned boxes: the separating-axis test over the four face normals (early exit on a gap
/// wider than the margin), then the incident edge clipped against the reference face: up to
/// two points.
bool CollideOrientedBoxes(const OrientedBox& a, const OrientedBox& b, Manifold* out,
                          double margin = 0.0);

// Circles meet along the line between their centres.
inline bool CollideCircles(Vec2 center_a, double radius_a, Vec2 center_b, double radius_b,
                           Manifold* out, double margin) {
  const Vec2 d = center_b - center_a;
  const double distance_squared = LengthSquared(d);
  const double radii = radius_a + radius_b;
  const double reach = radii + margin;
  if (distance_squared > reach * reach) return false;
  const double distance = std::sqrt(distance_squared);
  // Concentric circles have no direction between them; push B straight up, deterministically.
  const Vec2 normal = distance > 0.0 ? d / distance : Vec2{0.0, 1.0};
  const Vec2 surface_a = center_a + radius_a * normal;
  const Vec2 surface_b = center_b - radius_b * normal;
  out->normal = normal;
  out->points[0] = {0.5 * (surface_a + surface_b), radii - distance};
  out->point_count = 1;
  return true;
}

// Two axis-aligned boxes: the overlap of their extents, split along the axis of least overlap.
inline bool CollideBoxes(Vec2 center_a, Vec2 half_a, Vec2 center_b, Vec2 half_b, Manifold* out,
                         double margin) {
  const Vec2 d = center_b - center_a;
  const double overlap_x = half_a.x + half_b.x - std::abs(d.x);
  const double overlap_y = half_a.y + half_b.y - std::abs(d.y);
  if (overlap_x < -margin || overlap_y < -margin) return false;

  const Vec2 lower = {Larger(center_a.x - half_a.x, center_b.x - half_b.x),
                      Larger(center_a.y - half_a.y, center_b.y - half_b.y)};
  const Vec2 upper = {Smaller(center_a.x + half_a.x, center_b.x + half_b.x),
                      Smaller(center_a.y + half_a.y, center_b.y + half_b.y)};
  // Separate along the axis of least overlap; ties go to y, the axis gravity presses along,
  // so a box landing exactly on a corner is stood up rather than pushed aside. On a tie in
  // position too (d = 0) B goes up or right. Point ids name the face (its normal) and the end.
  if (overlap_y <= overlap_x) {
    const double middle_y = 0.5 * (lower.y + upper.y);
    const bool up = d.y >= 0.0;
    out->normal = {0.0, up ? 1.0 : -1.0};
    const std::uint8_t face = up ? 0 : 2;
    out->points[0] = {{lower.x, middle_y}, overlap_y, face};
    out->points[1] = {{Larger(upper.x, lower.x), middle_y}, overlap_y,
                      static_cast<std::uint8_t>(face + 1)};
  } else {
    const double middle_x = 0.5 * (lower.x + upper.x);
    const bool right = d.x >= 0.0;
    out->normal = {right ? 1.0 : -1.0, 0.0};
    const std::uint8_t face = right ? 4 : 6;
    out->points[0] = {{middle_x, lower.y}, overlap_x, face};
    out->points[1] = {{middle_x, Larger(upper.y, lower.y)}, overlap_x,
                      static_cast<std::uint8_t>(face + 1)};
  }
  // Corner to corner the overlap is one point; two identical points would double its impulse.
  out->point_count = out->points[0].point == out->points[1].point ? 1 : 2;
  return true;
}

}  // namespace engine
