// Sweep and prune: the x endpoints of every box in one list kept sorted from call to call, then
// a sweep along x that checks y for the boxes open together.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/pair_collector.h"
#include "engine/math.h"

namespace engine {

/// Sweep and prune: endpoint lists kept from step to step and re-sorted by insertion sort,
/// which costs O(n + swaps) when bodies move little between steps (temporal coherence).
/// Sweeps the x axis, then checks y for pairs overlapping in x. Pairs come out sorted by (a, b).
class SweepAndPrune {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});
  const PairCollector& Collector() const { return collector_; }

  /// Swaps made by the last insertion sort (up to the budget that hands over to a full sort); a
  /// measure of how coherent the motion was.
  std::int64_t LastSwapCount() const { return last_swap_count_; }

 private:
  struct Endpoint {
    double value;
    std::uint32_t body;
    bool is_max;
  };
  struct ActiveInterval {
    double lower_y;
    double upper_y;
    std::uint32_t body;
  };
  static bool SortsBefore(const Endpoint& p, const Endpoint& q);
  void Rebuild(std::span<const AABB> boxes);
  /// Refreshes the endpoints from the boxes and sorts them again.
  void RestoreOrder(std::span<const AABB> boxes);
  void Sweep(std::span<const AABB> boxes, std::vector<BodyPair>* pairs, std::span<const PairQuota> quotas);

  std::vector<Endpoint> endpoints_;
  std::vector<ActiveInterval> active_;
  std::vector<std::uint32_t> active_slot_;  ///< where each open body sits in active_
  PairCollector collector_;
  std::int64_t last_swap_count_ = 0;
};

}  // namespace engine
