// Broad phase: which bodies' bounding boxes overlap, reported as sorted id pairs.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "engine/math.h"

namespace engine {

enum class BroadPhaseType : std::uint8_t {
  /// All pairs for a handful of bodies; beyond, the AABB tree while bodies mostly stay inside
  /// their fat boxes (resting, settling) and the uniform grid while many move (see BroadPhase)
  kAuto,
  kAllPairs,
  kSweepAndPrune,
  kUniformGrid,
  kQuadtree,
  kAabbTree,
};

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

/// A uniform grid, hashed: each box goes into every cell it touches, and a pair is reported only
/// by the cell holding the lower corner of the two boxes' overlap, so a pair spanning several
/// shared cells comes out once. The cell size follows the boxes (twice their median extent) and is
/// chosen again only when the median drifts by more than a factor of two. Boxes that would touch
/// many cells (floors, walls) stay out of the cells and are tested on their own. O(n + pairs) for
/// similar-sized boxes. Pairs come out sorted by (a, b).
class UniformGrid {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

  /// m; 0 before the first call.
  double CellSize() const { return cell_size_; }
  /// Boxes the last call kept out of the cells because they touch too many.
  std::size_t LargeCount() const { return large_.size(); }

 private:
  struct CellRange {
    std::int32_t x0, y0, x1, y1;
  };
  struct Entry {
    AABB box;
    std::int32_t x, y;  ///< the cell
    std::uint32_t body;
    std::uint8_t first;  ///< bit 0: the box's leftmost column of cells; bit 1: its bottom row
  };
  bool CellSizeFits(std::span<const AABB> boxes) const;
  void ChooseCellSize(std::span<const AABB> boxes);
  CellRange Cells(const AABB& box) const;
  std::uint32_t Bucket(std::int32_t x, std::int32_t y) const;
  void FindLargePairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs) const;

  double cell_size_ = 0.0;
  double inv_cell_size_ = 0.0;
  std::vector<CellRange> ranges_;       ///< per body
  std::vector<std::uint32_t> large_;    ///< bodies tested on their own, in id order
  std::vector<std::uint32_t> small_;    ///< bodies in the cells, in id order
  // The occupied cells' bounds; when they hold few cells more than entries, buckets are the cells
  // themselves (dense), otherwise a hash of the cell picks the bucket.
  CellRange occupied_{};
  bool dense_ = false;
  std::uint32_t hash_shift_ = 0;
  std::vector<std::uint32_t> bucket_start_;
  std::vector<Entry> entries_;
  std::vector<double> extent_scratch_;
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
};

/// A quadtree built top-down each step from reused buffers: a node with more than a few boxes
/// splits into four quadrants at the centre of its boxes' centres, down to a bounded depth. A box
/// goes into every quadrant it touches; a pair is reported only by the node whose region holds the
/// lower corner of the pair's overlap, so it comes out once. A box big for its node that straddles
/// the split stays in the node and is tested against the whole subtree. Pairs come out sorted.
class Quadtree {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

  /// The deepest node the last call made (the root is 0).
  int LastDepth() const { return last_depth_; }

  /// A node with more boxes splits (16 measured a little faster than 4, 8 or 32 on bench_broadphase).
  static constexpr std::size_t kLeafCapacity = 16;
  static constexpr int kMaxDepth = 24;

 private:
  struct Region {
    Vec2 lower;  ///< inclusive; -inf at the outer edge
    Vec2 upper;  ///< exclusive; +inf at the outer edge
  };
  struct Item {
    AABB box;
    std::uint32_t body;
  };
  /// What a node needs of its boxes to split: the bounds of their centres and of the boxes,
  /// each box clipped to the node's region.
  struct Bounds {
    Vec2 centre_lower, centre_upper, lower, upper;
    void Add(const AABB& box, const Region& region);
  };
  void Build(int depth, const Region& region, std::size_t begin, std::size_t end, const Bounds& bounds);
  void TestAllPairs(const Region& region, const Item* items, std::size_t count);

  std::vector<BodyPair>* pairs_ = nullptr;
  /// levels_[d] holds the items of the nodes at depth d being worked on: the four children of one
  /// node, side by side.
  std::vector<std::vector<Item>> levels_;
  std::vector<Item> residents_;
  std::vector<std::uint8_t> quadrants_;
  int last_depth_ = 0;
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
};

/// A dynamic AABB tree (after Box2D's b2DynamicTree, Erin Catto): one leaf per body holding a
/// fattened box, internal nodes holding the union of their children, improved by rotations.
/// A body is removed and reinserted only when its box leaves its fat box, so a step of small
/// motions touches few nodes. The pairs of overlapping fat boxes are kept from step to step and
/// found again only for reinserted bodies (by a query each, or one traversal of the tree against
/// itself when many moved); an exact test of the bodies' own boxes picks the pairs. Deterministic:
/// node slots come from a free list, new bodies are inserted and moved ones reinserted in id
/// order. Pairs come out sorted by (a, b).
class AabbTree {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

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
  void RemoveLeaf(std::int32_t leaf);
  /// Refits unions and heights from `node` to the root, rotating where that shrinks a box.
  void RefitUpward(std::int32_t node);
  void Rotate(std::int32_t node);
  AABB FatBox(const AABB& box, const AABB& previous, bool* stretched) const;
  void Clear();
  /// Renumbers the nodes in depth-first order, so that a subtree sits together in memory.
  void Relayout();
  /// All pairs of leaves whose fat boxes overlap, by one traversal of the tree against itself.
  void FindAllCandidates();
  /// The same, from last call's list, by querying the tree for the moved leaves only.
  void UpdateCandidates();

  std::vector<Node> nodes_;
  std::vector<Node> relayout_scratch_;
  std::vector<std::int32_t> new_index_;
  std::int32_t root_ = kNull;
  std::int32_t free_list_ = kNull;
  std::vector<std::int32_t> leaf_of_;  ///< per body
  std::vector<AABB> previous_;         ///< each body's box at the last call, for its motion
  std::vector<std::pair<std::int32_t, std::int32_t>> stack_;
  std::vector<std::int32_t> query_stack_;
  /// Pairs of bodies whose fat boxes overlap, sorted by (a, b): a superset of the overlapping
  /// pairs that changes only where leaves moved.
  std::vector<BodyPair> candidates_;
  std::vector<BodyPair> fresh_;
  std::vector<std::uint8_t> moved_;          ///< per body: reinserted by this call
  std::vector<std::uint32_t> moved_list_;
  std::size_t reinserts_since_relayout_ = 0;
  bool forget_motion_ = false;
  std::size_t last_reinserts_ = 0;
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
};

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
  void FindPairs(BroadPhaseType type, std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

  /// The structure the last call used (never kAuto).
  BroadPhaseType LastUsed() const { return last_used_; }

  static constexpr std::size_t kAllPairsMaxBodies = 16;

 private:
  void FindPairsAuto(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

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
