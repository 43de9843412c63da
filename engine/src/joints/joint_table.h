// The world's joints, by slot: what each was made from, its frame on each body, and the
// impulses it carries from substep to substep. Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/ids.h"
#include "engine/joint.h"
#include "engine/math.h"

namespace engine::detail {

/// The impulses a joint's rows accumulate over a substep and start the next one with (the warm
/// start), N·s and N·m·s.
struct JointImpulses {
  Vec2 point;            ///< revolute, weld: the shared point; prismatic: x across the axis
  double angle = 0.0;    ///< weld, prismatic: relative turning
  double axial = 0.0;    ///< distance: along the anchors' line (fixed length)
  double lower = 0.0;    ///< the lower limit (angle, translation or min length), ≥ 0
  double upper = 0.0;    ///< the upper limit, ≥ 0
  double motor = 0.0;
};

/// One joint, with its bodies as slots (`a` is kNoBody for a target joint: the world).
struct Joint {
  JointDef def;
  BodyIndex a = kNoBody;
  BodyIndex b = kNoBody;
  Vec2 local_a;               ///< the anchor on A from A's centre of mass, A's frame (target: 0)
  Vec2 local_b;               ///< the anchor on B from B's centre of mass, B's frame
  Vec2 local_axis;            ///< prismatic: the unit axis in A's frame
  double reference_angle = 0.0;  ///< angle_b − angle_a when made
  // distance: the resolved lengths; a rigid joint holds `length` exactly
  double length = 0.0;
  double min_length = 0.0;
  double max_length = 0.0;
  bool rigid_length = false;
  JointImpulses impulses;
};

struct JointTable {
  std::vector<Joint> joints;              ///< by slot; a free slot's entry is stale
  std::vector<std::uint32_t> generations;
  std::vector<std::uint8_t> alive;
  std::vector<std::uint32_t> free_slots;  ///< a stack: the last freed slot is reused first
  std::vector<JointId> live_ids;          ///< in slot order, kept up to date by Allocate and Free
  /// Slots of the joints that act (both bodies enabled), in slot order: the only ones a step sees.
  std::vector<std::uint32_t> acting;
  /// The body pairs of acting joints that keep their bodies from colliding, sorted.
  std::vector<BodyPair> no_collide;
  /// The body pairs of acting joints between two bodies (sleep joins and wakes islands by them).
  std::vector<BodyPair> links;
  /// `acting`, `no_collide` and `links` wait for a Rebuild (joints or bodies changed since):
  /// making n joints one by one rebuilds once, at the next step, not n times.
  bool stale = false;

  bool IsLive(JointId id) const {
    return id.index < alive.size() && alive[id.index] && generations[id.index] == id.generation;
  }
  std::uint32_t Allocate();
  void Free(std::uint32_t slot);
  /// Rebuilds `acting`, `no_collide` and `links` (after joints or bodies came, went, or were
  /// enabled or disabled).
  void Rebuild(std::span<const std::uint8_t> body_enabled);
};

/// Drops from `pairs` (sorted) the pairs a joint keeps from colliding.
void DropJoinedPairs(std::span<const BodyPair> no_collide, std::vector<BodyPair>* pairs);

}  // namespace engine::detail
