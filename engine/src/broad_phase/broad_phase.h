// Broad phase: which bodies' bounding boxes overlap, reported as sorted id pairs.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "body_pair.h"
#include "engine/math.h"
#include "engine/world_def.h"

namespace engine {

/// Every overlapping pair by testing all of them: the reference, and the fastest for a handful
/// of boxes. Pairs come out sorted by (a, b).
void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs);

/// Per body, what the pair budget needs to know (World fills it in from the shapes).
struct PairQuota {
  /// The body's narrowest width, m: a circle's diameter, a box's shorter side; +infinity for a
  /// static body, which is never charged for a pair with a moving one.
  double width;
  /// How many pairs charged to the body it keeps in full while its box is its own size; past
  /// that it is in a crowd.
  std::uint32_t quota;
  /// m², the area of the body's own (unturned) bounding box. A box the broad phase is given grown
  /// beyond it meets others in proportion to its area, and the quota grows in the same proportion,
  /// up to kMaxQuota.
  double area;

  static constexpr std::uint32_t kMaxQuota = 256;
};

/// The pair budget, the one place that bounds what a broad phase reports, so that every broad
/// phase keeps exactly the same pairs. Each pair is charged to its narrower body (between equal
/// widths, the one with the higher id). A body charged with no more pairs than its quota keeps
/// them all; one charged with more is in a crowd that solid bodies cannot form (bodies piled at
/// one point) and keeps only its kCrowdPairs best: static partners first, then the deepest
/// overlap of the two boxes, then the lower id. Which pairs survive depends on the boxes alone,
/// never on the order a broad phase finds them in. A crowded body's pairs past its quota go
/// straight to a list of its kCrowdPairs best, so the collector never holds more than its quota
/// (plus that list) for a body, and n bodies piled at one point cost O(n) memory (the time stays O(n²) while every pair overlaps: each is
/// still looked at). docs/limits.md has the numbers. Without quotas the collector only sorts.
/// Pairs come out sorted by (a, b).
class PairCollector {
 public:
  /// What a body in a crowd keeps.
  static constexpr std::uint32_t kCrowdPairs = 4;

  /// Starts a call: `pairs` is cleared and filled by Add; `quotas` is empty or one per box.
  void Begin(std::span<const AABB> boxes, std::span<const PairQuota> quotas, std::vector<BodyPair>* pairs);
  void Add(std::uint32_t i, std::uint32_t j) {
    const BodyPair p = MakePair(i, j);
    if (quotas_.empty()) {
      pairs_->push_back(p);
      return;
    }
    const std::uint32_t charged = Charged(p);
    if (++charged_[charged] <= quotas_[charged].quota) {
      pairs_->push_back(p);
    } else {
      AddPastQuota(charged, p.a == charged ? p.b : p.a);
    }
  }
  /// Applies the budget and sorts the pairs by (a, b).
  void Finish();

  /// Bodies past their quota in the last call (0 whenever nothing is piled up).
  std::size_t CrowdedCount() const { return crowd_body_.size(); }
  /// The bodies past their quota in the last call, in the order they got there.
  std::span<const std::uint32_t> CrowdedBodies() const { return crowd_body_; }
  /// Pairs the budget left out in the last call.
  std::uint64_t DroppedCount() const { return dropped_; }
  /// The most pairs charged to one body in the last call (0 without quotas).
  std::uint32_t MostCharged() const { return most_charged_; }

 private:
  /// How a crowded body ranks a partner, best first: static partners, then the deepest overlap
  /// of the two boxes (the lesser of the two axes), then the lower id. A strict order, so the
  /// kept set is the same whatever order the pairs come in.
  struct Rank {
    bool moving;
    double shallowness;  ///< minus the overlap, m
    std::uint32_t id_distance;
    std::uint32_t other;
    friend bool operator<(const Rank& p, const Rank& q) {
      if (p.moving != q.moving) return q.moving;
      if (p.shallowness != q.shallowness) return p.shallowness < q.shallowness;
      if (p.id_distance != q.id_distance) return p.id_distance < q.id_distance;
      return p.other < q.other;
    }
  };
  std::uint32_t Charged(BodyPair p) const { return quotas_[p.a].width < quotas_[p.b].width ? p.a : p.b; }
  Rank RankOf(std::uint32_t body, std::uint32_t other) const;
  /// The quota for `body`'s box as given: its own, grown with the box's area.
  std::uint32_t GrownQuota(std::uint32_t body) const;
  /// A pair past `body`'s own quota: kept while within the grown quota, past that into the list
  /// of its best, if it ranks there.
  void AddPastQuota(std::uint32_t body, std::uint32_t other);
  void Keep(std::uint32_t body, const Rank& rank);

  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  std::span<const AABB> boxes_;
  std::span<const PairQuota> quotas_;
  std::vector<BodyPair>* pairs_ = nullptr;
  std::vector<std::uint32_t> charged_;  ///< per body: pairs charged to it in this call
  std::vector<std::uint32_t> crowd_of_;  ///< per body, once any is crowded: its list, or kNone
  std::vector<std::uint32_t> crowd_body_;  ///< per list: its body
  /// kCrowdPairs per crowded body, best first; the unused ends rank last.
  std::vector<Rank> kept_;
  std::uint64_t dropped_ = 0;
  std::uint32_t most_charged_ = 0;
  std::vector<BodyPair> scratch_;
  std::vector<std::uint32_t> counts_;
};

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
  void Rebuild(std::span<const AABB> boxes);

  std::vector<Endpoint> endpoints_;
  std::vector<ActiveInterval> active_;
  std::vector<std::uint32_t> active_slot_;  ///< where each open body sits in active_
  PairCollector collector_;
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
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});
  const PairCollector& Collector() const { return collector_; }

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
  void FindLargePairs(std::span<const AABB> boxes);

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
  PairCollector collector_;
};

/// A quadtree built top-down each step from reused buffers: a node with more than a few boxes
/// splits into four quadrants at the centre of its boxes' centres, down to a bounded depth. A box
/// goes into every quadrant it touches; a pair is reported only by the node whose region holds the
/// lower corner of the pair's overlap, so it comes out once. A box big for its node that straddles
/// the split stays in the node and is tested against the whole subtree. Pairs come out sorted.
class Quadtree {
 public:
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});
  const PairCollector& Collector() const { return collector_; }

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

  /// levels_[d] holds the items of the nodes at depth d being worked on: the four children of one
  /// node, side by side.
  std::vector<std::vector<Item>> levels_;
  std::vector<Item> residents_;
  std::vector<std::uint8_t> quadrants_;
  int last_depth_ = 0;
  PairCollector collector_;
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
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});
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
  void RemoveLeaf(std::int32_t leaf);
  /// Refits unions and heights from `node` to the root, rotating where that shrinks a box.
  void RefitUpward(std::int32_t node);
  void Rotate(std::int32_t node);
  AABB FatBox(const AABB& box, const AABB& previous, bool* stretched) const;
  void Clear();
  /// Renumbers the nodes in depth-first order, so that a subtree sits together in memory.
  void Relayout();
  /// All pairs of leaves whose fat boxes overlap, by one traversal of the tree against itself;
  /// past the candidate limit the pairs go straight to the collector and the tree is crowded.
  void FindAllCandidates(std::span<const AABB> boxes);
  /// The same, from last call's list, by querying the tree for the moved leaves only; false when
  /// the list would outgrow the candidate limit (the caller then traverses the whole tree).
  bool UpdateCandidates();
  std::size_t CandidateLimit() const;

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
  bool crowded_ = false;
  std::vector<BodyPair> sorted_scratch_;
  std::vector<std::uint32_t> counts_;
  PairCollector collector_;
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
  /// `quotas`: empty (every pair), or one per box (the pair budget, see PairCollector).
  void FindPairs(BroadPhaseType type, std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {});

  /// The structure the last call used (never kAuto).
  BroadPhaseType LastUsed() const { return last_used_; }
  /// The pair budget's account of the last call.
  const PairCollector& LastCollector() const;

  static constexpr std::size_t kAllPairsMaxBodies = 16;

 private:
  void FindPairsAuto(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                     std::span<const PairQuota> quotas);
  void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                         std::span<const PairQuota> quotas);

  PairCollector all_pairs_;
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
