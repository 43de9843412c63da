// Substepped contact constraints: rigid and warm-started for velocities, with overlap pushed out
// through separate push velocities (a split impulse). Rotation-free for now: impulses act at the
// centres.
#include "substep_solver.h"

#include <algorithm>
#include <cmath>

namespace engine::detail {

void PrepareSubstepConstraints(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                            std::vector<SubstepConstraint>* constraints) {
  constraints->clear();
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    SubstepConstraint sc;
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
    constraints->push_back(sc);
  }
}

void WarmStart(std::span<const SubstepConstraint> constraints, std::span<BodyState> states) {
  for (const SubstepConstraint& sc : constraints) {
    const Vec2 impulse = sc.normal_impulse * sc.normal + sc.tangent_impulse * LeftPerp(sc.normal);
    states[sc.a].velocity -= sc.inv_mass_a * impulse;
    states[sc.b].velocity += sc.inv_mass_b * impulse;
  }
}

void SolveContacts(std::span<SubstepConstraint> constraints, std::span<BodyState> states,
                   std::span<const Vec2> step_start_positions, double inv_h) {
  for (SubstepConstraint& sc : constraints) {
    BodyState& a = states[sc.a];
    BodyState& b = states[sc.b];
    const Vec2 n = sc.normal;

    // The separation now: at the step's start, plus how far the bodies have moved apart since.
    const Vec2 moved = (b.position - step_start_positions[sc.b]) - (a.position - step_start_positions[sc.a]);
    const double s = sc.base_separation + Dot(moved, n);
    // Rigid: no approach at all when touching; across a gap, no more than closes it this substep.
    const double min_vn = -std::max(s, 0.0) * inv_h;
    const double vn = Dot(b.velocity - a.velocity, n);
    const double new_normal = std::max(sc.normal_impulse + sc.normal_mass * (min_vn - vn), 0.0);
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

void PushOut(std::span<SubstepConstraint> constraints, std::span<const BodyState> states,
             std::span<const Vec2> step_start_positions, std::span<Vec2> push_velocities,
             double push_out_rate, double max_push_out_speed, double linear_slop) {
  // Gauss-Seidel on the push velocities alone, from zero every substep.
  for (SubstepConstraint& sc : constraints) {
    sc.push_impulse = 0.0;
  }
  for (Vec2& v : push_velocities) v = {};
  for (SubstepConstraint& sc : constraints) {
    const Vec2 n = sc.normal;
    const Vec2 moved = (states[sc.b].position - step_start_positions[sc.b]) -
                       (states[sc.a].position - step_start_positions[sc.a]);
    const double s = sc.base_separation + Dot(moved, n);
    if (s >= -linear_slop) continue;  // overlap within the slop is left alone: rest stays quiet
    const double target = std::min(push_out_rate * -(s + linear_slop), max_push_out_speed);
    Vec2& va = push_velocities[sc.a];
    Vec2& vb = push_velocities[sc.b];
    const double vn = Dot(vb - va, n);
    const double new_push = std::max(sc.push_impulse + sc.normal_mass * (target - vn), 0.0);
    const double dp = new_push - sc.push_impulse;
    sc.push_impulse = new_push;
    va -= (sc.inv_mass_a * dp) * n;
    vb += (sc.inv_mass_b * dp) * n;
  }
}

void MoveByPush(std::span<BodyState> states, std::span<const Vec2> push_velocities, double h) {
  for (std::size_t i = 0; i < states.size(); ++i) states[i].position += push_velocities[i] * h;
}

void ApplyImpactLags(std::span<const SubstepConstraint> constraints, std::span<BodyState> states) {
  for (const SubstepConstraint& sc : constraints) {
    if (sc.impact_lag == 0.0) continue;
    const double share = sc.impact_lag * sc.normal_mass;
    states[sc.a].position -= (share * sc.inv_mass_a) * sc.normal;
    states[sc.b].position += (share * sc.inv_mass_b) * sc.normal;
  }
}

void StoreImpulses(std::span<const SubstepConstraint> constraints, std::span<Contact> contacts) {
  for (const SubstepConstraint& sc : constraints) {
    Contact& c = contacts[sc.contact];
    c.normal_impulse[0] = sc.normal_impulse;
    c.normal_impulse[1] = 0.0;
    c.tangent_impulse[0] = sc.tangent_impulse;
    c.tangent_impulse[1] = 0.0;
  }
}

}  // namespace engine::detail
