// Sleeping: islands of touching bodies that have rested long enough stop being simulated.
// Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/contact.h"
#include "forces/springs.h"
#include "engine/world_def.h"
#include "body_pair.h"
#include "wakefulness.h"

namespace engine::detail {
class WorkerPool;
}

namespace engine::detail {

/// Per body: `rest_time`, s it has moved slower than the sleep speed; `awake`, a Wakefulness;
/// `island`, while asleep, the smallest body slot of its island (kNoBody while disabled).
struct SleepState {
  std::span<double> rest_time;
  std::span<std::uint8_t> awake;
  std::span<std::uint32_t> island;
};

/// The sleep state's storage, one entry per body, and the scratch its update uses.
struct SleepTable {
  std::vector<double> rest_time;
  std::vector<std::uint8_t> awake;  ///< also the integrators' mask of moving bodies
  std::vector<std::uint32_t> island;
  std::vector<Vec2> accelerations;  ///< scratch: the free accelerations the rest test reads
  std::vector<double> angular_accelerations;
  std::vector<BodyPair> kept_pairs;  ///< scratch: WakeTouchedIslands' pairs, when shared

  /// Sets the slot's entry for a body just placed or changed there.
  void Place(BodyIndex index, Wakefulness wakefulness, bool enabled) {
    if (index == awake.size()) {
      rest_time.push_back(0.0);
      awake.push_back(0);
      island.push_back(0);
    }
    rest_time[index] = 0.0;
    awake[index] = enabled ? wakefulness : kResting;
    island[index] = enabled ? index : kNoBody;
  }
  SleepState View() { return {rest_time, awake, island}; }
};

/// Before the narrow phase: a moving body that reaches a sleeping one, through a candidate pair
/// or an acting spring, wakes the sleeper's whole island; then the pairs where nothing moves
/// (static with static, or with a sleeping body) are dropped: they need no contact.
/// `pool`, `scratch`: threads to share the looking among, and a list to keep the pairs in.
void WakeTouchedIslands(std::vector<BodyPair>* pairs, std::span<const Spring> springs,
                        std::span<const BodyPair> joint_links, std::span<const BodyInfo> infos, SleepState sleep,
                        WorkerPool* pool = nullptr, std::vector<BodyPair>* scratch = nullptr);

/// After a step: counts resting time (slow, and held by a contact or pushed by no force:
/// `accelerations` are each body's free accelerations) and puts to sleep every island (bodies
/// linked by touching contacts or `springs`, the ones that act, static bodies excluded) whose
/// bodies have all rested for `time_to_sleep`.
void UpdateSleep(std::span<const Contact> contacts, std::span<const Spring> springs,
                 std::span<const BodyPair> joint_links,
                 std::span<const Vec2> accelerations, std::span<BodyState> states,
                 std::span<const BodyInfo> infos, const WorldDef& def, SleepState sleep);

/// How a body of this kind and velocity starts out: dynamic bodies awake, kinematic ones moving
/// while they have a velocity, static ones resting.
Wakefulness WakefulnessOf(const BodyInfo& info, const BodyState& state);

/// Wakes the sleeping island `body` belongs to (nothing if it is awake, static, kinematic or
/// disabled).
void WakeIsland(BodyIndex body, std::span<const BodyInfo> infos, SleepState sleep);

}  // namespace engine::detail
