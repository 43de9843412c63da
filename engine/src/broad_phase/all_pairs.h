// All pairs: every pair of boxes tested. The reference the other broad phases are checked
// against, and the fastest for a handful of boxes.
#pragma once

#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/pair_collector.h"
#include "engine/math.h"

namespace engine {

/// Every overlapping pair by testing all of them, with no pair budget: the reference. Pairs come
/// out sorted by (a, b).
void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

/// The same test of every pair, through the pair budget like every other broad phase. Pairs come
/// out sorted by (a, b).
class AllPairs {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});
  const PairCollector& Collector() const { return collector_; }

 private:
  PairCollector collector_;
};

}  // namespace engine
