// Helpers for the geometry tests: a seeded generator with a portable uniform mapping
// (std::uniform_real_distribution's output is implementation-defined), random convex shapes,
// and brute-force distances to check GJK and the manifolds against.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/math.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace geometry_test {

using engine::Vec2;

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [lo, hi): the top 53 bits of one draw scaled, the same on every library.
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(engine_() >> 11) * 0x1.0p-53);
  }
  Vec2 InBox(double half) { return {Uniform(-half, half), Uniform(-half, half)}; }
  /// A rotation by a uniform angle (libm is fine in tests: only the engine must be portable).
  engine::Rot AnyRotation() { return engine::MakeRot(Uniform(-3.14159265358979, 3.14159265358979)); }

 private:
  std::mt19937_64 engine_;
};

/// A convex polygon with `count` vertices on an ellipse at sorted random angles, so never
/// collinear, counter-clockwise round the origin.
inline std::vector<Vec2> RandomConvexPoints(Random& rng, int count, double rx, double ry) {
  std::vector<double> angles;
  for (int i = 0; i < count; ++i) angles.push_back(rng.Uniform(0.0, 2.0 * 3.14159265358979));
  std::sort(angles.begin(), angles.end());
  std::vector<Vec2> points;
  for (double a : angles) points.push_back({rx * std::cos(a), ry * std::sin(a)});
  return points;
}

inline double PointSegmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = engine::Dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(engine::Dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return engine::Length(p - (a + t * ab));
}

/// Whether p lies inside (or on) the convex counter-clockwise polygon (3+ points).
inline bool InsideConvex(const std::vector<Vec2>& poly, Vec2 p, double slack = 0.0) {
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if (engine::Cross(b - a, p - a) < -slack * engine::Length(b - a)) return false;
  }
  return true;
}

/// The distance between two convex point sets (closed hulls; 1 or 2 points are a point or a
/// segment) by brute force: 0 if one holds a point of the other or edges cross, else the least
/// vertex–edge distance.
inline double BruteDistance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const auto edges = [](const std::vector<Vec2>& p) {
    std::vector<std::pair<Vec2, Vec2>> e;
    if (p.size() == 1) e.push_back({p[0], p[0]});
    if (p.size() == 2) e.push_back({p[0], p[1]});
    if (p.size() >= 3) {
      for (std::size_t i = 0; i < p.size(); ++i) e.push_back({p[i], p[(i + 1) % p.size()]});
    }
    return e;
  };
  if (a.size() >= 3 && std::any_of(b.begin(), b.end(), [&](Vec2 q) { return InsideConvex(a, q); })) return 0.0;
  if (b.size() >= 3 && std::any_of(a.begin(), a.end(), [&](Vec2 q) { return InsideConvex(b, q); })) return 0.0;
  double best = INFINITY;
  for (const auto& [a1, a2] : edges(a)) {
    for (const auto& [b1, b2] : edges(b)) {
      // Crossing edges: opposite sides both ways.
      const double o1 = engine::Cross(a2 - a1, b1 - a1), o2 = engine::Cross(a2 - a1, b2 - a1);
      const double o3 = engine::Cross(b2 - b1, a1 - b1), o4 = engine::Cross(b2 - b1, a2 - b1);
      if (o1 * o2 < 0.0 && o3 * o4 < 0.0) return 0.0;
      best = std::min({best, PointSegmentDistance(a1, b1, b2), PointSegmentDistance(a2, b1, b2),
                       PointSegmentDistance(b1, a1, a2), PointSegmentDistance(b2, a1, a2)});
    }
  }
  return best;
}

inline std::vector<Vec2> Placed(const std::vector<Vec2>& points, const engine::geometry::Transform& xf) {
  std::vector<Vec2> out;
  for (Vec2 p : points) out.push_back(engine::geometry::TransformPoint(xf, p));
  return out;
}

inline std::vector<Vec2> CorePoints(const engine::geometry::Polygon& p) {
  return {p.vertices, p.vertices + p.count};
}

}  // namespace geometry_test
