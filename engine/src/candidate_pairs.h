// The broad-phase stage of a step: each body's bounds grown by how far it may reach within the
// step (its speculative margin), the pair budget's quotas, and the broad phase that pairs them.
// Internal to the engine.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "bodies.h"
#include "body_pair.h"
#include "broad_phase/broad_phase.h"
#include "engine/body.h"
#include "engine/ids.h"
#include "engine/world_def.h"

namespace engine::detail {

/// Speculative contacts start this many linear slops apart (Box2D's 4), so a body coming to rest
/// is caught a little before it touches; each resting body's bounds grow by half of it.
inline constexpr double kSpeculativeSlops = 4.0;

/// The body's bounding box where it stands (turned boxes included).
AABB BodyBounds(const Shape& shape, const BodyState& state);
/// A box of half extents `half` centred at `centre`, turned by `turn`: its bounding box. Inline:
/// compiled apart, it took its arguments in halves and stored them to load them back whole, each
/// load waiting for two stores.
inline AABB TurnedBoxBounds(Vec2 centre, Vec2 half, Rot turn) {
  const Vec2 reach{std::abs(turn.c) * half.x + std::abs(turn.s) * half.y,
                   std::abs(turn.s) * half.x + std::abs(turn.c) * half.y};
  return {centre - reach, centre + reach};
}

/// The bounding box of the body in `index`, whatever it is made of.
inline AABB BoundsOf(const Bodies& bodies, BodyIndex index) {
  if (IsSimpleShape(bodies.infos[index].shape.type)) return BodyBounds(bodies.infos[index].shape, bodies.states[index]);
  return PiecesBounds(*bodies.geometries[index], bodies.states[index]);
}

/// The pair budget's inputs for a body of this shape (docs/limits.md).
PairQuota QuotaOf(const Shape& shape, bool is_static);
/// The shape the body's quota is reckoned from: its own, or for a body of parts the box around
/// them (at least a millimetre across, so a flat polyline has an area).
Shape QuotaShape(const Bodies& bodies, BodyIndex index);

class CandidatePairs {
 public:
  /// The quota of a body just placed in slot `index` (a new slot is the next one).
  void Place(BodyIndex index, const Shape& shape, bool is_static) {
    if (index == quotas_.size()) quotas_.emplace_back();
    quotas_[index] = QuotaOf(shape, is_static);
  }

  /// Finds the pairs of enabled bodies whose grown bounds overlap and whose filters let them
  /// collide, sorted by (a, b). `speculative`: the solver takes contacts up to a margin apart
  /// (else only real overlap).
  void Find(const WorldDef& def, bool speculative, const Bodies& bodies, std::span<const std::uint8_t> awake,
            WorkerPool& pool);

  std::vector<BodyPair>& Pairs() { return pairs_; }
  /// Per body, how far it may reach within this step, m: two bodies closer than the sum of
  /// their margins get a (speculative) contact.
  std::span<const double> Margins() const { return margins_; }
  /// Per body, MakeRot of its angle as the last Find saw it, for every box of one shape (the
  /// other bodies' entries are not kept up): the narrow phase's boxes, made once a body rather
  /// than once a pair.
  std::span<const Rot> BoxTurns() const { return box_turns_; }
  /// The pair budget's account of the last Find (its bodies are the broad phase's, packed when
  /// some slot was not simulated: CrowdedSlot turns them into slots).
  const PairCollector& Budget() const { return broad_phase_.LastCollector(); }
  BodyIndex CrowdedSlot(std::uint32_t body) const { return packed_ ? packed_slots_[body] : body; }

 private:
  void FindAmongEnabled(const WorldDef& def, std::span<const std::uint8_t> enabled,
                        std::span<const PairQuota> quotas, WorkerPool& pool);

  std::vector<PairQuota> quotas_;
  std::vector<double> margins_;
  std::vector<Rot> box_turns_;
  std::vector<AABB> bounds_;
  std::vector<BodyPair> pairs_;
  // With some slots not simulated, the broad phase sees only the enabled bodies, packed:
  bool packed_ = false;
  std::vector<BodyIndex> packed_slots_;  ///< the slot of each packed body
  std::vector<AABB> packed_bounds_;
  std::vector<PairQuota> packed_quotas_;
  BroadPhase broad_phase_;  ///< every structure, so the choice can change between steps
};

}  // namespace engine::detail
