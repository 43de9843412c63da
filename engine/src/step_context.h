// What a contact solver's step works on: the bodies, this step's contacts, the forces, and where
// a numeric fault is recorded. After Box2D v3's b2StepContext. Internal to the engine.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "engine/events.h"
#include "engine/world_def.h"
#include "forces/force_model.h"
#include "integrate.h"
#include "joints/joint_solver.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

/// The first body (in id order) whose state is not finite, as a fault of step `step`; nothing
/// if every number is finite. `pool`: threads to share the looking among.
std::optional<NumericFault> FindNonFinite(std::span<const BodyState> states, std::int64_t step,
                                          WorkerPool* pool = nullptr);

struct StepContext {
  const WorldDef& def;                    ///< with the automatic settings filled in
  std::span<BodyState> states;
  std::span<const BodyInfo> infos;
  std::span<const std::uint8_t> moving;   ///< per body: integrated this step (awake, dynamic)
  /// This step's contacts in pair order: last step's impulses in (warm start), this step's out.
  std::span<Contact> contacts;
  /// The contacts' bodies alone, in the same order, where the narrow phase wrote them (on
  /// several threads); else empty.
  std::span<const BodyPair> contact_pairs;
  std::span<const Vec2> start_positions;  ///< each body's centre when the step began
  bool can_turn;                          ///< some body has finite inertia (rotation on)
  const ForceModel& forces;
  FreeMotion& free_motion;                ///< the integrators' scratch
  /// The joints with a moving body, prepared for this step; null when there are none.
  JointSolver* joints;
  std::int64_t step;                      ///< the step's number, for a fault report
  std::optional<NumericFault>& fault;
  WorkerPool& pool;                       ///< WorldDef::threads

  /// Records the first non-finite state as the fault; true if there is one (the solver then
  /// stops, so the fault is named where it appeared instead of spreading through the contacts).
  bool StopIfNonFinite() {
    fault = FindNonFinite(states, step, &pool);
    return fault.has_value();
  }
};

}  // namespace engine::detail
