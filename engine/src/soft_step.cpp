// Soft contact constraints with warm starting, solved once per substep plus a relax pass.
// Rotation-free for now: impulses act at the centres.
#include "soft_step.h"

#include <algorithm>
#include <cmath>

namespace engine::detail {

Softness MakeSoftness(double hertz, double damping_ratio, double h) {
  if (hertz == 0.0) return {};
  constexpr double kTwoPi = 6.28318530717958647692;
  const double omega = kTwoPi * hertz;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

void PrepareSoftConstraints(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                            const WorldDef& def, std::vector<SoftConstraint>* constraints) {
  const double h = def.dt / def.substeps;
  // A spring stiffer than a quarter of the substep rate would ring; contacts with static bodies
  // can be twice as stiff, as only one body moves (Box2D v3 does the same).
  const double hertz = std::min(def.contact_hertz, 0.25 / h);
  const Softness soft = MakeSoftness(hertz, def.contact_damping_ratio, h);
  const Softness static_soft = MakeSoftness(2.0 * hertz, def.contact_damping_ratio, h);
  constraints->clear();
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    SoftConstraint sc;
    sc.a = c.a;
    sc.b = c.b;
    sc.contact = i;
    sc.normal = c.manifold.normal;
    sc.inv_mass_a = infos[c.a].inv_mass;
    sc.inv_mass_b = infos[c.b].inv_mass;
    sc.normal_mass = 1.0 / (sc.inv_mass_a + sc.inv_mass_b);
    sc.friction = c.friction;
    sc.restitution = c.restitution;
    double depth = c.manifold.points[0].depth;
    for (int p = 1; p < c.manifold.point_count; ++p) depth = std::max(depth, c.manifold.points[p].depth);
    sc.base_separation = -depth;
    sc.normal_impulse = c.normal_impulse[0] + c.normal_impulse[1];
    sc.tangent_impulse = c.tangent_impulse[0] + c.tangent_impulse[1];
    sc.impact_lag = 0.0;
    sc.softness = infos[c.a].is_static || infos[c.b].is_static ? static_soft : soft;
    constraints->push_back(sc);
  }
}

void WarmStart(std::span<const SoftConstraint> constraints, std::span<BodyState> states) {
  for (const SoftConstraint& sc : constraints) {
    const Vec2 impulse = sc.normal_impulse * sc.normal + sc.tangent_impulse * LeftPerp(sc.normal);
    states[sc.a].velocity -= sc.inv_mass_a * impulse;
    states[sc.b].velocity += sc.inv_mass_b * impulse;
  }
}

void SolveSoftConstraints(std::span<SoftConstraint> constraints, std::span<BodyState> states,
                          std::span<const Vec2> step_start_positions, double inv_h,
                          double max_push_out_speed, double linear_slop, bool use_bias) {
  for (SoftConstraint& sc : constraints) {
    BodyState& a = states[sc.a];
    BodyState& b = states[sc.b];
    const Vec2 n = sc.normal;

    // The separation now: at the step's start, plus how far the bodies have moved apart since.
    const Vec2 moved = (b.position - step_start_positions[sc.b]) - (a.position - step_start_positions[sc.a]);
    const double s = sc.base_separation + Dot(moved, n);
    double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
    if (s > 0.0) {
      // Speculative: may approach by exactly the gap this substep. The relax pass leaves gaps
      // alone: capping the speed for a substep not yet taken would slow a falling body before
      // it arrives, and the next step's impact pass would then see the wrong impact speed.
      if (!use_bias) continue;
      bias = s * inv_h;
    } else if (use_bias) {
      // Overlap within the slop is left alone, so resting contacts stay quiet.
      bias = std::max(sc.softness.bias_rate * std::min(s + linear_slop, 0.0), -max_push_out_speed);
      mass_scale = sc.softness.mass_scale;
      impulse_scale = sc.softness.impulse_scale;
    }
    const double vn = Dot(b.velocity - a.velocity, n);
    const double impulse = -sc.normal_mass * mass_scale * (vn + bias) - impulse_scale * sc.normal_impulse;
    const double new_normal = std::max(sc.normal_impulse + impulse, 0.0);
    const double dn = new_normal - sc.normal_impulse;
    sc.normal_impulse = new_normal;
    a.velocity -= (sc.inv_mass_a * dn) * n;
    b.velocity += (sc.inv_mass_b * dn) * n;

    // Coulomb friction: the tangent impulse stays inside the cone of the normal impulse.
    const Vec2 t = LeftPerp(n);
    const double vt = Dot(b.velocity - a.velocity, t);
    const double max_friction = sc.friction * sc.normal_impulse;
    const double new_tangent = Clamp(sc.tangent_impulse - sc.normal_mass * vt, -max_friction, max_friction);
    const double dt_impulse = new_tangent - sc.tangent_impulse;
    sc.tangent_impulse = new_tangent;
    a.velocity -= (sc.inv_mass_a * dt_impulse) * t;
    b.velocity += (sc.inv_mass_b * dt_impulse) * t;
  }
}

void ApplyImpactLags(std::span<const SoftConstraint> constraints, std::span<BodyState> states) {
  for (const SoftConstraint& sc : constraints) {
    if (sc.impact_lag == 0.0) continue;
    const double share = sc.impact_lag * sc.normal_mass;
    states[sc.a].position -= (share * sc.inv_mass_a) * sc.normal;
    states[sc.b].position += (share * sc.inv_mass_b) * sc.normal;
  }
}

void StoreImpulses(std::span<const SoftConstraint> constraints, std::span<Contact> contacts) {
  for (const SoftConstraint& sc : constraints) {
    Contact& c = contacts[sc.contact];
    c.normal_impulse[0] = sc.normal_impulse;
    c.normal_impulse[1] = 0.0;
    c.tangent_impulse[0] = sc.tangent_impulse;
    c.tangent_impulse[1] = 0.0;
  }
}

}  // namespace engine::detail
