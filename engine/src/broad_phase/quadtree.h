// The quadtree: built top-down each call, nodes split into four beyond a few boxes, each pair
// reported by the one node whose region holds the lower corner of the pair's overlap.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/pair_collector.h"
#include "engine/math.h"

namespace engine {

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
    bool Holds(Vec2 p) const { return p.x >= lower.x && p.x < upper.x && p.y >= lower.y && p.y < upper.y; }
    /// Whether the node with this region reports the pair: the boxes overlap, and the lower corner
    /// of the overlap lies in the region.
    bool OwnsOverlap(const AABB& a, const AABB& b) const;
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
  /// Items per child: lower left, lower right, upper left, upper right.
  using ChildCounts = std::array<std::size_t, 4>;

  void Build(int depth, const Region& region, std::size_t begin, std::size_t end, const Bounds& bounds);
  static Vec2 SplitPoint(const Region& region, const Bounds& bounds);
  /// Fills quadrants_ and residents_ for the node's items; returns how many go to each child.
  ChildCounts AssignQuadrants(const Item* items, std::size_t count, Vec2 mid, const Bounds& bounds);
  void TestResidents(const Region& region, const Item* items, std::size_t count);
  void TestRestAsLeaf(const Region& region, const Item* items, std::size_t count);
  void BuildChildren(int depth, const Region& region, Vec2 mid, std::size_t begin, std::size_t count,
                     const ChildCounts& child_counts);
  void TestAllPairs(const Region& region, const Item* items, std::size_t count);

  /// levels_[d] holds the items of the nodes at depth d being worked on: the four children of one
  /// node, side by side.
  std::vector<std::vector<Item>> levels_;
  std::vector<Item> residents_;
  std::vector<std::uint8_t> quadrants_;  ///< per item of the node: the quadrant bits, 0 for a resident
  int last_depth_ = 0;
  PairCollector collector_;
};

}  // namespace engine
