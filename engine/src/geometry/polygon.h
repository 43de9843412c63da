// Convex polygons (up to 64 vertices, counter-clockwise, optionally rounded) and capsules, in
// their own frame. A capsule is also a two-vertex polygon with a radius, as in Box2D, so every
// polygon routine (mass, manifolds, distance, ray casts) serves it too.
#pragma once

#include <span>

#include "engine/math.h"
#include "geometry/transform.h"

namespace engine::geometry {

inline constexpr int kMaxPolygonVertices = 64;

/// A convex polygon grown by `radius`: every point within `radius` of the core polygon. Edge i
/// runs from vertex i to vertex i + 1 (mod count), counter-clockwise, with outward unit normal
/// normals[i]. Two vertices make a capsule (the core is a segment, its two edges the two sides).
struct Polygon {
  Vec2 vertices[kMaxPolygonVertices];
  Vec2 normals[kMaxPolygonVertices];
  Vec2 centroid;        ///< of the core's area (the segment's midpoint for two vertices)
  double radius = 0.0;  ///< m, ≥ 0
  int count = 0;        ///< 2 to kMaxPolygonVertices
};

/// A stadium: the segment between the two cap centres grown by `radius` (> 0).
struct Capsule {
  Vec2 center1;
  Vec2 center2;
  double radius = 0.0;
};

/// A polygon from 3 to 64 points that are already convex, counter-clockwise and free of
/// collinear runs (what NormaliseOutline gives for a convex outline), or from 2 distinct points
/// (a capsule core). The points are not checked here: validate a user's outline first.
Polygon MakePolygon(std::span<const Vec2> points, double radius = 0.0);

/// The box [−hx, hx] × [−hy, hy], corners counter-clockwise from the lower left (the corner order
/// of the oriented-box collider, so face i means the same face in both).
Polygon MakeBox(double half_width, double half_height);

/// A box centred at `center` and turned by `rotation` in the shape's frame.
Polygon MakeOffsetBox(double half_width, double half_height, Vec2 center, Rot rotation);

Polygon MakeCapsulePolygon(const Capsule& capsule);

/// The polygon moved by `xf`: vertices, normals and centroid in the frame xf maps into.
Polygon PlacePolygon(const Polygon& polygon, const Transform& xf);

/// The outward unit normal of the edge from a to b of a counter-clockwise outline.
inline Vec2 EdgeNormal(Vec2 a, Vec2 b) {
  const Vec2 e = b - a;
  return Vec2{e.y, -e.x} / Length(e);
}

}  // namespace engine::geometry
