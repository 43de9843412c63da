// The quadtree broad phase: nodes split into four quadrants beyond a few boxes, each pair reported
// by the one node whose region holds the lower corner of the pair's overlap.
//
// Why each pair comes out exactly once: a box is kept in the nodes it reaches (a leaf, or a node
// where it stays as a resident), whose half-open regions are disjoint and cover the box. The
// overlap's lower corner p lies in both boxes, so in exactly one kept node of each; those two nodes
// are nested, and the pair is reported only while testing in the deeper one's region.
#include "broad_phase/quadtree.h"

#include <algorithm>
#include <limits>

namespace engine {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Vec2 kFar{kInf, kInf};

// The quadrant bits: whether a box reaches the left (x below the split), right, bottom and top
// quadrants. A box at the split line itself belongs to the upper side, as the regions are
// half-open.
constexpr std::uint8_t kLeft = 1;
constexpr std::uint8_t kRight = 2;
constexpr std::uint8_t kBottom = 4;
constexpr std::uint8_t kTop = 8;
constexpr std::uint8_t kAllQuadrants = kLeft | kRight | kBottom | kTop;
// The bits a box needs to go into each child, in ChildCounts order.
constexpr std::uint8_t kChildNeeds[4] = {kLeft | kBottom, kRight | kBottom, kLeft | kTop, kRight | kTop};

Vec2 OverlapCorner(const AABB& a, const AABB& b) {
  return {std::max(a.lower.x, b.lower.x), std::max(a.lower.y, b.lower.y)};
}

}  // namespace

// Boxes are clipped to the node's region first: a floor's or wall's centre lies far outside most
// nodes it reaches, and would pull the split point to the region's edge, where it splits nothing.
void Quadtree::Bounds::Add(const AABB& box, const Region& region) {
  const Vec2 low{std::max(box.lower.x, region.lower.x), std::max(box.lower.y, region.lower.y)};
  const Vec2 high{std::min(box.upper.x, region.upper.x), std::min(box.upper.y, region.upper.y)};
  const Vec2 c = 0.5 * low + 0.5 * high;
  centre_lower = {std::min(centre_lower.x, c.x), std::min(centre_lower.y, c.y)};
  centre_upper = {std::max(centre_upper.x, c.x), std::max(centre_upper.y, c.y)};
  lower = {std::min(lower.x, low.x), std::min(lower.y, low.y)};
  upper = {std::max(upper.x, high.x), std::max(upper.y, high.y)};
}

void Quadtree::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                         std::span<const PairQuota> quotas) {
  collector_.Begin(boxes, quotas, pairs);
  last_depth_ = 0;
  if (boxes.size() < 2) {
    collector_.Finish();
    return;
  }
  levels_.resize(kMaxDepth + 1);
  // Boxes are copied into the item lists, so each level reads its boxes in order.
  std::vector<Item>& root = levels_[0];
  root.resize(boxes.size());
  const Region everywhere{-kFar, kFar};
  Bounds bounds{kFar, -kFar, kFar, -kFar};
  for (std::uint32_t i = 0; i < boxes.size(); ++i) {
    root[i] = {boxes[i], i};
    bounds.Add(boxes[i], everywhere);
  }
  Build(0, everywhere, 0, boxes.size(), bounds);
  collector_.Finish();
}

bool Quadtree::Region::OwnsOverlap(const AABB& a, const AABB& b) const {
  return Overlaps(a, b) && Holds(OverlapCorner(a, b));
}

void Quadtree::TestAllPairs(const Region& region, const Item* items, std::size_t count) {
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const AABB& a = items[i].box;
    for (std::size_t j = i + 1; j < count; ++j) {
      if (region.OwnsOverlap(a, items[j].box)) collector_.Add(items[i].body, items[j].body);
    }
  }
}

void Quadtree::Build(int depth, const Region& region, std::size_t begin, std::size_t end, const Bounds& bounds) {
  last_depth_ = std::max(last_depth_, depth);
  const Item* items = levels_[depth].data() + begin;
  const std::size_t count = end - begin;
  if (count <= kLeafCapacity || depth == kMaxDepth) {
    TestAllPairs(region, items, count);
    return;
  }
  const Vec2 mid = SplitPoint(region, bounds);
  const ChildCounts child_counts = AssignQuadrants(items, count, mid, bounds);
  if (!residents_.empty()) TestResidents(region, items, count);

  // When a split would not shrink the work (a clump of mutually overlapping boxes, or one side
  // receiving everything), this node is a leaf for the boxes that remain.
  const std::size_t rest = count - residents_.size();
  const std::size_t largest = *std::max_element(child_counts.begin(), child_counts.end());
  if (rest <= kLeafCapacity || largest == rest) {
    TestRestAsLeaf(region, items, count);
    return;
  }
  BuildChildren(depth, region, mid, begin, count, child_counts);
}

// At the centre of the boxes' centres rather than of the region: the tree then follows clusters,
// and a body flung far away costs one level instead of many.
Vec2 Quadtree::SplitPoint(const Region& region, const Bounds& bounds) {
  return {Clamp(0.5 * bounds.centre_lower.x + 0.5 * bounds.centre_upper.x, region.lower.x, region.upper.x),
          Clamp(0.5 * bounds.centre_lower.y + 0.5 * bounds.centre_upper.y, region.lower.y, region.upper.y)};
}

// A box reaching all four quadrants that is big for this node would be copied into every
// descendant; it stays here as a resident instead and meets the whole subtree at once.
Quadtree::ChildCounts Quadtree::AssignQuadrants(const Item* items, std::size_t count, Vec2 mid,
                                                const Bounds& bounds) {
  const double half_width = 0.5 * (bounds.upper.x - bounds.lower.x);
  const double half_height = 0.5 * (bounds.upper.y - bounds.lower.y);
  quadrants_.resize(count);
  residents_.clear();
  // Counted in a local array, not in the returned one: that lives in memory the byte stores to
  // quadrants_ may alias, and every box would load and store the four counts (seen in the code).
  std::size_t child_counts[4] = {0, 0, 0, 0};
  for (std::size_t k = 0; k < count; ++k) {
    const AABB& b = items[k].box;
    const auto q = static_cast<std::uint8_t>((b.lower.x < mid.x ? kLeft : 0) | (b.upper.x >= mid.x ? kRight : 0) |
                                             (b.lower.y < mid.y ? kBottom : 0) | (b.upper.y >= mid.y ? kTop : 0));
    if (q == kAllQuadrants && (b.upper.x - b.lower.x >= half_width || b.upper.y - b.lower.y >= half_height)) {
      quadrants_[k] = 0;
      residents_.push_back(items[k]);
      continue;
    }
    quadrants_[k] = q;
    for (int c = 0; c < 4; ++c) child_counts[c] += (q & kChildNeeds[c]) == kChildNeeds[c];
  }
  return {child_counts[0], child_counts[1], child_counts[2], child_counts[3]};
}

// Residents against each other and against every other box of the node.
void Quadtree::TestResidents(const Region& region, const Item* items, std::size_t count) {
  TestAllPairs(region, residents_.data(), residents_.size());
  for (const Item& r : residents_) {
    for (std::size_t k = 0; k < count; ++k) {
      if (quadrants_[k] != 0 && region.OwnsOverlap(r.box, items[k].box)) collector_.Add(r.body, items[k].body);
    }
  }
}

// The residents have met everything already; the other boxes meet each other here.
void Quadtree::TestRestAsLeaf(const Region& region, const Item* items, std::size_t count) {
  if (residents_.empty()) {
    TestAllPairs(region, items, count);
    return;
  }
  residents_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    if (quadrants_[k] != 0) residents_.push_back(items[k]);
  }
  TestAllPairs(region, residents_.data(), residents_.size());
}

// The four children's items, side by side in the next level's buffer, with their bounds.
void Quadtree::BuildChildren(int depth, const Region& region, Vec2 mid, std::size_t begin, std::size_t count,
                             const ChildCounts& child_counts) {
  std::vector<Item>& next = levels_[depth + 1];
  next.resize(child_counts[0] + child_counts[1] + child_counts[2] + child_counts[3]);
  std::size_t child_begin[5] = {0, 0, 0, 0, 0};
  for (int c = 0; c < 4; ++c) child_begin[c + 1] = child_begin[c] + child_counts[c];
  std::size_t cursor[4] = {child_begin[0], child_begin[1], child_begin[2], child_begin[3]};
  const Region children[4] = {
      {region.lower, mid},
      {{mid.x, region.lower.y}, {region.upper.x, mid.y}},
      {{region.lower.x, mid.y}, {mid.x, region.upper.y}},
      {mid, region.upper},
  };
  Bounds child_bounds[4];
  for (Bounds& b : child_bounds) b = {kFar, -kFar, kFar, -kFar};
  const Item* items = levels_[depth].data() + begin;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint8_t q = quadrants_[k];
    for (int c = 0; c < 4; ++c) {
      if ((q & kChildNeeds[c]) != kChildNeeds[c]) continue;
      next[cursor[c]++] = items[k];
      child_bounds[c].Add(items[k].box, children[c]);
    }
  }
  for (int c = 0; c < 4; ++c) {
    if (child_counts[c] >= 2) Build(depth + 1, children[c], child_begin[c], child_begin[c + 1], child_bounds[c]);
  }
}

}  // namespace engine
