// Conservative advancement: at each t the GJK normal n gives a lower bound on the distance,
// the separation along n, which no point can close faster than
// −n·(v_b − v_a) + ω_a·R_a + ω_b·R_b, so advancing t by (separation − target) over that rate
// never passes the first contact.
#include "geometry/time_of_impact.h"

#include <algorithm>
#include <cmath>

namespace engine::geometry {

namespace {

// The fastest the blended rotation turns, per unit of t. The blend (1 − t)·q1 + t·q2 of two
// rotations Δ apart turns at sin Δ / |blend|², fastest at t = ½ where |blend|² = (1 + cos Δ)/2:
// 2·sin Δ / (1 + cos Δ) = 2·tan(Δ/2), which is ≥ Δ, so also bounds the turn rate.
double MaxTurnRate(const Sweep& sweep) {
  const Rot delta = InvMulRot(sweep.rotation1, sweep.rotation2);
  return 2.0 * std::abs(delta.s) / (1.0 + delta.c);
}

// How far the shape's core reaches from its centre of mass.
double Reach(const ShapeProxy& proxy, Vec2 local_center) {
  double reach_squared = 0.0;
  for (int i = 0; i < proxy.count; ++i) {
    reach_squared = std::max(reach_squared, LengthSquared(proxy.points[i] - local_center));
  }
  return std::sqrt(reach_squared);
}

}  // namespace

Transform SweepTransform(const Sweep& sweep, double t) {
  const Vec2 center = (1.0 - t) * sweep.center1 + t * sweep.center2;
  const Rot q = NormalizeRot({(1.0 - t) * sweep.rotation1.c + t * sweep.rotation2.c,
                              (1.0 - t) * sweep.rotation1.s + t * sweep.rotation2.s});
  return {center - Rotate(q, sweep.local_center), q};
}

ToiOutput TimeOfImpact(const ShapeProxy& a, const Sweep& sweep_a, const ShapeProxy& b,
                       const Sweep& sweep_b, const ToiSettings& settings) {
  const Vec2 relative_motion = (sweep_b.center2 - sweep_b.center1) - (sweep_a.center2 - sweep_a.center1);
  const double turning = MaxTurnRate(sweep_a) * Reach(a, sweep_a.local_center) +
                         MaxTurnRate(sweep_b) * Reach(b, sweep_b.local_center);
  double t = 0.0;
  double separation = 0.0;
  for (int iteration = 0; iteration < settings.max_iterations; ++iteration) {
    const DistanceOutput d =
        ShapeDistance(a, SweepTransform(sweep_a, t), b, SweepTransform(sweep_b, t));
    separation = d.separation;
    if (separation < settings.target - settings.tolerance) {
      // Possible only at the start: the advancement never steps past the target.
      return {iteration == 0 ? ToiState::kOverlapped : ToiState::kHit, t, separation, iteration};
    }
    if (separation <= settings.target + settings.tolerance) {
      return {ToiState::kHit, t, separation, iteration};
    }
    const double closing_speed = std::max(0.0, -Dot(relative_motion, d.normal)) + turning;
    if (closing_speed > 0.0) t += (separation - settings.target) / closing_speed;
    if (closing_speed <= 0.0 || t >= 1.0) {
      return {ToiState::kSeparated, 1.0, separation, iteration + 1};
    }
  }
  return {ToiState::kFailed, t, separation, settings.max_iterations};
}

}  // namespace engine::geometry
