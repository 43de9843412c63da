// Sweep and prune along x: endpoints re-sorted by insertion sort (bodies move little between
// steps), then one sweep that keeps the open intervals with their y extents inline.
#include "broad_phase/sweep_and_prune.h"

#include <algorithm>

namespace engine {

// At equal values a lower end sorts before an upper end, so boxes that exactly touch are still
// reported.
bool SweepAndPrune::SortsBefore(const Endpoint& p, const Endpoint& q) {
  return p.value < q.value || (p.value == q.value && !p.is_max && q.is_max);
}

void SweepAndPrune::Rebuild(std::span<const AABB> boxes) {
  endpoints_.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    endpoints_.push_back({boxes[i].lower.x, i, false});
    endpoints_.push_back({boxes[i].upper.x, i, true});
  }
  // A fresh list can be in any order: insertion sort would take O(n²) on it. A stable
  // O(n log n) sort gives the same order insertion sort would (ties keep body order).
  std::stable_sort(endpoints_.begin(), endpoints_.end(), SortsBefore);
}

// The values are refreshed in place and the order restored by insertion sort: after a small step
// almost nothing moves, so this is close to linear.
void SweepAndPrune::RestoreOrder(std::span<const AABB> boxes) {
  for (Endpoint& e : endpoints_) {
    e.value = e.is_max ? boxes[e.body].upper.x : boxes[e.body].lower.x;
  }
  // A reshuffle (a pile bursting apart, bodies teleported) would make that quadratic: past a
  // budget of swaps the rest is left to a stable O(n log n) sort. Both sorts are stable and the
  // part done by insertion keeps equal keys in their old order, so the order is the same.
  const auto swap_budget = static_cast<std::int64_t>(8 * endpoints_.size() + 1024);
  std::int64_t swaps = 0;
  for (std::size_t i = 1; i < endpoints_.size(); ++i) {
    const Endpoint key = endpoints_[i];
    std::size_t j = i;
    while (j > 0 && SortsBefore(key, endpoints_[j - 1])) {
      endpoints_[j] = endpoints_[j - 1];
      --j;
      ++swaps;
    }
    endpoints_[j] = key;
    if (swaps > swap_budget) {
      std::stable_sort(endpoints_.begin(), endpoints_.end(), SortsBefore);
      break;
    }
  }
  last_swap_count_ = swaps;
}

// Every body whose interval is open when another's opens overlaps it in x. The open intervals
// keep their y extents inline, so the inner loop reads memory in order.
void SweepAndPrune::Sweep(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                          std::span<const PairQuota> quotas) {
  collector_.Begin(boxes, quotas, pairs);
  active_.clear();
  active_slot_.resize(boxes.size());
  for (const Endpoint& e : endpoints_) {
    if (e.is_max) {
      const std::uint32_t slot = active_slot_[e.body];
      active_[slot] = active_.back();
      active_slot_[active_[slot].body] = slot;
      active_.pop_back();
      continue;
    }
    const AABB& box = boxes[e.body];
    for (const ActiveInterval& other : active_) {
      if (box.lower.y <= other.upper_y && other.lower_y <= box.upper.y) {
        collector_.Add(e.body, other.body);
      }
    }
    active_slot_[e.body] = static_cast<std::uint32_t>(active_.size());
    active_.push_back({box.lower.y, box.upper.y, e.body});
  }
  collector_.Finish();
}

void SweepAndPrune::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                              std::span<const PairQuota> quotas) {
  if (endpoints_.size() != 2 * boxes.size()) Rebuild(boxes);
  RestoreOrder(boxes);
  Sweep(boxes, pairs, quotas);
}

}  // namespace engine
