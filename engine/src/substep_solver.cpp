// Substepped contact constraints: rigid and warm-started for velocities, with overlap pushed out
// through separate push velocities (a split impulse). Pairs that cannot turn take a linear-only
// path: no angular arithmetic at all, one constraint per contact.
#include "substep_solver.h"

#include "block_solver.h"

#include <algorithm>
#include <cmath>

namespace engine::detail {

namespace {

// Velocity of B's anchor relative to A's.
Vec2 RelativeVelocity(const SubstepPoint& p, const BodyState& a, const BodyState& b) {
  return (b.velocity + Cross(b.angular_velocity, p.anchor_b)) -
         (a.velocity + Cross(a.angular_velocity, p.anchor_a));
}

void ApplyImpulse(const SubstepConstraint& sc, const SubstepPoint& p, Vec2 impulse, BodyState& a,
                  BodyState& b) {
  a.velocity -= sc.inv_mass_a * impulse;
  a.angular_velocity -= sc.inv_inertia_a * Cross(p.anchor_a, impulse);
  b.velocity += sc.inv_mass_b * impulse;
  b.angular_velocity += sc.inv_inertia_b * Cross(p.anchor_b, impulse);
}

// 1 / (m_a⁻¹ + m_b⁻¹ + I_a⁻¹·(r_a × d)² + I_b⁻¹·(r_b × d)²): the effective mass along d.
double EffectiveMass(const SubstepConstraint& sc, Vec2 anchor_a, Vec2 anchor_b, Vec2 d) {
  const double ra = Cross(anchor_a, d), rb = Cross(anchor_b, d);
  return 1.0 / (sc.inv_mass_a + sc.inv_mass_b + sc.inv_inertia_a * ra * ra + sc.inv_inertia_b * rb * rb);
}

}  // namespace

TwoPointMass NormalMass(const SubstepConstraint& sc, const SubstepPoint& p1, const SubstepPoint& p2,
                        double inv_mass_a, double inv_mass_b, double inv_inertia_a,
                        double inv_inertia_b) {
  const double r1a = Cross(p1.anchor_a, sc.normal), r1b = Cross(p1.anchor_b, sc.normal);
  const double r2a = Cross(p2.anchor_a, sc.normal), r2b = Cross(p2.anchor_b, sc.normal);
  const double m = inv_mass_a + inv_mass_b;
  return {m + inv_inertia_a * r1a * r1a + inv_inertia_b * r1b * r1b,
          m + inv_inertia_a * r1a * r2a + inv_inertia_b * r1b * r2b,
          m + inv_inertia_a * r2a * r2a + inv_inertia_b * r2b * r2b};
}

void PrepareSubstepConstraints(std::span<const Contact> contacts, std::span<const BodyInfo> infos,
                               std::span<const BodyState> states,
                               std::vector<SubstepConstraint>* constraints) {
  // Filled in place, every field a constraint reads set (a point past point_count is never read):
  // copying each one in would cost a call to memcpy apiece.
  constraints->resize(contacts.size());
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    SubstepConstraint& sc = (*constraints)[i];
    sc.a = c.a;
    sc.b = c.b;
    sc.contact = i;
    sc.normal = c.manifold.normal;
    sc.inv_mass_a = infos[c.a].inv_mass;
    sc.inv_mass_b = infos[c.b].inv_mass;
    sc.inv_inertia_a = infos[c.a].inv_inertia;
    sc.inv_inertia_b = infos[c.b].inv_inertia;
    sc.friction = c.friction;
    sc.restitution = c.restitution;
    sc.impact_lag = 0.0;
    sc.angular = sc.inv_inertia_a != 0.0 || sc.inv_inertia_b != 0.0;
    if (!sc.angular) {
      SubstepPoint& p = sc.points[0];
      p.anchor_a = p.anchor_b = Vec2{};
      p.normal_mass = p.tangent_mass = 1.0 / (sc.inv_mass_a + sc.inv_mass_b);
      double depth = c.manifold.points[0].depth;
      for (int k = 1; k < c.manifold.point_count; ++k) depth = std::max(depth, c.manifold.points[k].depth);
      p.base_separation = -depth;
      p.normal_impulse = c.normal_impulse[0] + c.normal_impulse[1];
      p.tangent_impulse = c.tangent_impulse[0] + c.tangent_impulse[1];
      p.push_impulse = 0.0;
      sc.point_count = 1;
    } else {
      const Vec2 t = LeftPerp(sc.normal);
      sc.point_count = c.manifold.point_count;
      for (int k = 0; k < sc.point_count; ++k) {
        SubstepPoint& p = sc.points[k];
        const ContactPoint& cp = c.manifold.points[k];
        p.anchor_a = cp.point - states[c.a].position;
        p.anchor_b = cp.point - states[c.b].position;
        p.base_separation = -cp.depth - Dot(p.anchor_b - p.anchor_a, sc.normal);
        p.normal_mass = EffectiveMass(sc, p.anchor_a, p.anchor_b, sc.normal);
        p.tangent_mass = EffectiveMass(sc, p.anchor_a, p.anchor_b, t);
        p.normal_impulse = c.normal_impulse[k];
        p.tangent_impulse = c.tangent_impulse[k];
        p.push_impulse = 0.0;
      }
    }
  }
}

void WarmStart(std::span<const SubstepConstraint> constraints, std::span<BodyState> states) {
  for (const SubstepConstraint& sc : constraints) {
    const Vec2 t = LeftPerp(sc.normal);
    if (!sc.angular) {
      const SubstepPoint& p = sc.points[0];
      const Vec2 impulse = p.normal_impulse * sc.normal + p.tangent_impulse * t;
      states[sc.a].velocity -= sc.inv_mass_a * impulse;
      states[sc.b].velocity += sc.inv_mass_b * impulse;
      continue;
    }
    for (int k = 0; k < sc.point_count; ++k) {
      const SubstepPoint& p = sc.points[k];
      ApplyImpulse(sc, p, p.normal_impulse * sc.normal + p.tangent_impulse * t, states[sc.a], states[sc.b]);
    }
  }
}

void SolveContacts(std::span<SubstepConstraint> constraints, std::span<BodyState> states,
                   const StepStart& start, double inv_h) {
  for (SubstepConstraint& sc : constraints) {
    BodyState& a = states[sc.a];
    BodyState& b = states[sc.b];
    const Vec2 n = sc.normal;
    const Vec2 t = LeftPerp(n);
    if (!sc.angular) {
      SubstepPoint& p = sc.points[0];
      // Rigid: no approach at all when touching; across a gap, no more than closes it this substep.
      const double s = CurrentSeparation(sc, p, states, start);
      const double min_vn = -std::max(s, 0.0) * inv_h;
      const double vn = Dot(b.velocity - a.velocity, n);
      const double new_normal = std::max(p.normal_impulse + p.normal_mass * (min_vn - vn), 0.0);
      const double dn = new_normal - p.normal_impulse;
      p.normal_impulse = new_normal;
      a.velocity -= (sc.inv_mass_a * dn) * n;
      b.velocity += (sc.inv_mass_b * dn) * n;

      // Coulomb friction: the tangent impulse stays inside the cone of the normal impulse.
      const double vt = Dot(b.velocity - a.velocity, t);
      const double max_friction = sc.friction * p.normal_impulse;
      const double new_tangent = Clamp(p.tangent_impulse - p.tangent_mass * vt, -max_friction, max_friction);
      const double dt_impulse = new_tangent - p.tangent_impulse;
      p.tangent_impulse = new_tangent;
      a.velocity -= (sc.inv_mass_a * dt_impulse) * t;
      b.velocity += (sc.inv_mass_b * dt_impulse) * t;
      continue;
    }
    double min_vn[2], vn[2];
    for (int k = 0; k < sc.point_count; ++k) {
      min_vn[k] = -std::max(CurrentSeparation(sc, sc.points[k], states, start), 0.0) * inv_h;
      vn[k] = Dot(RelativeVelocity(sc.points[k], a, b), n);
    }
    double x[2];
    if (sc.point_count == 2 &&
        SolveTwoPoints(NormalMass(sc, sc.points[0], sc.points[1], sc.inv_mass_a, sc.inv_mass_b,
                                  sc.inv_inertia_a, sc.inv_inertia_b),
                       sc.points[0].normal_impulse, sc.points[1].normal_impulse, vn[0], vn[1],
                       min_vn[0], min_vn[1], &x[0], &x[1])) {
      for (int k = 0; k < 2; ++k) {
        SubstepPoint& p = sc.points[k];
        ApplyImpulse(sc, p, (x[k] - p.normal_impulse) * n, a, b);
        p.normal_impulse = x[k];
      }
    } else {
      for (int k = 0; k < sc.point_count; ++k) {
        SubstepPoint& p = sc.points[k];
        const double v = Dot(RelativeVelocity(p, a, b), n);
        const double new_normal = std::max(p.normal_impulse + p.normal_mass * (min_vn[k] - v), 0.0);
        const double dn = new_normal - p.normal_impulse;
        p.normal_impulse = new_normal;
        ApplyImpulse(sc, p, dn * n, a, b);
      }
    }
    for (int k = 0; k < sc.point_count; ++k) {
      SubstepPoint& p = sc.points[k];
      const double vt = Dot(RelativeVelocity(p, a, b), t);
      const double max_friction = sc.friction * p.normal_impulse;
      const double new_tangent = Clamp(p.tangent_impulse - p.tangent_mass * vt, -max_friction, max_friction);
      const double dt_impulse = new_tangent - p.tangent_impulse;
      p.tangent_impulse = new_tangent;
      ApplyImpulse(sc, p, dt_impulse * t, a, b);
    }
  }
}

void PushOut(std::span<SubstepConstraint> constraints, std::span<const BodyState> states,
             const StepStart& start, PushVelocities push, double push_out_rate,
             double max_push_out_speed, double linear_slop) {
  // Gauss-Seidel on the push velocities alone, from zero every substep.
  for (Vec2& v : push.linear) v = {};
  for (double& w : push.angular) w = 0.0;
  for (SubstepConstraint& sc : constraints) {
    const Vec2 n = sc.normal;
    for (int k = 0; k < sc.point_count; ++k) {
      SubstepPoint& p = sc.points[k];
      p.push_impulse = 0.0;
      const double s = CurrentSeparation(sc, p, states, start);
      if (s >= -linear_slop) continue;  // overlap within the slop is left alone: rest stays quiet
      const double target = std::min(push_out_rate * -(s + linear_slop), max_push_out_speed);
      Vec2& va = push.linear[sc.a];
      Vec2& vb = push.linear[sc.b];
      double vn = Dot(vb - va, n);
      if (sc.angular) {
        vn += Dot(Cross(push.angular[sc.b], p.anchor_b) - Cross(push.angular[sc.a], p.anchor_a), n);
      }
      const double new_push = std::max(p.push_impulse + p.normal_mass * (target - vn), 0.0);
      const double dp = new_push - p.push_impulse;
      p.push_impulse = new_push;
      va -= (sc.inv_mass_a * dp) * n;
      vb += (sc.inv_mass_b * dp) * n;
      if (sc.angular) {
        push.angular[sc.a] -= sc.inv_inertia_a * Cross(p.anchor_a, dp * n);
        push.angular[sc.b] += sc.inv_inertia_b * Cross(p.anchor_b, dp * n);
      }
    }
  }
}

void MoveByPush(std::span<BodyState> states, PushVelocities push, bool rotation, double h) {
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].position += push.linear[i] * h;
    if (rotation) states[i].angle += push.angular[i] * h;
  }
}

void ApplyImpactLags(std::span<const SubstepConstraint> constraints, std::span<BodyState> states) {
  for (const SubstepConstraint& sc : constraints) {
    if (sc.impact_lag == 0.0) continue;
    const double share = sc.impact_lag * (1.0 / (sc.inv_mass_a + sc.inv_mass_b));
    states[sc.a].position -= (share * sc.inv_mass_a) * sc.normal;
    states[sc.b].position += (share * sc.inv_mass_b) * sc.normal;
  }
}

void StoreImpulses(std::span<const SubstepConstraint> constraints, std::span<Contact> contacts) {
  for (const SubstepConstraint& sc : constraints) {
    Contact& c = contacts[sc.contact];
    for (int k = 0; k < 2; ++k) {
      c.normal_impulse[k] = k < sc.point_count ? sc.points[k].normal_impulse : 0.0;
      c.tangent_impulse[k] = k < sc.point_count ? sc.points[k].tangent_impulse : 0.0;
    }
  }
}

}  // namespace engine::detail
