// The broad-phase stage of a step: each body's bounds grown by how far it may reach within the
// step (its speculative margin), the pair budget's quotas, and the broad phase that pairs them.
// Internal to the engine.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/broad_phase.h"
#include "engine/body.h"
#include "engine/ids.h"
#include "engine/world_def.h"

namespace engine::detail {

/// The body's bounding box where it stands (turned boxes included).
AABB BodyBounds(const Shape& shape, const BodyState& state);

/// The pair budget's inputs for a body of this shape (docs/limits.md).
PairQuota QuotaOf(const Shape& shape, bool is_static);

class CandidatePairs {
 public:
  /// A new body's quota; call once per body, in id order.
  void AddBody(const Shape& shape, bool is_static) { quotas_.push_back(QuotaOf(shape, is_static)); }

  /// Finds the pairs of bodies whose grown bounds overlap, sorted by (a, b). `speculative`: the
  /// solver takes contacts up to a margin apart (else only real overlap).
  void Find(const WorldDef& def, bool speculative, std::span<const BodyState> states,
            std::span<const BodyInfo> infos, std::span<const std::uint8_t> awake);

  std::vector<BodyPair>& Pairs() { return pairs_; }
  /// Per body, how far it may reach within this step, m: two bodies closer than the sum of
  /// their margins get a (speculative) contact.
  std::span<const double> Margins() const { return margins_; }
  /// The pair budget's account of the last Find.
  const PairCollector& Budget() const { return broad_phase_.LastCollector(); }

 private:
  std::vector<PairQuota> quotas_;
  std::vector<double> margins_;
  std::vector<AABB> bounds_;
  std::vector<BodyPair> pairs_;
  BroadPhase broad_phase_;  ///< every structure, so the choice can change between steps
};

}  // namespace engine::detail
