// Impacts with restitution, pair by pair, with the bounce placed at the moment of impact.
#include "impact.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace engine::detail {

namespace {

// Passes over the contacts before giving up on a chain of impacts; each pass carries an impact
// at least one pair further, so this bounds the chains resolved exactly to this many pairs.
constexpr int kMaxImpactPasses = 64;

struct Bounce {
  double start_velocity;  ///< relative normal velocity to give the pair now
  double lag;             ///< separation to add after the step
};

// The bounce of a pair approaching at `vn` from separation `s0` under relative acceleration `a`,
// integrated in `n` substeps of `h`; nothing when the pair would not come within `slop` of each
// other in this step. Meeting just at the step's end counts: left to the next step, the contact
// solver would see the pair touching and absorb the impact before the bounce.
bool ComputeBounce(double s0, double vn, double a, double e, int n, double h, double slop,
                   Bounce* out) {
  // Where free flight would take the pair by the end of the step (semi-implicit Euler).
  const double kicks = h * h * n * (n + 1) / 2.0;
  const double s_free = s0 + n * h * vn + a * kicks;
  if (s_free >= slop) return false;
  const double s_end = -e * s_free;  // mirrored: where a bounce at the moment of impact ends up
  const double energy = 0.5 * vn * vn - a * s0 + 0.5 * a * h * vn;
  // Solve ½v² + ½·a·h·v − (a·s_end + e²·H) = 0 for the separating root.
  const double half_ah = 0.5 * a * h;
  const double discriminant = half_ah * half_ah + 2.0 * (a * s_end + e * e * energy);
  const double v_end = -half_ah + std::sqrt(std::max(discriminant, 0.0));
  out->start_velocity = v_end - a * n * h;
  out->lag = s_end - (s0 + n * h * out->start_velocity + a * kicks);
  return true;
}

}  // namespace

void ResolveImpacts(std::span<SubstepConstraint> constraints, std::span<BodyState> states,
                    std::span<const Vec2> accelerations, const WorldDef& def) {
  const double h = def.dt / def.substeps;
  for (int pass = 0; pass < kMaxImpactPasses; ++pass) {
    bool any = false;
    for (SubstepConstraint& sc : constraints) {
      if (sc.restitution == 0.0) continue;
      BodyState& a = states[sc.a];
      BodyState& b = states[sc.b];
      // A turning pair is struck at the middle of its manifold, so a box landing flat stays flat.
      Vec2 anchor_a, anchor_b;
      double separation = sc.points[0].base_separation;
      double normal_mass = sc.points[0].normal_mass;
      if (sc.angular) {
        separation = std::numeric_limits<double>::infinity();
        for (int k = 0; k < sc.point_count; ++k) {
          const SubstepPoint& p = sc.points[k];
          anchor_a += p.anchor_a / sc.point_count;
          anchor_b += p.anchor_b / sc.point_count;
          separation = std::min(separation, p.base_separation + Dot(p.anchor_b - p.anchor_a, sc.normal));
        }
        const double ra = Cross(anchor_a, sc.normal), rb = Cross(anchor_b, sc.normal);
        normal_mass = 1.0 / (sc.inv_mass_a + sc.inv_mass_b + sc.inv_inertia_a * ra * ra +
                             sc.inv_inertia_b * rb * rb);
      }
      Vec2 relative = b.velocity - a.velocity;
      if (sc.angular) relative += Cross(b.angular_velocity, anchor_b) - Cross(a.angular_velocity, anchor_a);
      const double vn = Dot(relative, sc.normal);
      // Slow impacts, and bounces that would come out slower than the threshold, are left to
      // the contact solver as inelastic: a resting body must not buzz.
      if (vn >= -def.restitution_threshold || sc.restitution * -vn < def.restitution_threshold) {
        continue;
      }
      const double relative_acceleration = Dot(accelerations[sc.b] - accelerations[sc.a], sc.normal);
      Bounce bounce;
      if (!ComputeBounce(separation, vn, relative_acceleration, sc.restitution,
                         def.substeps, h, def.linear_slop, &bounce)) {
        continue;
      }
      const double impulse = (bounce.start_velocity - vn) * normal_mass;
      a.velocity -= (impulse * sc.inv_mass_a) * sc.normal;
      b.velocity += (impulse * sc.inv_mass_b) * sc.normal;
      if (sc.angular) {
        a.angular_velocity -= sc.inv_inertia_a * Cross(anchor_a, impulse * sc.normal);
        b.angular_velocity += sc.inv_inertia_b * Cross(anchor_b, impulse * sc.normal);
      }
      sc.impact_lag = bounce.lag;
      any = true;
    }
    if (!any) break;
  }
}

}  // namespace engine::detail
