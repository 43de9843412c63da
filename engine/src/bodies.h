// The bodies' storage: one slot per body, what every step writes, what it only reads, and the
// embedder's per-body settings. Slots of destroyed bodies wait on a free list for the next body;
// each slot's generation tells a live id from a stale one. Internal to the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "body_geometry.h"
#include "engine/body.h"
#include "engine/ids.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

struct Bodies {
  std::vector<BodyState> states;
  std::vector<BodyInfo> infos;
  /// The pieces of a body made of parts; null for a lone circle or box.
  std::vector<std::shared_ptr<const BodyGeometry>> geometries;
  /// For a body made of parts, its frame's origin as last placed (made, or set by hand) and the
  /// centre and angle it had then: while the body stays there the origin is reported as given,
  /// not recomputed from the centre of mass with a rounding error.
  struct PlacedOrigin {
    Vec2 origin;
    Vec2 center;
    double angle = 0.0;
  };
  std::vector<PlacedOrigin> placed_origins;
  std::vector<Vec2> start_positions;  ///< each body's centre when the current step began
  /// Each body's angle when the step began, kept only while some body is made of parts (the
  /// continuous pass sweeps them).
  std::vector<double> start_angles;
  std::vector<std::uint32_t> generations;
  std::vector<std::uint8_t> alive;    ///< 0: the slot is free
  std::vector<std::uint8_t> enabled;  ///< 0: disabled or free: not simulated at all
  std::vector<Filter> filters;
  std::vector<std::uint64_t> user_data;
  /// Forces and torques the embedder applied since the last step (cleared by each step).
  std::vector<Vec2> applied_forces;
  std::vector<double> applied_torques;
  std::vector<BodyIndex> free_slots;  ///< a stack: the last freed slot is reused first
  std::vector<BodyId> live_ids;       ///< the live bodies, in slot order

  std::size_t damped = 0;             ///< bodies with linear or angular damping
  std::size_t turnable = 0;           ///< bodies free to turn (finite inertia)
  std::size_t inactive = 0;           ///< slots not simulated: disabled bodies and free slots
  std::size_t filtered = 0;           ///< bodies whose filter is not the default
  std::size_t sensors = 0;
  std::size_t kinematic = 0;
  std::size_t with_parts = 0;         ///< bodies made of parts (not a lone circle or box)
  bool forces_applied = false;        ///< some applied force or torque waits for the step

  /// A slot for a new body (a free one, else a new one at the end), its generation kept.
  BodyIndex Allocate();
  /// A new slot at the end, live, generation 0 (snapshots rebuild the slots in order with it).
  BodyIndex AppendSlot();
  /// Frees the slot and makes every id of it stale.
  void Free(BodyIndex index);
  bool IsLive(BodyId id) const {
    return id.index < alive.size() && alive[id.index] && generations[id.index] == id.generation;
  }
  BodyId IdOf(BodyIndex index) const { return {index, generations[index]}; }
  /// Adds or removes the body's share of the counts above.
  void Count(BodyIndex index, int sign);
  void ClearAppliedForces();

  /// The body frame's origin: the centre, unless the body is made of parts.
  Vec2 Origin(BodyIndex index) const {
    if (!geometries[index]) return states[index].position;
    const PlacedOrigin& placed = placed_origins[index];
    const BodyState& s = states[index];
    if (s.position == placed.center && s.angle == placed.angle) return placed.origin;
    return OriginOf(*geometries[index], s);
  }
  /// A point given in the body's frame, seen from its centre of mass (the same for a lone
  /// circle or box).
  Vec2 FromCenter(BodyIndex index, Vec2 local) const {
    return geometries[index] ? local - geometries[index]->local_center : local;
  }
  /// Places a body made of parts with its frame's origin at `origin`, turned by `angle`.
  void PlaceOrigin(BodyIndex index, Vec2 origin, double angle) {
    states[index].position = origin + Rotate(MakeRot(angle), geometries[index]->local_center);
    states[index].angle = angle;
    placed_origins[index] = {origin, states[index].position, angle};
  }

  /// Each body's centre (and, with bodies made of parts, angle) as the step begins; with a
  /// pool, each thread its share of the bodies, whose states its core wrote last (on the first
  /// thread alone, half of them came from the other core).
  void MarkStepStart(WorkerPool* pool) {
    start_positions.resize(states.size());
    if (with_parts > 0) start_angles.resize(states.size());
    ForEachIndex(pool, states.size(), kMinSharedBodies,
                 [positions = start_positions.data(), angles = with_parts > 0 ? start_angles.data() : nullptr,
                  states = states.data()](std::uint32_t i) {
                   positions[i] = states[i].position;
                   if (angles) angles[i] = states[i].angle;
                 });
  }
};

/// kg: the given mass, or density × area (of a circle or box; a body of parts has its
/// geometry's).
double BodyMass(const BodyDef& def);

/// What a step reads of a body made from `def` (preconditions checked): mass and inertia from
/// the shape, or from `geometry` for a body made of parts; infinite inertia (0 inverse) without
/// rotation.
BodyInfo MakeBodyInfo(const BodyDef& def, const BodyGeometry* geometry, bool rotation);

}  // namespace engine::detail
