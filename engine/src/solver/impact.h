// The impact pass: restitution resolved as a sequence of two-body impacts before the contact
// solve. Internal to the engine.
#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "engine/spring.h"
#include "engine/world_def.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

/// For each contact whose bodies would meet during this step faster than the restitution
/// threshold, applies the bounce impulse and records in `lags` how far to move the bodies
/// apart after the step, so that they end where a bounce at the moment of impact would put them.
/// Repeats over all contacts until no pair still approaches, so an impact travels along a chain
/// of touching bodies one pair at a time, as in Newton's cradle (the propagation model; Smith et
/// al., "Reflections on Simultaneous Impact", SIGGRAPH 2012, discuss why simultaneous models
/// cannot do this).
///
/// The bounce keeps e² of the relative motion's energy exactly, as the integrator sees it: under
/// a constant relative acceleration a, each integrator's free flight conserves ½w² − a·s, with
/// w = v + ½·c·a·h (c = 1 semi-implicit Euler, −1 explicit Euler, 0 the methods exact for
/// constant acceleration), so every apex is e² times the last, free of the step's phase and of
/// the integrator. The bounce is the reflection of that flight at its time of impact, or for
/// semi-implicit Euler e²·H at the mirrored position −e·s (impact.cpp says why).
/// `accelerations` holds each body's acceleration (zero for static and sleeping ones). The
/// contacts are visited in contact order, contact i's constraint at `slot[i]` and its lag at
/// `lags[i]` (one per contact, zero unless it bounces; `lags` is left empty when none bounces).
template <typename C>
void ResolveImpacts(std::span<C> constraints, std::span<const std::uint32_t> slot,
                    std::span<const Contact> contacts, std::span<BodyState> states,
                    std::span<const Vec2> accelerations, const WorldDef& def, std::vector<double>* lags);

/// Whether ResolveImpacts would bounce any pair: its first look at each contact, before any
/// bounce has changed a velocity. When none bounces, ResolveImpacts changes nothing and can be
/// left out. Unlike ResolveImpacts it only reads, so `pool`'s threads share the contacts (from
/// kMinSharedContacts): in a settled pile almost no step has an impact, and the one-thread pass
/// read every body, whose lines the other core then had to take back. `restitutions`: each
/// contact's restitution, written apart as the constraints were prepared, so that only a turning
/// pair's contact is read (the contacts' 152 bytes each had cost the look 80-100 kcyc a step of
/// the 4 000-circle pour on one thread).
template <typename C>
bool AnyImpact(std::span<const C> constraints, std::span<const std::uint32_t> slot,
               std::span<const Contact> contacts, std::span<const double> restitutions,
               std::span<const BodyState> states, std::span<const Vec2> accelerations, const WorldDef& def,
               WorkerPool* pool = nullptr);

/// AnyImpact's look at one contact (`contact`, its constraint `sc`, its `restitution`): whether
/// ResolveImpacts would bounce it, before any bounce has changed a velocity.
template <typename C>
bool StrikesAtFirst(const C& sc, double restitution, const Contact& contact, std::span<const BodyState> states,
                    std::span<const Vec2> accelerations, const WorldDef& def);

/// AnyImpact's answer gathered as the constraints are prepared (PrepareSubstepConstraints), each
/// contact looked at (StrikesAtFirst) while its lines are at hand: the look on its own read every
/// contact and constraint again (352 kcyc a step of the turning 4 000-circle pour on one thread).
/// Threads preparing side by side share one: `found` is only ever set.
struct ImpactLook {
  std::span<const Vec2> accelerations;
  const WorldDef& def;
  std::atomic<bool> found{false};

  template <typename C>
  void Look(const C& sc, const Contact& contact, std::span<const BodyState> states) {
    if (!found.load(std::memory_order_relaxed) &&
        StrikesAtFirst(sc, contact.restitution, contact, states, accelerations, def)) {
      found.store(true, std::memory_order_relaxed);
    }
  }
};

}  // namespace engine::detail
