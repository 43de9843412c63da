// Ray casts in the shape's frame: the ray against each boundary piece (edges, corner discs),
// keeping the first entry.
#include "geometry/ray_cast.h"

#include <cmath>

namespace engine::geometry {

namespace {

struct LocalRay {
  Vec2 p;  // origin
  Vec2 d;  // translation
};

// The fraction at which the ray crosses the edge e1 → e2 from the side its normal n faces.
bool CrossesEdge(const LocalRay& ray, Vec2 e1, Vec2 e2, Vec2 n, double* t) {
  const double approach = Dot(n, ray.d);
  const double height = Dot(n, ray.p - e1);  // how far in front of the edge's line the ray starts
  if (approach >= 0.0 || height < 0.0) return false;
  const double crossing = height / -approach;
  const Vec2 q = ray.p + crossing * ray.d;
  const double along = Dot(q - e1, e2 - e1);
  if (along < 0.0 || along > LengthSquared(e2 - e1)) return false;
  *t = crossing;
  return true;
}

// The fraction at which the ray enters the disc of radius r at c, from outside it.
bool EntersDisc(const LocalRay& ray, Vec2 c, double r, double* t) {
  const Vec2 m = ray.p - c;
  const double a = Dot(ray.d, ray.d), b = Dot(m, ray.d), k = Dot(m, m) - r * r;
  if (a == 0.0 || k < 0.0) return false;
  const double discriminant = b * b - a * k;
  if (discriminant < 0.0 || b >= 0.0) return false;  // misses, or heads away
  *t = (-b - std::sqrt(discriminant)) / a;
  return true;
}

// Keeps the first hit within the ray's reach (on a tie, the piece offered first).
void Offer(double t, Vec2 normal, double* best, Vec2* best_normal, bool* found) {
  if (*found ? t < *best : t <= *best) *best = t, *best_normal = normal, *found = true;
}

CastOutput ToWorld(const Transform& xf, const RayCastInput& ray, double t, Vec2 normal) {
  return {ray.origin + t * ray.translation, Rotate(xf.rotation, normal), t, true};
}

}  // namespace

CastOutput RayCastPolygon(const Polygon& polygon, const Transform& xf, const RayCastInput& ray) {
  const LocalRay local{InvTransformPoint(xf, ray.origin), InvRotate(xf.rotation, ray.translation)};
  double best = ray.max_fraction, t = 0.0;
  Vec2 normal;
  bool found = false;
  const double r = polygon.radius;
  for (int i = 0; i < polygon.count; ++i) {
    const Vec2 n = polygon.normals[i], offset = r * n;
    const Vec2 e1 = polygon.vertices[i] + offset;
    const Vec2 e2 = polygon.vertices[(i + 1) % polygon.count] + offset;
    if (CrossesEdge(local, e1, e2, n, &t)) Offer(t, n, &best, &normal, &found);
    if (r > 0.0 && EntersDisc(local, polygon.vertices[i], r, &t)) {
      Offer(t, (local.p + t * local.d - polygon.vertices[i]) / r, &best, &normal, &found);
    }
  }
  return found ? ToWorld(xf, ray, best, normal) : CastOutput{};
}

CastOutput RayCastCapsule(const Capsule& capsule, const Transform& xf, const RayCastInput& ray) {
  return RayCastPolygon(MakeCapsulePolygon(capsule), xf, ray);
}

CastOutput RayCastSegment(Vec2 start, Vec2 end, const Transform& xf, const RayCastInput& ray) {
  const LocalRay local{InvTransformPoint(xf, ray.origin), InvRotate(xf.rotation, ray.translation)};
  Vec2 n = EdgeNormal(start, end);
  if (Dot(n, local.d) > 0.0) n = -n;  // the side the ray comes from
  double t = 0.0;
  if (!CrossesEdge(local, start, end, n, &t) || t > ray.max_fraction) return {};
  return ToWorld(xf, ray, t, n);
}

}  // namespace engine::geometry
