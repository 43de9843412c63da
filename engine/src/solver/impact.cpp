// Impacts with restitution, pair by pair, with the bounce placed at the moment of impact.
#include "solver/impact.h"

#include "parallel/per_thread.h"
#include "solver/substep_passes.h"

#include <algorithm>
#include <cassert>
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

// Under a constant acceleration a, every integrator puts a body at its step points on a parabola
// s0 + w·t + ½·a·t², whose slope w is the velocity v offset by c halves of a kick, w = v + ½·c·a·h:
// c = 1 for semi-implicit Euler (it moves with the velocity after the kick), −1 for explicit
// Euler (before it), 0 for velocity Verlet, midpoint and RK4, which follow the parabola exactly.
// ½·w² − a·s is what each conserves in free flight (for semi-implicit Euler that is its modified
// energy H = ½v² − a·s + ½·a·h·v, up to a constant).
double KickOffset(Integrator integrator) {
  switch (integrator) {
    case Integrator::kSemiImplicitEuler: return 1.0;
    case Integrator::kExplicitEuler: return -1.0;
    case Integrator::kVelocityVerlet:
    case Integrator::kMidpoint:
    case Integrator::kRungeKutta4: return 0.0;
  }
  return 0.0;
}

// The separation after n substeps of h of free flight from (s0, v): s0 + n·h·v + a·h²·n(n + c)/2.
double FreeSeparation(double s0, double v, double a, int n, double h, double c) {
  return s0 + n * h * v + a * (h * h * n * (n + c) / 2.0);
}

// Semi-implicit Euler: the bounce keeps e²·H, placed at the mirrored position −e·s_free. This
// differs from the exact reflection below by ½·a·r²·(1 + e) (r the time left after the impact),
// second order and below this integrator's own first-order error (S7's largest error is the
// same to three digits either way); it is kept so that bounces under the default integrator keep
// their bits (the default scene's golden state hash).
bool MirroredBounce(double s0, double vn, double a, double e, int n, double h, Bounce* out) {
  const double s_free = FreeSeparation(s0, vn, a, n, h, 1.0);
  if (s_free >= 0.0) return false;  // no contact within the step: the next step's impact pass sees it
  const double s_end = -e * s_free;
  const double energy = 0.5 * vn * vn - a * s0 + 0.5 * a * h * vn;
  // Solve ½v² + ½·a·h·v − (a·s_end + e²·H) = 0 for the separating root.
  const double half_ah = 0.5 * a * h;
  const double discriminant = half_ah * half_ah + 2.0 * (a * s_end + e * e * energy);
  const double v_end = -half_ah + std::sqrt(std::max(discriminant, 0.0));
  out->start_velocity = v_end - a * n * h;
  out->lag = s_end - FreeSeparation(s0, out->start_velocity, a, n, h, 1.0);
  return true;
}

// Every other integrator: the parabola reflected where it meets s = 0 (its first root τ in the
// step), leaving at −e times the slope it arrives with. For Verlet, midpoint and RK4 under
// constant acceleration this is the exact bounce, to rounding. A pair already touching bounces
// at once, from where it is.
bool BounceAtImpact(double s0, double vn, double a, double e, int n, double h, double c, Bounce* out) {
  const double step = n * h;
  const double w0 = vn + 0.5 * c * a * h;
  double tau = 0.0, w_impact = w0, s_impact = s0;
  if (s0 > 0.0) {
    // First root of s0 + w0·t + ½·a·t², in the form that does not cancel: t = 2·s0 / (√D − w0).
    const double discriminant = w0 * w0 - 2.0 * a * s0;
    if (discriminant < 0.0) return false;  // the pair turns back before it meets
    const double root = std::sqrt(discriminant);
    if (root - w0 <= 0.0) return false;
    tau = 2.0 * s0 / (root - w0);
    if (tau >= step) return false;  // no contact within the step: the next step's impact pass sees it
    w_impact = -root;
    s_impact = 0.0;
  }
  if (w_impact >= 0.0) return false;
  const double rest = step - tau;
  const double w_end = -e * w_impact + a * rest;
  const double s_end = s_impact - e * w_impact * rest + 0.5 * a * rest * rest;
  out->start_velocity = w_end - 0.5 * c * a * h - a * step;
  out->lag = s_end - FreeSeparation(s0, out->start_velocity, a, n, h, c);
  return true;
}

// The bounce of a pair approaching at `vn` from separation `s0` under relative acceleration `a`,
// integrated in `n` substeps of `h`; nothing when free flight would not bring the pair into
// contact within this step.
bool ComputeBounce(Integrator integrator, double s0, double vn, double a, double e, int n, double h,
                   Bounce* out) {
  if (integrator == Integrator::kSemiImplicitEuler) return MirroredBounce(s0, vn, a, e, n, h, out);
  return BounceAtImpact(s0, vn, a, e, n, h, KickOffset(integrator), out);
}

// Where a pair is struck and how fast it closes, as the pass sees it now.
struct Strike {
  Vec2 anchor_a, anchor_b;
  double vn = 0.0;
  Bounce bounce{};
};

// Whether contact `contact`'s pair (constraint `sc`, the contact's `restitution`) bounces now,
// and if so where and how: it closes faster than the restitution threshold, would come out of
// the bounce faster than it, and meets within the step. The contact itself is read only for a
// turning pair.
template <typename C>
bool Strikes(const C& sc, double restitution, const Contact& contact, std::span<const BodyState> states,
             std::span<const Vec2> accelerations, const WorldDef& def, double h, Strike* out) {
  if (restitution == 0.0) return false;
  const BodyState& a = states[sc.a];
  const BodyState& b = states[sc.b];
  // A turning pair is struck at the middle of its manifold, so a box landing flat stays flat.
  Vec2 anchor_a, anchor_b;
  double separation = Point(sc, 0).base_separation;
  if constexpr (kCanTurn<C>) {
    if (sc.angular) {
      separation = std::numeric_limits<double>::infinity();
      double gaps[2] = {0.0, 0.0};
      for (int k = 0; k < sc.point_count; ++k) {
        const SubstepPoint& p = sc.points[k];
        gaps[k] = p.base_separation + Dot(p.anchor_b - p.anchor_a, sc.normal);
        separation = std::min(separation, gaps[k]);
      }
      // The points struck: all, or those within the slop of the first to touch.
      int struck = sc.point_count;
      if (contact.strike_first_touch) {
        struck = 0;
        for (int k = 0; k < sc.point_count; ++k) struck += gaps[k] <= separation + def.linear_slop ? 1 : 0;
      }
      for (int k = 0; k < sc.point_count; ++k) {
        if (struck < sc.point_count && gaps[k] > separation + def.linear_slop) continue;
        anchor_a += sc.points[k].anchor_a / struck;
        anchor_b += sc.points[k].anchor_b / struck;
      }
    }
  }
  Vec2 relative = b.velocity - a.velocity;
  if (Turns(sc)) relative += Cross(b.angular_velocity, anchor_b) - Cross(a.angular_velocity, anchor_a);
  const double vn = Dot(relative, sc.normal);
  // Slow impacts, and bounces that would come out slower than the threshold, are left to
  // the contact solver as inelastic: a resting body must not buzz.
  if (vn >= -def.restitution_threshold || restitution * -vn < def.restitution_threshold) return false;
  const double relative_acceleration = Dot(accelerations[sc.b] - accelerations[sc.a], sc.normal);
  if (!ComputeBounce(def.integrator, separation, vn, relative_acceleration, restitution, def.substeps, h,
                     &out->bounce)) {
    return false;
  }
  out->anchor_a = anchor_a;
  out->anchor_b = anchor_b;
  out->vn = vn;
  return true;
}

}  // namespace

template <typename C>
bool AnyImpact(std::span<const C> constraints, std::span<const std::uint32_t> slot,
               std::span<const Contact> contacts, std::span<const double> restitutions,
               std::span<const BodyState> states, std::span<const Vec2> accelerations, const WorldDef& def,
               WorkerPool* pool) {
  assert(restitutions.size() == contacts.size());
  const double h = def.dt / def.substeps;
  const auto any_in = [&](std::uint32_t begin, std::uint32_t end) {
    Strike strike;
    for (std::uint32_t i = begin; i < end; ++i) {
      if (Strikes(constraints[slot[i]], restitutions[i], contacts[i], states, accelerations, def, h, &strike)) {
        return true;
      }
    }
    return false;
  };
  const auto count = static_cast<std::uint32_t>(contacts.size());
  if (pool == nullptr || pool->Threads() == 1 || count < kMinSharedContacts) return any_in(0, count);
  // Each thread its part of the contacts, which are in pair order: mostly the bodies of its own
  // share, as the passes over the bodies cut them, so their lines stay in its core's cache.
  const int threads = pool->Threads();
  std::vector<PerThread<std::uint8_t>> found(static_cast<std::size_t>(threads));
  pool->RunOnAll([&](int thread) {
    const auto part = [&](int t) {
      return static_cast<std::uint32_t>(std::uint64_t{count} * static_cast<std::uint64_t>(t) /
                                        static_cast<std::uint64_t>(threads));
    };
    found[static_cast<std::size_t>(thread)].value = any_in(part(thread), part(thread + 1)) ? 1 : 0;
  });
  return std::any_of(found.begin(), found.end(), [](const PerThread<std::uint8_t>& f) { return f.value != 0; });
}

template <typename C>
bool StrikesAtFirst(const C& sc, double restitution, const Contact& contact, std::span<const BodyState> states,
                    std::span<const Vec2> accelerations, const WorldDef& def) {
  Strike strike;
  return Strikes(sc, restitution, contact, states, accelerations, def, def.dt / def.substeps, &strike);
}

template <typename C>
void ResolveImpacts(std::span<C> constraints, std::span<const std::uint32_t> slot,
                    std::span<const Contact> contacts, std::span<BodyState> states,
                    std::span<const Vec2> accelerations, const WorldDef& def, std::vector<double>* lags) {
  const double h = def.dt / def.substeps;
  lags->clear();  // stays empty unless a pair bounces
  for (int pass = 0; pass < kMaxImpactPasses; ++pass) {
    bool any = false;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      C& sc = constraints[slot[i]];
      Strike strike;
      if (!Strikes(sc, contacts[i].restitution, contacts[i], states, accelerations, def, h, &strike)) continue;
      double normal_mass = Point(sc, 0).normal_mass;
      if constexpr (kCanTurn<C>) {
        if (sc.angular) {  // worked out for the pairs that bounce alone: most do not
          const double ra = Cross(strike.anchor_a, sc.normal), rb = Cross(strike.anchor_b, sc.normal);
          normal_mass = 1.0 / (sc.inv_mass_a + sc.inv_mass_b + sc.inv_inertia_a * ra * ra +
                               sc.inv_inertia_b * rb * rb);
        }
      }
      BodyState& a = states[sc.a];
      BodyState& b = states[sc.b];
      const double impulse = (strike.bounce.start_velocity - strike.vn) * normal_mass;
      a.velocity -= (impulse * sc.inv_mass_a) * sc.normal;
      b.velocity += (impulse * sc.inv_mass_b) * sc.normal;
      if constexpr (kCanTurn<C>) {
        if (sc.angular) {
          a.angular_velocity -= sc.inv_inertia_a * Cross(strike.anchor_a, impulse * sc.normal);
          b.angular_velocity += sc.inv_inertia_b * Cross(strike.anchor_b, impulse * sc.normal);
        }
      }
      if (lags->empty()) lags->assign(contacts.size(), 0.0);
      (*lags)[i] = strike.bounce.lag;
      any = true;
    }
    if (!any) break;
  }
}

template bool AnyImpact(std::span<const SubstepConstraint>, std::span<const std::uint32_t>,
                         std::span<const Contact>, std::span<const double>, std::span<const BodyState>,
                         std::span<const Vec2>, const WorldDef&, WorkerPool*);
template bool AnyImpact(std::span<const LinearConstraint>, std::span<const std::uint32_t>,
                         std::span<const Contact>, std::span<const double>, std::span<const BodyState>,
                         std::span<const Vec2>, const WorldDef&, WorkerPool*);
template bool StrikesAtFirst(const SubstepConstraint&, double, const Contact&, std::span<const BodyState>,
                              std::span<const Vec2>, const WorldDef&);
template bool StrikesAtFirst(const LinearConstraint&, double, const Contact&, std::span<const BodyState>,
                              std::span<const Vec2>, const WorldDef&);
template void ResolveImpacts(std::span<SubstepConstraint>, std::span<const std::uint32_t>,
                             std::span<const Contact>, std::span<BodyState>, std::span<const Vec2>,
                             const WorldDef&, std::vector<double>*);
template void ResolveImpacts(std::span<LinearConstraint>, std::span<const std::uint32_t>,
                             std::span<const Contact>, std::span<BodyState>, std::span<const Vec2>,
                             const WorldDef&, std::vector<double>*);

}  // namespace engine::detail
