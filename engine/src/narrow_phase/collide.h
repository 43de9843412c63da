// Narrow phase: exact contact manifolds between circles and boxes, axis-aligned or turned.
#pragma once

#include <cmath>
#include <cstdint>

#include "engine/contact.h"
#include "engine/math.h"

namespace engine {

/// Each function returns false (and leaves `out` alone) when the shapes are farther apart than
/// `margin`; touching shapes collide with depth 0, and shapes up to `margin` apart give a
/// speculative contact with negative depth. Boxes are given by centre and half extents.
/// (Inline: the narrow phase of a circle pour is mostly this, and a call that passes the
/// centres in registers costs more than the test, measured.)
inline bool CollideCircles(Vec2 center_a, double radius_a, Vec2 center_b, double radius_b,
                           Manifold* out, double margin = 0.0);
bool CollideCircleBox(Vec2 center_a, double radius_a, Vec2 center_b, Vec2 half_b, Manifold* out,
                      double margin = 0.0);
bool CollideBoxes(Vec2 center_a, Vec2 half_a, Vec2 center_b, Vec2 half_b, Manifold* out,
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

}  // namespace engine
