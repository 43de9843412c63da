// All-pairs and sweep-and-prune broad phases, the pair collector every broad phase ends with (the
// pair budget, then pairs sorted by (a, b), so what the solver sees never depends on how they were
// found), and BroadPhase, which dispatches to the chosen structure and makes the automatic choice.
#include "broad_phase/broad_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "broad_phase/pair_sort.h"

namespace engine {

namespace detail {

void SortPairs(std::size_t body_count, std::vector<BodyPair>* pairs, std::vector<BodyPair>* scratch,
               std::vector<std::uint32_t>* counts) {
  scratch->resize(pairs->size());
  auto pass = [&](const std::vector<BodyPair>& from, std::vector<BodyPair>& to, bool by_a) {
    counts->assign(body_count + 1, 0);
    for (const BodyPair& p : from) ++(*counts)[(by_a ? p.a : p.b) + 1];
    for (std::size_t i = 1; i <= body_count; ++i) (*counts)[i] += (*counts)[i - 1];
    for (const BodyPair& p : from) to[(*counts)[by_a ? p.a : p.b]++] = p;
  };
  pass(*pairs, *scratch, false);
  pass(*scratch, *pairs, true);
}

}  // namespace detail

void PairCollector::Begin(std::span<const AABB> boxes, std::span<const PairQuota> quotas,
                          std::vector<BodyPair>* pairs) {
  boxes_ = boxes;
  quotas_ = quotas;
  pairs_ = pairs;
  pairs->clear();
  crowd_of_.clear();
  crowd_body_.clear();
  kept_.clear();
  dropped_ = 0;
  most_charged_ = 0;
  if (!quotas.empty()) charged_.assign(boxes.size(), 0);
}

PairCollector::Rank PairCollector::RankOf(std::uint32_t body, std::uint32_t other) const {
  const AABB& b = boxes_[body];
  const AABB& o = boxes_[other];
  const double x = std::min(b.upper.x, o.upper.x) - std::max(b.lower.x, o.lower.x);
  const double y = std::min(b.upper.y, o.upper.y) - std::max(b.lower.y, o.lower.y);
  return {!std::isinf(quotas_[other].width), -std::min(x, y), other < body ? body - other : other - body, other};
}

void PairCollector::Keep(std::uint32_t body, const Rank& rank) {
  Rank* list = kept_.data() + std::size_t{crowd_of_[body]} * kCrowdPairs;
  if (!(rank < list[kCrowdPairs - 1])) return;
  std::uint32_t k = kCrowdPairs - 1;
  for (; k > 0 && rank < list[k - 1]; --k) list[k] = list[k - 1];
  list[k] = rank;
}

std::uint32_t PairCollector::GrownQuota(std::uint32_t body) const {
  const AABB& box = boxes_[body];
  const double growth = (box.upper.x - box.lower.x) * (box.upper.y - box.lower.y) / quotas_[body].area;
  // A NaN (a body of no area) or a growth past the limit both give the limit.
  const double quota = std::ceil(quotas_[body].quota * growth);
  return quota < PairQuota::kMaxQuota ? static_cast<std::uint32_t>(quota) : PairQuota::kMaxQuota;
}

void PairCollector::AddPastQuota(std::uint32_t body, std::uint32_t other) {
  if (crowd_of_.empty()) crowd_of_.assign(boxes_.size(), kNone);
  if (crowd_of_[body] == kNone) {
    // Only bodies past their own quota get here, few outside a pile: the grown quota is worked
    // out for them alone, each time (it only depends on the box).
    if (charged_[body] <= GrownQuota(body)) {
      pairs_->push_back(MakePair(body, other));
      return;
    }
    crowd_of_[body] = static_cast<std::uint32_t>(crowd_body_.size());
    crowd_body_.push_back(body);
    const Rank last{true, std::numeric_limits<double>::infinity(), kNone, kNone};
    kept_.insert(kept_.end(), kCrowdPairs, last);
  }
  Keep(body, RankOf(body, other));
}

void PairCollector::Finish() {
  if (!quotas_.empty()) {
    std::uint64_t offered = 0;
    for (std::uint32_t c : charged_) {
      offered += c;
      most_charged_ = std::max(most_charged_, c);
    }
    if (!crowd_body_.empty()) {
      // A crowded body's first pairs, from before it was past its quota, compete for its list too.
      std::vector<BodyPair>& pairs = *pairs_;
      std::size_t write = 0;
      for (const BodyPair& p : pairs) {
        const std::uint32_t c = Charged(p);
        if (crowd_of_[c] == kNone) {
          pairs[write++] = p;
        } else {
          Keep(c, RankOf(c, p.a == c ? p.b : p.a));
        }
      }
      pairs.resize(write);
      for (std::size_t list = 0; list < crowd_body_.size(); ++list) {
        const std::uint32_t body = crowd_body_[list];
        for (std::uint32_t k = 0; k < kCrowdPairs; ++k) {
          const std::uint32_t other = kept_[list * kCrowdPairs + k].other;
          if (other == kNone) break;
          pairs.push_back(MakePair(body, other));
        }
      }
    }
    dropped_ = offered - pairs_->size();
  }
  detail::SortPairs(boxes_.size(), pairs_, &scratch_, &counts_);
}

void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
  pairs->clear();
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (Overlaps(boxes[i], boxes[j])) pairs->push_back({i, j});
    }
  }
}

void SweepAndPrune::Rebuild(std::span<const AABB> boxes) {
  endpoints_.clear();
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    endpoints_.push_back({boxes[i].lower.x, i, false});
    endpoints_.push_back({boxes[i].upper.x, i, true});
  }
  // A fresh list can be in any order: insertion sort would take O(n²) on it. A stable
  // O(n log n) sort gives the same order insertion sort would (ties keep body order).
  std::stable_sort(endpoints_.begin(), endpoints_.end(), [](const Endpoint& p, const Endpoint& q) {
    return p.value < q.value || (p.value == q.value && !p.is_max && q.is_max);
  });
}

void SweepAndPrune::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                              std::span<const PairQuota> quotas) {
  if (endpoints_.size() != 2 * boxes.size()) Rebuild(boxes);

  // Refresh the values in place, then restore the order by insertion sort: after a small step
  // almost nothing moves, so this is close to linear. At equal values a lower end sorts before
  // an upper end, so boxes that exactly touch are still reported.
  for (Endpoint& e : endpoints_) {
    e.value = e.is_max ? boxes[e.body].upper.x : boxes[e.body].lower.x;
  }
  auto less = [](const Endpoint& p, const Endpoint& q) {
    return p.value < q.value || (p.value == q.value && !p.is_max && q.is_max);
  };
  // A reshuffle (a pile bursting apart, bodies teleported) would make that quadratic: past a
  // budget of swaps the rest is left to a stable O(n log n) sort. Both sorts are stable and the
  // part done by insertion keeps equal keys in their old order, so the order is the same.
  const auto swap_budget = static_cast<std::int64_t>(8 * endpoints_.size() + 1024);
  std::int64_t swaps = 0;
  for (std::size_t i = 1; i < endpoints_.size(); ++i) {
    const Endpoint key = endpoints_[i];
    std::size_t j = i;
    while (j > 0 && less(key, endpoints_[j - 1])) {
      endpoints_[j] = endpoints_[j - 1];
      --j;
      ++swaps;
    }
    endpoints_[j] = key;
    if (swaps > swap_budget) {
      std::stable_sort(endpoints_.begin(), endpoints_.end(), less);
      break;
    }
  }
  last_swap_count_ = swaps;

  // Sweep x: every body whose interval is open when another's opens overlaps it in x. The open
  // intervals keep their y extents inline, so the inner loop reads memory in order.
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

void BroadPhase::FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                                   std::span<const PairQuota> quotas) {
  all_pairs_.Begin(boxes, quotas, pairs);
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (Overlaps(boxes[i], boxes[j])) all_pairs_.Add(i, j);
    }
  }
  all_pairs_.Finish();
}

const PairCollector& BroadPhase::LastCollector() const {
  switch (last_used_) {
    case BroadPhaseType::kSweepAndPrune: return sweep_and_prune_.Collector();
    case BroadPhaseType::kUniformGrid: return uniform_grid_.Collector();
    case BroadPhaseType::kQuadtree: return quadtree_.Collector();
    case BroadPhaseType::kAabbTree: return aabb_tree_.Collector();
    default: return all_pairs_;
  }
}

void BroadPhase::FindPairs(BroadPhaseType type, std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                           std::span<const PairQuota> quotas) {
  if (type != BroadPhaseType::kAuto) {
    auto_on_grid_ = false;
    auto_previous_.clear();
  }
  last_used_ = type;
  switch (type) {
    case BroadPhaseType::kAuto: FindPairsAuto(boxes, pairs, quotas); break;
    case BroadPhaseType::kAllPairs: FindPairsAllPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kSweepAndPrune: sweep_and_prune_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kUniformGrid: uniform_grid_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kQuadtree: quadtree_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kAabbTree: aabb_tree_.FindPairs(boxes, pairs, quotas); break;
  }
}

namespace {

// Calls the grid keeps the automatic choice before motion is checked again (a second at 60 Hz):
// every return to the tree reinserts what moved meanwhile, so flipping back and forth costs.
constexpr int kGridMinCalls = 60;

}  // namespace

void BroadPhase::FindPairsAuto(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                               std::span<const PairQuota> quotas) {
  const std::size_t n = boxes.size();
  if (n <= kAllPairsMaxBodies) {
    last_used_ = BroadPhaseType::kAllPairs;
    FindPairsAllPairs(boxes, pairs, quotas);
    return;
  }
  if (auto_on_grid_ && ++auto_grid_calls_ > kGridMinCalls && auto_previous_.size() == n) {
    // Back to the tree once few boxes still move by more than a sliver of their size per call:
    // those are the ones the tree would reinsert every few calls.
    std::size_t moving = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const AABB& now = boxes[i];
      const AABB& before = auto_previous_[i];
      const double size = std::max(now.upper.x - now.lower.x, now.upper.y - now.lower.y);
      const double dx = (now.lower.x + now.upper.x) - (before.lower.x + before.upper.x);
      const double dy = (now.lower.y + now.upper.y) - (before.lower.y + before.upper.y);
      moving += 0.5 * std::max(std::abs(dx), std::abs(dy)) > 0.02 * size;
    }
    auto_on_grid_ = 8 * moving > n;
    if (!auto_on_grid_) {
      // The tree last saw the boxes before the motion: their displacement since is no motion
      // to stretch fat boxes for, and reinserting what moved is no sign of motion now.
      aabb_tree_.ForgetMotion();
      auto_tree_bodies_ = 0;
    }
  }
  if (auto_on_grid_) {
    last_used_ = BroadPhaseType::kUniformGrid;
    uniform_grid_.FindPairs(boxes, pairs, quotas);
    auto_previous_.assign(boxes.begin(), boxes.end());
    return;
  }
  // New bodies are inserted, not moved: only a call on the same bodies measures motion.
  const bool same_bodies = auto_tree_bodies_ == n;
  auto_tree_bodies_ = n;
  last_used_ = BroadPhaseType::kAabbTree;
  aabb_tree_.FindPairs(boxes, pairs, quotas);
  if (same_bodies && 4 * aabb_tree_.LastReinsertCount() > n) {
    auto_on_grid_ = true;
    auto_grid_calls_ = 0;
    auto_previous_.assign(boxes.begin(), boxes.end());
  }
}

}  // namespace engine
