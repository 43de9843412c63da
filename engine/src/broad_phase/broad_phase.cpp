// BroadPhase: the call to the chosen structure, and the automatic choice between all pairs, the
// AABB tree and the uniform grid.
#include "broad_phase/broad_phase.h"

#include <algorithm>
#include <cmath>

namespace engine {

namespace {

// Calls the grid keeps the automatic choice before motion is checked again (a second at 60 Hz):
// every return to the tree reinserts what moved meanwhile, so flipping back and forth costs.
constexpr int kGridMinCalls = 60;

// Whether more than `most` boxes moved their centre by more than 2% of their size since
// `before`: the ones the tree would reinsert every few calls. Looked at in blocks, the count
// without a branch, and given up once past `most` (a count of all took 9.4 kcyc a step of
// bench_threads' window of the 4 000-circle pour, where the grid is looked at in 37 steps of 60;
// given up, 4.9-6.4).
bool MoreMovingThan(std::span<const AABB> boxes, std::span<const AABB> before, std::size_t most) {
  constexpr std::size_t kBlock = 64;
  std::size_t moving = 0;
  for (std::size_t block = 0; block < boxes.size(); block += kBlock) {
    for (std::size_t i = block; i < std::min(boxes.size(), block + kBlock); ++i) {
      const AABB& now = boxes[i];
      const AABB& then = before[i];
      const double size = std::max(now.upper.x - now.lower.x, now.upper.y - now.lower.y);
      const double dx = (now.lower.x + now.upper.x) - (then.lower.x + then.upper.x);
      const double dy = (now.lower.y + now.upper.y) - (then.lower.y + then.upper.y);
      moving += 0.5 * std::max(std::abs(dx), std::abs(dy)) > 0.02 * size;
    }
    if (moving > most) return true;
  }
  return false;
}

}  // namespace

const PairCollector& BroadPhase::LastCollector() const {
  switch (last_used_) {
    case BroadPhaseType::kSweepAndPrune: return sweep_and_prune_.Collector();
    case BroadPhaseType::kUniformGrid: return uniform_grid_.Collector();
    case BroadPhaseType::kQuadtree: return quadtree_.Collector();
    case BroadPhaseType::kAabbTree: return aabb_tree_.Collector();
    default: return all_pairs_.Collector();
  }
}

void BroadPhase::FindPairs(BroadPhaseType type, std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                           std::span<const PairQuota> quotas, detail::WorkerPool* pool) {
  if (type != BroadPhaseType::kAuto) {
    auto_on_grid_ = false;
    auto_previous_.clear();
  }
  last_used_ = type;
  switch (type) {
    case BroadPhaseType::kAuto: FindPairsAuto(boxes, pairs, quotas, pool); break;
    case BroadPhaseType::kAllPairs: all_pairs_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kSweepAndPrune: sweep_and_prune_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kUniformGrid: uniform_grid_.FindPairs(boxes, pairs, quotas, pool); break;
    case BroadPhaseType::kQuadtree: quadtree_.FindPairs(boxes, pairs, quotas); break;
    case BroadPhaseType::kAabbTree: aabb_tree_.FindPairs(boxes, pairs, quotas, pool); break;
  }
}

void BroadPhase::FindPairsAuto(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                               std::span<const PairQuota> quotas, detail::WorkerPool* pool) {
  const std::size_t n = boxes.size();
  if (n <= kAllPairsMaxBodies) {
    last_used_ = BroadPhaseType::kAllPairs;
    all_pairs_.FindPairs(boxes, pairs, quotas);
    return;
  }
  if (auto_on_grid_ && ++auto_grid_calls_ > kGridMinCalls && auto_previous_.size() == n) {
    // Back to the tree once few boxes still move by more than a sliver of their size per call.
    auto_on_grid_ = MoreMovingThan(boxes, auto_previous_, n / 8);
    if (!auto_on_grid_) {
      // The tree last saw the boxes before the motion: their displacement since is no motion
      // to stretch fat boxes for, and reinserting what moved is no sign of motion now.
      aabb_tree_.ForgetMotion();
      auto_tree_bodies_ = 0;
    }
  }
  if (auto_on_grid_) {
    last_used_ = BroadPhaseType::kUniformGrid;
    uniform_grid_.FindPairs(boxes, pairs, quotas, pool);
    auto_previous_.assign(boxes.begin(), boxes.end());
    return;
  }
  FindPairsAutoTree(boxes, pairs, quotas, pool);
}

// The tree, and a switch to the grid when it reinserted more than a quarter of the bodies.
void BroadPhase::FindPairsAutoTree(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                                   std::span<const PairQuota> quotas, detail::WorkerPool* pool) {
  const std::size_t n = boxes.size();
  // New bodies are inserted, not moved: only a call on the same bodies measures motion.
  const bool same_bodies = auto_tree_bodies_ == n;
  auto_tree_bodies_ = n;
  last_used_ = BroadPhaseType::kAabbTree;
  aabb_tree_.FindPairs(boxes, pairs, quotas, pool);
  if (same_bodies && 4 * aabb_tree_.LastReinsertCount() > n) {
    auto_on_grid_ = true;
    auto_grid_calls_ = 0;
    auto_previous_.assign(boxes.begin(), boxes.end());
  }
}

}  // namespace engine
