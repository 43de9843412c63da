// The substep solver's passes over the contact constraints: warm start, solve, push out, and
// what the step does before and after them. Each takes either kind of constraint. Internal.
#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "solver/block_solver.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "integrate.h"
#include "parallel/worker_pool.h"
#include "solver/impact.h"
#include "solver/substep_constraint.h"

namespace engine::detail {

/// Where the bodies were at the step's start and how far each has turned since: the separation
/// of a contact now follows from these and the contact's anchors.
struct StepStart {
  std::span<const Vec2> positions;
  /// Each body's rotation since the step's start; empty where no contact's body turns its
  /// points (SubstepSolver::TurnsAnchors), the anchors then fixed.
  std::span<const Rot> turned;
};

// The passes take either kind of constraint: SubstepConstraint where something can turn,
// LinearConstraint where nothing can. These say what a pass may ask of each; the angular terms
// are compiled only for the first.
template <typename C>
inline constexpr bool kCanTurn = std::is_same_v<C, SubstepConstraint>;
inline bool Turns(const SubstepConstraint& c) { return c.angular; }
constexpr bool Turns(const LinearConstraint&) { return false; }
inline int PointCount(const SubstepConstraint& c) { return c.point_count; }
constexpr int PointCount(const LinearConstraint&) { return 1; }
inline SubstepPoint& Point(SubstepConstraint& c, int k) { return c.points[k]; }
inline const SubstepPoint& Point(const SubstepConstraint& c, int k) { return c.points[k]; }
inline LinearConstraint& Point(LinearConstraint& c, int) { return c; }
inline const LinearConstraint& Point(const LinearConstraint& c, int) { return c; }

/// Contacts are shared among threads from these many: fewer cost more to hand out than they save.
inline constexpr std::uint32_t kMinSharedContacts = 4096;

/// What the step's SubstepConstraints hold, found as they are prepared, so that no pass over
/// them asks again: a pair that cannot turn (shock propagation takes those; the turning lanes
/// take none), and a heavy pair (IsHeavyPair: the direct solve's). Set by whichever thread meets
/// one, never cleared within a step.
struct ConstraintKinds {
  std::atomic<bool> not_turning{false};
  std::atomic<bool> heavy{false};
};

/// One constraint per contact, with the impulses carried over from the last step; contact i's
/// goes to `slot[i]` (the solve order, ColourContacts). `states` give the bodies' centres, to
/// turn contact points into anchors. `pool`: threads to share the contacts among (each
/// constraint is written by its contact alone; from kMinSharedContacts, in ForEachIndex's runs).
/// `look`: where not null, each contact is also looked at for an impact (ImpactLook).
/// `kinds`: where not null (SubstepConstraints), what kinds of constraint were met.
template <typename C>
void PrepareSubstepConstraints(std::span<const Contact> contacts, std::span<const std::uint32_t> slot,
                               std::span<const BodyInfo> infos, std::span<const BodyState> states,
                               std::vector<C>* constraints, WorkerPool* pool = nullptr, ImpactLook* look = nullptr,
                               ConstraintKinds* kinds = nullptr);
/// The same for contacts [begin, end) alone, into constraints already the contacts' number; and
/// where `restitutions` is not empty (the contacts' number), each contact's restitution there.
void PrepareLinearConstraints(std::span<const Contact> contacts, std::span<const std::uint32_t> slot,
                              std::span<const BodyInfo> infos, std::span<LinearConstraint> constraints,
                              std::uint32_t begin, std::uint32_t end, std::span<double> restitutions = {});

/// K of a two-point contact for the given (possibly partly zeroed) inverse masses and inertias.
TwoPointMass NormalMass(const SubstepConstraint& sc, const SubstepPoint& p1, const SubstepPoint& p2,
                        double inv_mass_a, double inv_mass_b, double inv_inertia_a,
                        double inv_inertia_b);

/// The separation of point `p` of `sc` now, m (negative when overlapping): the separation at the
/// step's start plus how far the anchors have moved apart along the normal since. Inline: every
/// pass over the contacts asks it for every point.
template <typename C, typename P>
inline double CurrentSeparation(const C& sc, const P& p, std::span<const BodyState> states,
                                const StepStart& start) {
  Vec2 moved = (states[sc.b].position - start.positions[sc.b]) -
               (states[sc.a].position - start.positions[sc.a]);
  if constexpr (kCanTurn<C>) {
    if (sc.angular && start.turned.empty()) {  // no body's turn moves its points (TurnsAnchors)
      moved = moved + p.anchor_b - p.anchor_a;
    } else if (sc.angular) {
      moved = moved + Rotate(start.turned[sc.b], p.anchor_b) - Rotate(start.turned[sc.a], p.anchor_a);
    }
  }
  return p.base_separation + Dot(moved, sc.normal);
}

/// Scratch for `WarmStart`, one entry per body: the sums of the force-free contacts' warm-start
/// impulses on each body (`angular` empty when nothing turns).
struct WarmStartImpulses {
  std::span<Vec2> linear;
  std::span<double> angular;
};

/// Applies the impulses accumulated so far again, so the solve starts from the last answer
/// (docs/solver.md, "Warm start"), except
/// - sliding friction that would now push the pair the way it slides: a tangent impulse stored
///   at the edge of Coulomb's cone is dropped when the relative sliding is along it;
/// - the impulses of force-free contacts, those whose bodies carry no applied force (`loaded` is
///   0 for both; an empty `loaded` means every body is loaded), are scaled by the factor in
///   [0, 1] that leaves the least kinetic energy, so that there the contacts only take energy
///   out. Returns that factor (1 when nothing is force-free).
template <typename C>
double WarmStart(std::span<C> constraints, std::span<BodyState> states,
                 std::span<const BodyInfo> infos, std::span<const std::uint8_t> loaded,
                 const StepStart& start, double inv_h, WarmStartImpulses scratch);

/// WarmStart where every body is loaded (`loaded` empty): the impulses go straight on. Each
/// constraint writes only its own moving bodies: threads may run it on a group's ranges.
template <typename C>
void WarmStartAll(std::span<C> constraints, std::span<BodyState> states);

/// Kinetic energy of all bodies, J (rotation counted only where the body can turn).
double KineticEnergy(std::span<const BodyState> states, std::span<const BodyInfo> infos);

/// For a world where no applied force acts: if the substep's contact impulses left more kinetic
/// energy than `energy_before` (the warm start's bound has one exception: a friction impulse cut
/// back to a cone that shrank with its normal impulse), takes back the least fraction of every
/// contact's impulse that brings it down to `energy_before`. Returns that fraction (0: none).
template <typename C>
double LimitContactEnergy(std::span<C> constraints, std::span<BodyState> states,
                          std::span<const BodyInfo> infos, double energy_before,
                          WarmStartImpulses scratch);

/// One Gauss-Seidel pass over all contacts: touching bodies may not approach, bodies with a gap
/// may close no more than it this substep (speculative contact), friction within Coulomb's cone.
/// `block_solve`: both normal impulses of a turning pair's two-point contact found together
/// (SolveTwoPoints); otherwise one point after the other.
template <typename C>
void SolveContacts(std::span<C> constraints, std::span<BodyState> states,
                   const StepStart& start, double inv_h, bool block_solve);

/// Sets every push velocity to zero, before a step's first PushOut (MoveByPush zeroes them
/// after each).
void ClearPush(PushVelocities push, WorkerPool* pool = nullptr);

/// Split impulse (Catto, GDC 2009; Bullet's "split impulse"): overlap beyond the slop is pushed
/// out through separate push velocities at `push_out_rate` per second of overlap, at most
/// `max_push_out_speed`, starting from zero. They move positions this substep and are then
/// dropped, so resolving an overlap never launches a body. Like SolveContacts, it writes only
/// the constraints' moving bodies.
template <typename C>
void PushOut(std::span<C> constraints, std::span<const BodyState> states,
             const StepStart& start, PushVelocities push, double push_out_rate,
             double max_push_out_speed, double linear_slop);

/// Moves every body by its push velocity for one substep, and sets the push velocities back to
/// zero for the next (in the same pass: a pass of its own over every body cost a hand-off to the
/// threads and back each substep). `pool`: threads to share the bodies among.
void MoveByPush(std::span<BodyState> states, PushVelocities push, bool rotation, double h,
                WorkerPool* pool = nullptr);

/// Moves each pair of bodies apart by what the impact pass asked for: `lags[i]` for contact i,
/// whose constraint is at `slot[i]`.
template <typename C>
void ApplyImpactLags(std::span<const C> constraints, std::span<const std::uint32_t> slot,
                     std::span<const double> lags, std::span<BodyState> states);

/// Stores the accumulated impulses back on the contacts for the next step's warm start.
template <typename C>
void StoreImpulses(std::span<const C> constraints, std::span<const std::uint32_t> slot,
                   std::span<Contact> contacts, WorkerPool* pool = nullptr);

}  // namespace engine::detail
