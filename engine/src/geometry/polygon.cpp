// Building convex polygons: edge normals and the core's centroid.
#include "geometry/polygon.h"

#include <cassert>

namespace engine::geometry {

namespace {

// The area centroid by a fan of triangles from the first vertex (kept as the origin of the sums,
// which keeps them small for a polygon far from its frame's origin).
Vec2 CoreCentroid(const Polygon& p) {
  if (p.count == 2) return 0.5 * (p.vertices[0] + p.vertices[1]);
  const Vec2 origin = p.vertices[0];
  double area = 0.0;
  Vec2 moment;
  for (int i = 1; i + 1 < p.count; ++i) {
    const Vec2 e1 = p.vertices[i] - origin, e2 = p.vertices[i + 1] - origin;
    const double triangle_area = 0.5 * Cross(e1, e2);
    area += triangle_area;
    moment += (triangle_area / 3.0) * (e1 + e2);
  }
  return origin + moment / area;
}

}  // namespace

Polygon MakePolygon(std::span<const Vec2> points, double radius) {
  assert(points.size() >= 2 && points.size() <= kMaxPolygonVertices);
  Polygon p;
  p.count = static_cast<int>(points.size());
  p.radius = radius;
  for (int i = 0; i < p.count; ++i) p.vertices[i] = points[i];
  for (int i = 0; i < p.count; ++i) {
    p.normals[i] = EdgeNormal(p.vertices[i], p.vertices[(i + 1) % p.count]);
  }
  p.centroid = CoreCentroid(p);
  return p;
}

Polygon PlacePolygon(const Polygon& polygon, const Transform& xf) {
  Polygon placed;
  placed.count = polygon.count;
  placed.radius = polygon.radius;
  placed.centroid = TransformPoint(xf, polygon.centroid);
  for (int i = 0; i < polygon.count; ++i) {
    placed.vertices[i] = TransformPoint(xf, polygon.vertices[i]);
    placed.normals[i] = Rotate(xf.rotation, polygon.normals[i]);
  }
  return placed;
}

Polygon MakeBox(double half_width, double half_height) {
  return MakeOffsetBox(half_width, half_height, {0.0, 0.0}, Rot{});
}

Polygon MakeOffsetBox(double half_width, double half_height, Vec2 center, Rot rotation) {
  const Vec2 corners[4] = {{-half_width, -half_height},
                           {half_width, -half_height},
                           {half_width, half_height},
                           {-half_width, half_height}};
  Vec2 placed[4];
  for (int i = 0; i < 4; ++i) placed[i] = center + Rotate(rotation, corners[i]);
  return MakePolygon(placed);
}

Polygon MakeCapsulePolygon(const Capsule& capsule) {
  const Vec2 centers[2] = {capsule.center1, capsule.center2};
  return MakePolygon(centers, capsule.radius);
}

}  // namespace engine::geometry
