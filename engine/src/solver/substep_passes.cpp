// Substepped contact constraints: rigid and warm-started for velocities, with overlap pushed out
// through separate push velocities (a split impulse). Pairs that cannot turn take a linear-only
// path: no angular arithmetic at all, one constraint per contact.
#include "solver/substep_passes.h"

#include "solver/block_solver.h"
#include "solver/direct_solver.h"

#include <algorithm>
#include <cmath>

#include "store_whole.h"

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

void ApplyImpulse(const LinearConstraint& lc, const LinearConstraint&, Vec2 impulse, BodyState& a,
                  BodyState& b) {
  a.velocity -= lc.inv_mass_a * impulse;
  b.velocity += lc.inv_mass_b * impulse;
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

namespace {

// What either kind of constraint takes from its contact and bodies alike.
template <typename C>
void FillPair(const Contact& c, std::span<const BodyInfo> infos, C* constraint) {
  constraint->a = c.a;
  constraint->b = c.b;
  constraint->normal = c.manifold.normal;
  constraint->inv_mass_a = infos[c.a].inv_mass;
  constraint->inv_mass_b = infos[c.b].inv_mass;
  constraint->friction = c.friction;
}

// The one row of a pair that cannot turn, at the centres: the deepest point's separation and the
// sum of the points' impulses (every point has the same Jacobian, so they act as one).
template <typename Row>
void FillCentreRow(const Contact& c, double inv_mass_a, double inv_mass_b, Row* row) {
  row->normal_mass = 1.0 / (inv_mass_a + inv_mass_b);
  double depth = c.manifold.points[0].depth;
  for (int k = 1; k < c.manifold.point_count; ++k) depth = std::max(depth, c.manifold.points[k].depth);
  row->base_separation = -depth;
  row->normal_impulse = c.normal_impulse[0] + c.normal_impulse[1];
  row->tangent_impulse = c.tangent_impulse[0] + c.tangent_impulse[1];
}

}  // namespace

template <>
void PrepareSubstepConstraints(std::span<const Contact> contacts, std::span<const std::uint32_t> slot,
                               std::span<const BodyInfo> infos, std::span<const BodyState> states,
                               std::vector<LinearConstraint>* constraints, WorkerPool* pool, ImpactLook* look,
                               ConstraintKinds* /*kinds*/) {
  constraints->resize(contacts.size());
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
    PrepareLinearConstraints(contacts, slot, infos, *constraints, i, i + 1);
    if (look) look->Look((*constraints)[slot[i]], contacts[i], states);
  });
}

void PrepareLinearConstraints(std::span<const Contact> contacts, std::span<const std::uint32_t> slot,
                              std::span<const BodyInfo> infos, std::span<LinearConstraint> constraints,
                              std::uint32_t begin, std::uint32_t end, std::span<double> restitutions) {
  for (std::uint32_t i = begin; i < end; ++i) {
    const Contact& c = contacts[i];
    LinearConstraint& lc = constraints[slot[i]];
    FillPair(c, infos, &lc);
    FillCentreRow(c, lc.inv_mass_a, lc.inv_mass_b, &lc);
    if (!restitutions.empty()) restitutions[i] = c.restitution;
  }
}

template <>
void PrepareSubstepConstraints(std::span<const Contact> contacts, std::span<const std::uint32_t> slot,
                               std::span<const BodyInfo> infos, std::span<const BodyState> states,
                               std::vector<SubstepConstraint>* constraints, WorkerPool* pool, ImpactLook* look,
                               ConstraintKinds* kinds) {
  // Filled in place, every field a constraint reads set (a point past point_count is never read):
  // copying each one in would cost a call to memcpy apiece.
  constraints->resize(contacts.size());
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
    const Contact& c = contacts[i];
    SubstepConstraint& sc = (*constraints)[slot[i]];
    FillPair(c, infos, &sc);
    sc.inv_inertia_a = infos[c.a].inv_inertia;
    sc.inv_inertia_b = infos[c.b].inv_inertia;
    sc.angular = sc.inv_inertia_a != 0.0 || sc.inv_inertia_b != 0.0;
    if (!sc.angular) {
      // As LinearConstraint: one row at the centres.
      SubstepPoint& p = sc.points[0];
      p.anchor_a = p.anchor_b = Vec2{};
      FillCentreRow(c, sc.inv_mass_a, sc.inv_mass_b, &p);
      p.tangent_mass = p.normal_mass;
      p.push_impulse = 0.0;
      sc.point_count = 1;
    } else {
      const Vec2 t = LeftPerp(sc.normal);
      sc.point_count = c.manifold.point_count;
      for (int k = 0; k < sc.point_count; ++k) {
        SubstepPoint& p = sc.points[k];
        const ContactPoint& cp = c.manifold.points[k];
        const Vec2 anchor_a = cp.point - states[c.a].position;
        const Vec2 anchor_b = cp.point - states[c.b].position;
        StoreWhole(&p.anchor_a, anchor_a);
        StoreWhole(&p.anchor_b, anchor_b);
        p.base_separation = -cp.depth - Dot(anchor_b - anchor_a, sc.normal);
        p.normal_mass = EffectiveMass(sc, anchor_a, anchor_b, sc.normal);
        p.tangent_mass = EffectiveMass(sc, anchor_a, anchor_b, t);
        p.normal_impulse = c.normal_impulse[k];
        p.tangent_impulse = c.tangent_impulse[k];
        p.push_impulse = 0.0;
      }
    }
    if (look) look->Look(sc, c, states);
    if (kinds && !sc.angular) kinds->not_turning.store(true, std::memory_order_relaxed);
    if (kinds && IsHeavyPair(sc, infos)) kinds->heavy.store(true, std::memory_order_relaxed);
  });
}

namespace {

// The least relative normal velocity the contact solve allows point `p` of `sc` now: rigid, no
// approach at all when touching; across a gap, no more than closes it this substep.
template <typename C, typename P>
[[gnu::always_inline]] inline double TargetVelocity(const C& sc, const P& p,
                                                    std::span<const BodyState> states,
                                                    const StepStart& start, double inv_h) {
  return -std::max(CurrentSeparation(sc, p, states, start), 0.0) * inv_h;
}

// For WarmStart: drops point `p`'s tangent impulse if that was sliding friction and the pair now
// slides along it (judged as the impulses go on, as the pass would see it), and returns the
// impulse to apply again. Inlined: it runs for every contact in every substep.
template <typename C, typename P>
[[gnu::always_inline]] inline Vec2 WarmImpulse(const C& sc, P& p, Vec2 t, const BodyState& a,
                                               const BodyState& b) {
  // A stored tangent impulse at least this close to the cone's edge was sliding friction (the
  // clamp puts it exactly there; the margin covers the force-free scale's rounding).
  constexpr double kSliding = 1.0 - 1e-9;
  Vec2 relative = b.velocity - a.velocity;
  if constexpr (kCanTurn<C>) {
    if (sc.angular) relative = RelativeVelocity(p, a, b);
  }
  if (p.tangent_impulse * Dot(relative, t) > 0.0 &&
      std::abs(p.tangent_impulse) >= kSliding * sc.friction * p.normal_impulse) {
    p.tangent_impulse = 0.0;
  }
  return p.normal_impulse * sc.normal + p.tangent_impulse * t;
}

// Adds point `p`'s impulse to its bodies' sums of impulse (and angular impulse, where they turn).
template <typename C, typename P>
[[gnu::always_inline]] inline void AddToBodySums(const C& sc, const P& p, Vec2 impulse,
                                                  WarmStartImpulses sums) {
  sums.linear[sc.a] -= impulse;
  sums.linear[sc.b] += impulse;
  if constexpr (kCanTurn<C>) {
    if (sc.angular) {
      sums.angular[sc.a] -= Cross(p.anchor_a, impulse);
      sums.angular[sc.b] += Cross(p.anchor_b, impulse);
    }
  }
}

// Writes back the velocities of a constraint's bodies, worked on in copies, but only where a
// body moves: a static or kinematic body is never written (its velocity is the same after any
// impulse times its zero inverse mass), so threads solving contacts side by side may share it.
template <typename C>
[[gnu::always_inline]] inline void WriteBack(const C& sc, const BodyState& a, const BodyState& b,
                                             std::span<BodyState> states) {
  if (sc.inv_mass_a != 0.0) {
    states[sc.a].velocity = a.velocity;
    if constexpr (kCanTurn<C>) states[sc.a].angular_velocity = a.angular_velocity;
  }
  if (sc.inv_mass_b != 0.0) {
    states[sc.b].velocity = b.velocity;
    if constexpr (kCanTurn<C>) states[sc.b].angular_velocity = b.angular_velocity;
  }
}

}  // namespace

template <typename C>
void WarmStartAll(std::span<C> constraints, std::span<BodyState> states) {
  for (C& sc : constraints) {
    BodyState a = states[sc.a];
    BodyState b = states[sc.b];
    const Vec2 t = LeftPerp(sc.normal);
    if (!Turns(sc)) {
      const Vec2 impulse = WarmImpulse(sc, Point(sc, 0), t, a, b);
      a.velocity -= sc.inv_mass_a * impulse;
      b.velocity += sc.inv_mass_b * impulse;
      WriteBack(sc, a, b, states);
      continue;
    }
    if constexpr (kCanTurn<C>) {
      for (int k = 0; k < sc.point_count; ++k) {
        SubstepPoint& p = sc.points[k];
        ApplyImpulse(sc, p, WarmImpulse(sc, p, t, a, b), a, b);
      }
      WriteBack(sc, a, b, states);
    }
  }
}

namespace {

// The first half of WarmStart's scaling: applies the loaded contacts' impulses and adds the
// force-free ones to their bodies' sums (`sums`) instead. Returns the targets' side of the
// force-free a = λwᵀ(u₀ − t), and sets `any_free`.
template <typename C>
double ApplyLoadedSumForceFree(std::span<C> constraints, std::span<BodyState> states,
                               std::span<const std::uint8_t> loaded, const StepStart& start, double inv_h,
                               WarmStartImpulses sums, bool* any_free) {
  for (Vec2& p : sums.linear) p = {};
  for (double& l : sums.angular) l = 0.0;
  double a = 0.0;
  bool any = false;
  for (C& sc : constraints) {
    BodyState& body_a = states[sc.a];
    BodyState& body_b = states[sc.b];
    const Vec2 t = LeftPerp(sc.normal);
    const bool free = !loaded[sc.a] && !loaded[sc.b];
    any = any || free;
    for (int k = 0; k < PointCount(sc); ++k) {
      auto& p = Point(sc, k);
      const Vec2 impulse = WarmImpulse(sc, p, t, body_a, body_b);
      if (!free) {
        ApplyImpulse(sc, p, impulse, body_a, body_b);
        continue;
      }
      a -= p.normal_impulse * TargetVelocity(sc, p, states, start, inv_h);
      AddToBodySums(sc, p, impulse, sums);
    }
  }
  *any_free = any;
  return a;
}

// The second half: with the loaded part applied, λwᵀ(u₀ − t) = Σ P·v (+ L·ω) + the targets' side
// (`a` brings it), and λwᵀAλw = Σ |P|²/m (+ L²/I), P and L each body's sums of the force-free
// impulses. Applies them scaled by α = clamp(−a / b, 0, 1), scales the stored ones to match, and
// returns α.
template <typename C>
double ApplyForceFreeScaled(std::span<C> constraints, std::span<BodyState> states,
                            std::span<const BodyInfo> infos, std::span<const std::uint8_t> loaded,
                            WarmStartImpulses sums, double a) {
  const bool rotation = !sums.angular.empty();
  double b = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Vec2 p = sums.linear[i];
    a += Dot(p, states[i].velocity);
    b += infos[i].inv_mass * Dot(p, p);
    if (rotation) {
      const double l = sums.angular[i];
      a += l * states[i].angular_velocity;
      b += infos[i].inv_inertia * l * l;
    }
  }
  if (!(b > 0.0)) return 1.0;  // no force-free impulse moves anything
  const double alpha = std::clamp(-a / b, 0.0, 1.0);
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].velocity += (alpha * infos[i].inv_mass) * sums.linear[i];
    if (rotation) states[i].angular_velocity += (alpha * infos[i].inv_inertia) * sums.angular[i];
  }
  if (alpha != 1.0) {
    for (C& sc : constraints) {
      if (loaded[sc.a] || loaded[sc.b]) continue;
      for (int k = 0; k < PointCount(sc); ++k) {
        Point(sc, k).normal_impulse *= alpha;
        Point(sc, k).tangent_impulse *= alpha;
      }
    }
  }
  return alpha;
}

}  // namespace

// The warm start re-applies last substep's impulses λw, the guess that the contacts need the
// same again. That holds for contacts carrying a load (a stack holding up its weight gets the
// same impulse every substep), not for one-off ones: the impulse that stopped two bodies running
// into each other, applied again, drives them apart at the speed they met, and one Gauss-Seidel
// pass takes that back only for an isolated pair. In a large packed cluster the remainder grows
// from substep to substep. Measured on 625 circles packed in a box without gravity
// (docs/solver.md, "Warm start"), two things pump:
//
// 1. Sliding friction. A tangent impulse stored at the edge of Coulomb's cone was kinetic
//    friction: the normal impulse and the direction of sliding fixed it. Once the pair slides
//    the other way, applying it again pushes the sliding along, which friction never does.
//    Kinetic energy ran away (×42 in 7 steps at 4 substeps) only with friction, and not once
//    these impulses were dropped. Static friction (inside the cone) is kept: piles hold their
//    shape by it.
// 2. Normal impulses of collisions, re-applied. These alone never ran away, but they make the
//    kinetic energy rise from one step to the next (by up to 25 % at 4 substeps and 38 % at 8,
//    without friction).
//
// For (2) the bound comes from what one pass of SolveContacts is: projected Gauss-Seidel, that
// is coordinate descent on the merit function of the contact problem (Catto, "Iterative
// Dynamics with Temporal Coherence", GDC 2005, poses sequential impulses as this problem):
//   G(λ) = ½·λᵀAλ + λᵀ(u₀ − t),   A = J·M⁻¹·Jᵀ,
// λ the impulses applied this substep, u₀ the contact velocities before them, t the targets
// (0 touching, −gap/h across a gap). The kinetic energy the impulses add is
// ΔKE(λ) = ½·λᵀAλ + λᵀu₀ = G(λ) + λᵀt ≤ G(λ), as t ≤ 0 and only normal impulses (≥ 0) have
// targets. Each row of the pass moves its impulse to the minimum of G along that row within its
// bounds, so G never rises (a friction row whose cone just shrank with its normal impulse is the
// one exception: Coulomb's law needs that clamp; LimitContactEnergy answers for it). From the
// start point αλw, G(αλw) = α·a + ½α²·b, and α = clamp(−a / b, 0, 1) gives G(αλw) ≤ G(0) = 0:
// the contacts then only take energy out. For a resting stack λw exactly cancels the gravity
// kick, G's minimum along λw: α = 1.
//
// That bound is applied only where no applied force acts (`loaded`). A loaded pile needs its
// warm start whole: one pass per substep builds the support of a deep pile up only over many
// substeps, and a lasting shortfall becomes sinking (a 2000-circle pour sinks through its floor
// when every warm start loses 1 %, measured). Where nothing pushes the bodies together, no
// contact carries a load, and the scale costs no support.

template <typename C>
double WarmStart(std::span<C> constraints, std::span<BodyState> states,
                 std::span<const BodyInfo> infos, std::span<const std::uint8_t> loaded,
                 const StepStart& start, double inv_h, WarmStartImpulses scratch) {
  if (loaded.empty()) {
    WarmStartAll(constraints, states);
    return 1.0;
  }
  bool any_free = false;
  const double a = ApplyLoadedSumForceFree(constraints, states, loaded, start, inv_h, scratch, &any_free);
  if (!any_free) return 1.0;
  return ApplyForceFreeScaled(constraints, states, infos, loaded, scratch, a);
}

double KineticEnergy(std::span<const BodyState> states, std::span<const BodyInfo> infos) {
  double energy = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const BodyState& s = states[i];
    energy += 0.5 * infos[i].mass * Dot(s.velocity, s.velocity);
    if (infos[i].inv_inertia != 0.0) {
      energy += 0.5 * infos[i].inertia * s.angular_velocity * s.angular_velocity;
    }
  }
  return energy;
}

template <typename C>
double LimitContactEnergy(std::span<C> constraints, std::span<BodyState> states,
                          std::span<const BodyInfo> infos, double energy_before,
                          WarmStartImpulses scratch) {
  // Rises this small are the rounding of the sums themselves.
  constexpr double kRoundoff = 1e-12;
  const double excess = KineticEnergy(states, infos) - energy_before;
  if (!(excess > kRoundoff * energy_before)) return 0.0;
  // P, L: each body's sum of this substep's contact impulses. Taking back the fraction d of
  // them leaves KE(d) = KE − d·S + ½d²·Q, S = Σ P·v (+ L·ω), Q = Σ |P|²/m (+ L²/I). KE(1) is
  // the energy before the contacts acted, so the least d with KE(d) = energy_before is in (0, 1]:
  // 2·excess / Q when that is below 1. Unrelated contacts elsewhere make Q large and d small.
  const bool rotation = !scratch.angular.empty();
  for (Vec2& p : scratch.linear) p = {};
  for (double& l : scratch.angular) l = 0.0;
  for (const C& sc : constraints) {
    const Vec2 t = LeftPerp(sc.normal);
    for (int k = 0; k < PointCount(sc); ++k) {
      const auto& p = Point(sc, k);
      AddToBodySums(sc, p, p.normal_impulse * sc.normal + p.tangent_impulse * t, scratch);
    }
  }
  double slope = 0.0, curvature = 0.0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Vec2 p = scratch.linear[i];
    slope += Dot(p, states[i].velocity);
    curvature += infos[i].inv_mass * Dot(p, p);
    if (rotation) {
      slope += scratch.angular[i] * states[i].angular_velocity;
      curvature += infos[i].inv_inertia * scratch.angular[i] * scratch.angular[i];
    }
  }
  if (!(curvature > 0.0)) return 0.0;
  // The smaller root of ½Q·d² − S·d + excess = 0, written to keep its digits when excess is
  // tiny; without a real root (rounding), the minimum of KE(d).
  const double discriminant = slope * slope - 2.0 * curvature * excess;
  const double d = std::clamp(discriminant > 0.0 && slope > 0.0
                                  ? 2.0 * excess / (slope + std::sqrt(discriminant))
                                  : slope / curvature,
                              0.0, 1.0);
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].velocity -= (d * infos[i].inv_mass) * scratch.linear[i];
    if (rotation) states[i].angular_velocity -= (d * infos[i].inv_inertia) * scratch.angular[i];
  }
  for (C& sc : constraints) {
    for (int k = 0; k < PointCount(sc); ++k) {
      Point(sc, k).normal_impulse *= 1.0 - d;
      Point(sc, k).tangent_impulse *= 1.0 - d;
    }
  }
  return d;
}

namespace {

// SolveContacts for a pair that can turn: block-solved normals for two points, then friction.
void SolveTurning(SubstepConstraint& sc, BodyState& a, BodyState& b, const StepStart& start,
                  std::span<const BodyState> states, double inv_h, bool block_solve) {
  const Vec2 n = sc.normal;
  const Vec2 t = LeftPerp(n);
  double min_vn[2], vn[2];
  for (int k = 0; k < sc.point_count; ++k) {
    min_vn[k] = TargetVelocity(sc, sc.points[k], states, start, inv_h);
    vn[k] = Dot(RelativeVelocity(sc.points[k], a, b), n);
  }
  double x[2];
  if (block_solve && sc.point_count == 2 &&
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

}  // namespace

template <typename C>
void SolveContacts(std::span<C> constraints, std::span<BodyState> states, const StepStart& start,
                   double inv_h, bool block_solve) {
  for (C& sc : constraints) {
    BodyState a = states[sc.a];
    BodyState b = states[sc.b];
    const Vec2 n = sc.normal;
    const Vec2 t = LeftPerp(n);
    if (!Turns(sc)) {
      auto& p = Point(sc, 0);
      const double min_vn = TargetVelocity(sc, p, states, start, inv_h);
      const double vn = Dot(b.velocity - a.velocity, n);
      const double new_normal = std::max(p.normal_impulse + p.normal_mass * (min_vn - vn), 0.0);
      const double dn = new_normal - p.normal_impulse;
      p.normal_impulse = new_normal;
      a.velocity -= (sc.inv_mass_a * dn) * n;
      b.velocity += (sc.inv_mass_b * dn) * n;

      // Coulomb friction: the tangent impulse stays inside the cone of the normal impulse.
      const double vt = Dot(b.velocity - a.velocity, t);
      const double max_friction = sc.friction * p.normal_impulse;
      // Without turning the effective mass is the same in every direction.
      const double new_tangent = Clamp(p.tangent_impulse - p.normal_mass * vt, -max_friction, max_friction);
      const double dt_impulse = new_tangent - p.tangent_impulse;
      p.tangent_impulse = new_tangent;
      a.velocity -= (sc.inv_mass_a * dt_impulse) * t;
      b.velocity += (sc.inv_mass_b * dt_impulse) * t;
      WriteBack(sc, a, b, states);
      continue;
    }
    if constexpr (kCanTurn<C>) {
      SolveTurning(sc, a, b, start, states, inv_h, block_solve);
      WriteBack(sc, a, b, states);
    }
  }
}

template <typename C>
void PushOut(std::span<C> constraints, std::span<const BodyState> states, const StepStart& start,
             PushVelocities push, double push_out_rate, double max_push_out_speed,
             double linear_slop) {
  // Gauss-Seidel on the push velocities alone, from zero every substep (ClearPush): each
  // point's push impulse starts at 0 (kept where the direct solver takes Gauss-Seidel's pushes
  // back).
  for (C& sc : constraints) {
    const Vec2 n = sc.normal;
    for (int k = 0; k < PointCount(sc); ++k) {
      auto& p = Point(sc, k);
      if constexpr (kCanTurn<C>) p.push_impulse = 0.0;
      const double s = CurrentSeparation(sc, p, states, start);
      if (s >= -linear_slop) continue;  // overlap within the slop is left alone: rest stays quiet
      const double target = std::min(push_out_rate * -(s + linear_slop), max_push_out_speed);
      // Copies, written back only where a body moves (as WriteBack).
      Vec2 va = push.linear[sc.a];
      Vec2 vb = push.linear[sc.b];
      double vn = Dot(vb - va, n);
      if constexpr (kCanTurn<C>) {
        if (sc.angular) {
          vn += Dot(Cross(push.angular[sc.b], p.anchor_b) - Cross(push.angular[sc.a], p.anchor_a), n);
        }
      }
      const double dp = std::max(p.normal_mass * (target - vn), 0.0);  // from zero: all of it is new
      if constexpr (kCanTurn<C>) p.push_impulse = dp;
      va -= (sc.inv_mass_a * dp) * n;
      vb += (sc.inv_mass_b * dp) * n;
      if (sc.inv_mass_a != 0.0) push.linear[sc.a] = va;
      if (sc.inv_mass_b != 0.0) push.linear[sc.b] = vb;
      if constexpr (kCanTurn<C>) {
        if (sc.angular) {
          if (sc.inv_mass_a != 0.0) push.angular[sc.a] -= sc.inv_inertia_a * Cross(p.anchor_a, dp * n);
          if (sc.inv_mass_b != 0.0) push.angular[sc.b] += sc.inv_inertia_b * Cross(p.anchor_b, dp * n);
        }
      }
    }
  }
}

void ClearPush(PushVelocities push, WorkerPool* pool) {
  ForEachIndex(pool, std::max(push.linear.size(), push.angular.size()), kMinSharedBodies, [=](std::uint32_t i) {
    if (i < push.linear.size()) push.linear[i] = {};
    if (i < push.angular.size()) push.angular[i] = 0.0;
  });
}

void MoveByPush(std::span<BodyState> states, PushVelocities push, bool rotation, double h, WorkerPool* pool) {
  ForEachIndex(pool, states.size(), kMinSharedBodies,
               [=](std::uint32_t i) { MoveBodyByPush(states, push, rotation, h, i); });
}

template <typename C>
void ApplyImpactLags(std::span<const C> constraints, std::span<const std::uint32_t> slot,
                     std::span<const double> lags, std::span<BodyState> states) {
  for (std::size_t i = 0; i < lags.size(); ++i) {
    if (lags[i] == 0.0) continue;
    const C& sc = constraints[slot[i]];
    const double share = lags[i] * (1.0 / (sc.inv_mass_a + sc.inv_mass_b));
    states[sc.a].position -= (share * sc.inv_mass_a) * sc.normal;
    states[sc.b].position += (share * sc.inv_mass_b) * sc.normal;
  }
}

template <typename C>
void StoreImpulses(std::span<const C> constraints, std::span<const std::uint32_t> slot,
                   std::span<Contact> contacts, WorkerPool* pool) {
  ForEachIndex(pool, contacts.size(), kMinSharedContacts, [&](std::uint32_t i) {
    const C& sc = constraints[slot[i]];
    Contact& c = contacts[i];
    for (int k = 0; k < 2; ++k) {
      c.normal_impulse[k] = k < PointCount(sc) ? Point(sc, k).normal_impulse : 0.0;
      c.tangent_impulse[k] = k < PointCount(sc) ? Point(sc, k).tangent_impulse : 0.0;
    }
  });
}

// The passes for either kind of constraint.
#define ENGINE_SUBSTEP_PASSES(C)                                                                  \
  template double WarmStart(std::span<C>, std::span<BodyState>, std::span<const BodyInfo>,        \
                            std::span<const std::uint8_t>, const StepStart&, double,              \
                            WarmStartImpulses);                                                   \
  template double LimitContactEnergy(std::span<C>, std::span<BodyState>, std::span<const BodyInfo>, \
                                     double, WarmStartImpulses);                                   \
  template void WarmStartAll(std::span<C>, std::span<BodyState>);                                \
  template void SolveContacts(std::span<C>, std::span<BodyState>, const StepStart&, double, bool); \
  template void PushOut(std::span<C>, std::span<const BodyState>, const StepStart&, PushVelocities, \
                        double, double, double);                                                  \
  template void ApplyImpactLags(std::span<const C>, std::span<const std::uint32_t>,              \
                                std::span<const double>, std::span<BodyState>);                   \
  template void StoreImpulses(std::span<const C>, std::span<const std::uint32_t>, std::span<Contact>, WorkerPool*);
ENGINE_SUBSTEP_PASSES(SubstepConstraint)
ENGINE_SUBSTEP_PASSES(LinearConstraint)
#undef ENGINE_SUBSTEP_PASSES

}  // namespace engine::detail
