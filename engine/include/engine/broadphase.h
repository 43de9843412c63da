// Broad phase: which bodies' bounding boxes overlap, reported as sorted id pairs.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/math.h"

namespace engine {

struct BodyPair {
  std::uint32_t a;  ///< the smaller index
  std::uint32_t b;
  friend constexpr bool operator==(BodyPair, BodyPair) = default;
};

/// Every overlapping pair by testing all of them: the reference, and the fastest for a handful
/// of boxes. Pairs come out sorted by (a, b).
void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

/// Sweep and prune: endpoint lists kept from step to step and re-sorted by insertion sort,
/// which costs O(n + swaps) when bodies move little between steps (temporal coherence).
/// Sweeps the x axis, then checks y for pairs overlapping in x. Pairs come out sorted by (a, b).
class SweepAndPrune {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

  /// Swaps made by the last insertion sort; a measure of how coherent the motion was.
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
  void Rebuild(std::span<const AABB> boxes);

  std::vector<Endpoint> endpoints_;
  std::vector<ActiveInterval> active_;
  std::vector<std::uint32_t> active_slot_;  ///< where each open body sits in active_
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
  std::int64_t last_swap_count_ = 0;
};

}  // namespace engine
