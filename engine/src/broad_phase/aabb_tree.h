// The dynamic AABB tree: a leaf per body with a fattened box, reinserted only when the body leaves
// it, and the pairs of overlapping fat boxes kept from call to call.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "body_pair.h"
#include "broad_phase/pair_collector.h"
#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"
#include "engine/math.h"

namespace engine {

/// A dynamic AABB tree (after Box2D's b2DynamicTree, Erin Catto): one leaf per body holding a
/// fattened box, internal nodes holding the union of their children, improved by rotations.
/// A body is removed and reinserted only when its box leaves its fat box, so a step of small
/// motions touches few nodes; when a quarter of the bodies or more moved, the tree is built anew
/// over all the fat boxes instead (median splits; Box2D v3 rebuilds what moved of its tree in the
/// same spirit). The pairs of overlapping fat boxes are kept from step to step and found again
/// only for reinserted bodies (by a query each, or one traversal of the tree against itself when
/// many moved); an exact test of the bodies' own boxes picks the pairs. Deterministic: node slots
/// come from a free list, new bodies are inserted and moved ones reinserted in id order, a new
/// tree's splits depend on the boxes alone. Pairs come out sorted by (a, b), and never depend on
/// the tree's shape.
class AabbTree {
 public:
  /// `pool`: threads to share the check of the kept candidates among (the pairs and the
  /// budget's choices are the same whatever the pool).
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {}, detail::WorkerPool* pool = nullptr);
  const PairCollector& Collector() const { return collector_; }
  /// True while the fat boxes overlap in more pairs than the tree keeps (kCandidatesPerBody a
  /// body): the pairs are then found by a traversal every call, and none are kept.
  bool Crowded() const { return crowded_; }
  static constexpr std::size_t kCandidatesPerBody = 16;

  /// Leaves removed and inserted again by the last call (new bodies included).
  std::size_t LastReinsertCount() const { return last_reinserts_; }
  /// The longest path from the root to a leaf (a single leaf is 0; -1 when empty).
  int Height() const;
  /// Checks parent links, unions and heights; for tests.
  bool IsValid() const;
  /// The next call predicts no motion from the boxes of the last one: for a caller that skipped
  /// calls while the boxes moved.
  void ForgetMotion() { forget_motion_ = true; }

 private:
  static constexpr std::int32_t kNull = -1;
  struct Node {
    AABB box;                    ///< leaves: the fat box; internal nodes: the union of children
    std::int32_t parent = kNull;
    std::int32_t child1 = kNull;  ///< kNull for a leaf
    std::int32_t child2 = kNull;
    std::int32_t height = 0;     ///< 0 for a leaf
    std::uint32_t body = 0;      ///< leaves only
    bool stretched = false;      ///< leaves only: the fat box reaches ahead of the body's motion
    bool IsLeaf() const { return child1 == kNull; }
  };
  std::int32_t Allocate();
  void Free(std::int32_t node);
  void InsertLeaf(std::int32_t leaf);
  /// Puts `leaf` next to its best sibling under `start`, with `parent` (a node out of the tree)
  /// as their parent; refits below `top`. `top_side` (0 or 1, where known): which of `top`'s
  /// children holds `start`, so that its link is written without reading the other's.
  void AttachLeaf(std::int32_t leaf, std::int32_t parent, std::int32_t start, std::int32_t top, int top_side = -1);
  /// The node under `start` whose pairing with `box` adds the least perimeter.
  std::int32_t FindBestSibling(const AABB& box, std::int32_t start) const;
  void RemoveLeaf(std::int32_t leaf);
  /// Takes a leaf (not the root) out of the tree, refits below `top`, and returns its parent
  /// node, now out of the tree too. `top_side`: as AttachLeaf's.
  std::int32_t DetachLeaf(std::int32_t leaf, std::int32_t top, int top_side = -1);
  /// `node`'s child link on `side` (0: child1, 1: child2).
  std::int32_t& ChildLink(std::int32_t node, int side) {
    return side == 0 ? nodes_[node].child1 : nodes_[node].child2;
  }
  std::int32_t ChildLink(std::int32_t node, int side) const {
    return side == 0 ? nodes_[node].child1 : nodes_[node].child2;
  }
  /// Refits unions and heights from `node` up to `top` (kNull: the root, included), rotating
  /// where that shrinks a box.
  void RefitUpward(std::int32_t node, std::int32_t top = kNull);
  void Rotate(std::int32_t node);
  AABB FatBox(const AABB& box, const AABB& previous, bool* stretched) const;
  void Clear();
  /// Renumbers the nodes in depth-first order, so that a subtree sits together in memory.
  void Relayout();
  /// Marks the bodies that left their fat boxes (or shed their motion), and the new ones, into
  /// moved_ and, in id order, moved_list_.
  void MarkMovedLeaves(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// Body i's box at the last call (or now, when the motion since is forgotten).
  const AABB& PreviousBox(std::span<const AABB> boxes, std::uint32_t i) const {
    return forget_motion_ ? boxes[i] : previous_[i];
  }
  /// Reinserts the marked bodies one by one, in id order, new ones with leaves of their own.
  void ReinsertMovedLeaves(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// Shared reinsertion: a subtree of the tree's top, `parent`'s child on `side`, whose moved
  /// bodies (branch_moved_, in id order) one thread takes back into it.
  struct Branch {
    std::int32_t parent;
    int side;
  };
  /// The branch's root: its parent's child on its side.
  std::int32_t BranchRoot(const Branch& branch) const { return ChildLink(branch.parent, branch.side); }
  /// Cuts the tree's top into about `count` branches (branches_; none for a tree too low).
  void FindBranches(std::size_t count);
  /// The moved bodies into their branches, or outside_moved_.
  void SortIntoBranches();
  void ReinsertInBranch(std::span<const AABB> boxes, const Branch& branch, std::span<const std::uint32_t> moved);
  /// A new tree over every body's fat box, the marked ones' made anew.
  void Rebuild(std::span<const AABB> boxes, detail::WorkerPool* pool);
  void BuildSubtree(std::uint32_t first, std::uint32_t last, std::int32_t index, std::int32_t parent,
                    detail::WorkerPool* pool);
  /// Brings the candidate pairs up to date with the moved leaves.
  /// True when it found the overlapping ones too (into found_, for CollectFound).
  bool RefreshCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// All pairs of leaves whose fat boxes overlap, by one traversal of the tree against itself;
  /// past the candidate limit the pairs go straight to the collector and the tree is crowded.
  void FindAllCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// The same traversal shared among the pool's threads; false when past the candidate limit.
  bool FindAllCandidatesShared(detail::WorkerPool& pool);
  template <typename Push, typename Found>
  void VisitNodePair(std::int32_t a, std::int32_t b, Push&& push, Found&& found) const;
  void AddCandidate(std::uint32_t a, std::uint32_t b, std::span<const AABB> boxes, std::size_t limit);
  /// The same, from last call's list, by querying the tree for the moved leaves only, with the
  /// overlapping ones into found_; false when the list would outgrow the candidate limit (the
  /// caller then traverses the whole tree).
  bool UpdateCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// Adds to `fresh` the pairs of moved body `body` with the leaves its fat box overlaps
  /// (`stack`: scratch).
  void QueryFreshPairs(std::uint32_t body, std::vector<std::int32_t>* stack, std::vector<BodyPair>* fresh) const;
  /// The candidates whose bodies' own boxes overlap, to the collector.
  void AddOverlappingCandidates(std::span<const AABB> boxes, detail::WorkerPool* pool);
  /// found_'s runs to the collector, in order.
  void CollectFound(detail::WorkerPool* pool);
  std::size_t CandidateLimit() const;

  std::vector<Node> nodes_;
  std::vector<Node> relayout_scratch_;
  std::vector<std::int32_t> new_index_;
  std::int32_t root_ = kNull;
  std::int32_t free_list_ = kNull;
  std::vector<std::int32_t> leaf_of_;  ///< per body
  std::vector<AABB> previous_;         ///< each body's box at the last call, for its motion
  std::vector<std::pair<std::int32_t, std::int32_t>> stack_;
  std::vector<std::pair<std::int32_t, std::int32_t>> node_pairs_;  ///< the shared traversal's starts
  /// A run of the shared traversal: its stack and the candidates it found.
  struct TraversalRun {
    std::vector<std::pair<std::int32_t, std::int32_t>> stack;
    std::vector<BodyPair> pairs;
  };
  std::vector<detail::PerThread<TraversalRun>> traversal_runs_;
  /// Rebuild's scratch: each body's leaf, and its box's centre (doubled) to split by.
  std::vector<Node> leaves_;
  struct BuildItem {
    Vec2 centre;
    std::uint32_t body;
  };
  std::vector<BuildItem> build_items_;
  /// Pairs of bodies whose fat boxes overlap, sorted by (a, b): a superset of the overlapping
  /// pairs that changes only where leaves moved.
  std::vector<BodyPair> candidates_;
  std::vector<BodyPair> fresh_;
  /// A thread's share of UpdateCandidates' queries.
  struct FreshRun {
    std::vector<std::int32_t> stack;
    std::vector<BodyPair> pairs;
    std::vector<BodyPair> sorted_scratch;  ///< SortPairs' buffers
    std::vector<std::uint32_t> counts;
  };
  std::vector<detail::PerThread<FreshRun>> fresh_runs_;
  std::vector<std::uint8_t> moved_;          ///< per body: reinserted by this call
  std::vector<std::uint32_t> moved_list_;
  std::vector<Branch> branches_;                 ///< shared reinsertion's
  std::vector<std::vector<std::uint32_t>> branch_moved_;  ///< per branch: its moved bodies
  std::vector<std::uint32_t> branch_order_;      ///< the branches, most moved bodies first
  std::vector<std::int32_t> branch_of_node_;     ///< per node: the branch it is the root of (-1: none)
  std::vector<std::uint32_t> outside_moved_;     ///< the moved bodies under no branch
  std::size_t reinserts_since_relayout_ = 0;
  bool forget_motion_ = false;
  std::size_t last_reinserts_ = 0;
  bool crowded_ = false;
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
  PairCollector collector_;
  /// A run's overlapping candidates: the first `count` of `pairs` (every pair tested is written
  /// there, the count advancing past the overlapping ones: OverlappingInto).
  struct FoundRun {
    std::vector<BodyPair> pairs;
    std::size_t count = 0;
  };
  std::vector<detail::PerThread<FoundRun>> found_;  ///< each run's overlapping candidates
  std::vector<std::span<const BodyPair>> found_runs_;  ///< found_'s, for the collector
  std::vector<detail::PerThread<std::vector<BodyPair>>> merged_;  ///< UpdateCandidates' runs' candidates
};

}  // namespace engine
