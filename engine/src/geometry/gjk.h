// The distance between two convex shapes by GJK (Gilbert, Johnson and Keerthi, "A fast procedure
// for computing the distance between complex objects in three-dimensional space", 1988), with
// the 2D simplex solved by Voronoi regions in barycentric coordinates (Ericson, "Real-Time
// Collision Detection", 2005, ch. 9; Catto, "Computing Distance", GDC 2010).
#pragma once

#include <span>

#include "engine/math.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// A convex shape as the hull of its core points grown by a radius: a polygon, a capsule (two
/// points), a segment (two points, radius 0) or a circle (one point).
struct ShapeProxy {
  Vec2 points[kMaxPolygonVertices];
  int count = 0;
  double radius = 0.0;
};

ShapeProxy MakeProxy(std::span<const Vec2> points, double radius);
ShapeProxy MakeProxy(const Polygon& polygon);
ShapeProxy MakeProxy(const Capsule& capsule);

/// A vertex of the witness simplex: a point of each core (world), and its weight in the
/// closest points.
struct SimplexVertex {
  Vec2 point_a;
  Vec2 point_b;
  double weight = 0.0;
  int index_a = 0;  ///< which of A's points
  int index_b = 0;
};

struct DistanceOutput {
  Vec2 point_a;            ///< the closest point on A's core, world
  Vec2 point_b;            ///< on B's core
  Vec2 normal;             ///< unit, from A to B; (0, 0) when the cores overlap
  double distance = 0.0;   ///< between the cores, 0 when they overlap
  /// Between the surfaces: distance − radius_a − radius_b (negative when the skins overlap;
  /// when the cores overlap too it is only −(radius_a + radius_b), not the depth).
  double separation = 0.0;
  SimplexVertex simplex[3];  ///< the witness: point_a = Σ weight·simplex.point_a, likewise B
  int simplex_count = 0;     ///< 3 means the cores overlap
  int iterations = 0;
};

/// The closest points between the cores of a (placed by xa) and b (placed by xb). Deterministic
/// and allocation free; at most kMaxGjkIterations support steps.
DistanceOutput ShapeDistance(const ShapeProxy& a, const Transform& xa, const ShapeProxy& b,
                             const Transform& xb);

inline constexpr int kMaxGjkIterations = 40;

}  // namespace engine::geometry
