// Arctangent by argument halving and a short Taylor series: each halving
// atan x = 2·atan(x / (1 + √(1 + x²))) shrinks the argument, and three of them take [0, 1] to
// [0, tan(π/32)] ≈ [0, 0.0985], where nine terms of x − x³/3 + x⁵/5 − … leave an error below
// 10⁻¹⁸ of the result.
#include "geometry/turn_angle.h"

#include <cmath>

namespace engine::geometry {

namespace {

constexpr int kHalvings = 3;
constexpr int kSeriesTerms = 9;

// atan(x) for 0 ≤ x ≤ 1.
double AtanOfUnitRange(double x) {
  for (int i = 0; i < kHalvings; ++i) x = x / (1.0 + std::sqrt(1.0 + x * x));
  const double x2 = x * x;
  double power = x, sum = x;
  for (int k = 1; k <= kSeriesTerms; ++k) {
    power *= -x2;
    sum += power / (2 * k + 1);
  }
  return sum * (1 << kHalvings);
}

}  // namespace

double PortableAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  if (ax == 0.0 && ay == 0.0) return 0.0;
  // Reduce to the first octant, then unfold: the quadrant from the signs, as atan2 does.
  double angle = ay <= ax ? AtanOfUnitRange(ay / ax) : 0.5 * kPi - AtanOfUnitRange(ax / ay);
  if (x < 0.0) angle = kPi - angle;
  return y < 0.0 ? -angle : angle;
}

double TurnAngle(Vec2 from, Vec2 to) {
  const double angle = PortableAtan2(Cross(from, to), Dot(from, to));
  return angle < 0.0 ? angle + 2.0 * kPi : angle;
}

}  // namespace engine::geometry
