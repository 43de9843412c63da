// Closest points between segments: minimise |p1 + s·d1 − p2 − t·d2|² over the unit square,
// clamping s, then t, and s again when t was clamped.
#include "geometry/segment_distance.h"

namespace engine::geometry {

namespace {

// Squared length below which a segment is taken as a point, and the relative size of the
// parallel test's determinant below which two segments are taken as parallel.
constexpr double kPointLengthSquared = 1e-30;
constexpr double kParallel = 1e-12;

double Clamp01(double v) { return Clamp(v, 0.0, 1.0); }

}  // namespace

SegmentDistanceResult SegmentDistance(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2) {
  const Vec2 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r);
  double s = 0.0, t = 0.0;
  if (a <= kPointLengthSquared) {
    if (e > kPointLengthSquared) t = Clamp01(f / e);
  } else {
    const double c = Dot(d1, r);
    if (e <= kPointLengthSquared) {
      s = Clamp01(-c / a);
    } else {
      const double b = Dot(d1, d2), denominator = a * e - b * b;
      s = denominator > kParallel * a * e ? Clamp01((b * f - c * e) / denominator) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0, s = Clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0, s = Clamp01((b - c) / a);
      }
    }
  }
  SegmentDistanceResult result;
  result.fraction1 = s, result.fraction2 = t;
  result.closest1 = p1 + s * d1;
  result.closest2 = p2 + t * d2;
  result.distance_squared = LengthSquared(result.closest1 - result.closest2);
  return result;
}

}  // namespace engine::geometry
