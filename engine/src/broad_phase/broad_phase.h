// The broad phase: which bodies' bounding boxes overlap, reported as sorted id pairs. BroadPhase
// holds every structure and picks one per call, or lets the automatic choice pick; this header
// brings in each of them and the pair budget.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/aabb_tree.h"
#include "broad_phase/all_pairs.h"
#include "broad_phase/pair_collector.h"
#include "broad_phase/quadtree.h"
#include "broad_phase/sweep_and_prune.h"
#include "broad_phase/uniform_grid.h"
#include "engine/math.h"
#include "engine/world_def.h"

namespace engine {

/// Every broad phase behind one call, each keeping its state from call to call, and the automatic
/// choice. Whatever the choice, the pairs are the same; only the time differs.
///
/// kAuto: all pairs up to kAllPairsMaxBodies boxes. Beyond, the AABB tree, which costs almost
/// nothing while boxes stay inside their fat boxes; when a call reinserts more than a quarter of
/// the bodies, the uniform grid (linear, no state to update) takes over for at least a second of
/// calls (60), until a call sees at most an eighth of the boxes move by more than 2% of their size
/// since the last call. Deterministic: the switch depends on the boxes only. The numbers behind
/// the rule: docs/broadphase.md.
class BroadPhase {
 public:
  /// `quotas`: empty (every pair), or one per box (the pair budget, see PairCollector).
  /// `pool`: threads the uniform grid and the AABB tree may share their searches among (the
  /// others run on the caller).
  void FindPairs(BroadPhaseType type, std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {}, detail::WorkerPool* pool = nullptr);

  /// The structure the last call used (never kAuto).
  BroadPhaseType LastUsed() const { return last_used_; }
  /// The pair budget's account of the last call.
  const PairCollector& LastCollector() const;

  static constexpr std::size_t kAllPairsMaxBodies = 16;

 private:
  void FindPairsAuto(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                     std::span<const PairQuota> quotas, detail::WorkerPool* pool);
  void FindPairsAutoTree(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                         std::span<const PairQuota> quotas, detail::WorkerPool* pool);

  AllPairs all_pairs_;
  SweepAndPrune sweep_and_prune_;
  UniformGrid uniform_grid_;
  Quadtree quadtree_;
  AabbTree aabb_tree_;
  BroadPhaseType last_used_ = BroadPhaseType::kAllPairs;
  bool auto_on_grid_ = false;
  int auto_grid_calls_ = 0;  ///< calls since the grid took over
  std::size_t auto_tree_bodies_ = 0;  ///< how many boxes the tree had at its last automatic call
  std::vector<AABB> auto_previous_;  ///< the boxes at the last call, while the grid runs
};

}  // namespace engine
