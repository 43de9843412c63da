// The quadtree broad phase: nodes split into four quadrants beyond a few boxes, each pair reported
// by the one node whose region holds the lower corner of the pair's overlap.
//
// Why each pair comes out exactly once: a box is kept in the nodes it reaches (a leaf, or a node
// where it stays as a resident), whose half-open regions are disjoint and cover the box. The
// overlap's lower corner p lies in both boxes, so in exactly one kept node of each; those two nodes
// are nested, and the pair is reported only while testing in the deeper one's region.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "engine/broadphase.h"
#include "pair_sort.h"

namespace engine {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The quadrant bits: whether a box reaches the left (x below the split), right, bottom and top
// quadrants. A box at the split line itself belongs to the upper side, as the regions are
// half-open.
constexpr std::uint8_t kLeft = 1;
constexpr std::uint8_t kRight = 2;
constexpr std::uint8_t kBottom = 4;
constexpr std::uint8_t kTop = 8;

Vec2 OverlapCorner(const AABB& a, const AABB& b) {
  return {std::max(a.lower.x, b.lower.x), std::max(a.lower.y, b.lower.y)};
}

}  // namespace

void Quadtree::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
  pairs->clear();
  last_depth_ = 0;
  if (boxes.size() < 2) return;
  boxes_ = boxes;
  pairs_ = pairs;
  levels_.resize(kMaxDepth + 1);
  levels_[0].resize(boxes.size());
  std::iota(levels_[0].begin(), levels_[0].end(), 0u);
  Build(0, {{-kInf, -kInf}, {kInf, kInf}}, 0, boxes.size());
  detail::SortPairs(boxes.size(), pairs, &sorted_scratch_, &counts_);
}

void Quadtree::TestAllPairs(const Region& region, const std::uint32_t* items, std::size_t count) {
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const AABB& a = boxes_[items[i]];
    for (std::size_t j = i + 1; j < count; ++j) {
      const AABB& b = boxes_[items[j]];
      if (!Overlaps(a, b)) continue;
      const Vec2 p = OverlapCorner(a, b);
      if (p.x >= region.lower.x && p.x < region.upper.x && p.y >= region.lower.y && p.y < region.upper.y) {
        pairs_->push_back(detail::MakePair(items[i], items[j]));
      }
    }
  }
}

void Quadtree::Build(int depth, const Region& region, std::size_t begin, std::size_t end) {
  last_depth_ = std::max(last_depth_, depth);
  // Item lists keep ascending ids at every level, so leaf pairs come out as (smaller, larger).
  std::vector<std::uint32_t>& items = levels_[depth];
  const std::size_t count = end - begin;
  if (count <= kLeafCapacity || depth == kMaxDepth) {
    TestAllPairs(region, items.data() + begin, count);
    return;
  }

  // Split at the centre of the boxes' centres rather than of the region: the tree then follows
  // clusters, and a body flung far away costs one level instead of many.
  Vec2 centre_lower{kInf, kInf}, centre_upper{-kInf, -kInf};
  Vec2 union_lower{kInf, kInf}, union_upper{-kInf, -kInf};
  for (std::size_t k = begin; k < end; ++k) {
    const AABB& b = boxes_[items[k]];
    const Vec2 c = 0.5 * b.lower + 0.5 * b.upper;
    centre_lower = {std::min(centre_lower.x, c.x), std::min(centre_lower.y, c.y)};
    centre_upper = {std::max(centre_upper.x, c.x), std::max(centre_upper.y, c.y)};
    union_lower = {std::min(union_lower.x, b.lower.x), std::min(union_lower.y, b.lower.y)};
    union_upper = {std::max(union_upper.x, b.upper.x), std::max(union_upper.y, b.upper.y)};
  }
  const Vec2 mid{Clamp(0.5 * centre_lower.x + 0.5 * centre_upper.x, region.lower.x, region.upper.x),
                 Clamp(0.5 * centre_lower.y + 0.5 * centre_upper.y, region.lower.y, region.upper.y)};
  const double half_width = 0.5 * (union_upper.x - union_lower.x);
  const double half_height = 0.5 * (union_upper.y - union_lower.y);

  // A box reaching all four quadrants that is big for this node would be copied into every
  // descendant; it stays here as a resident instead and meets the whole subtree at once.
  quadrants_.resize(count);
  residents_.clear();
  std::size_t child_counts[4] = {0, 0, 0, 0};
  for (std::size_t k = begin; k < end; ++k) {
    const AABB& b = boxes_[items[k]];
    const auto q = static_cast<std::uint8_t>((b.lower.x < mid.x ? kLeft : 0) | (b.upper.x >= mid.x ? kRight : 0) |
                                             (b.lower.y < mid.y ? kBottom : 0) | (b.upper.y >= mid.y ? kTop : 0));
    const bool resident = q == (kLeft | kRight | kBottom | kTop) &&
                          (b.upper.x - b.lower.x >= half_width || b.upper.y - b.lower.y >= half_height);
    quadrants_[k - begin] = resident ? 0 : q;
    if (resident) {
      residents_.push_back(items[k]);
      continue;
    }
    child_counts[0] += (q & kLeft) && (q & kBottom);
    child_counts[1] += (q & kRight) && (q & kBottom);
    child_counts[2] += (q & kLeft) && (q & kTop);
    child_counts[3] += (q & kRight) && (q & kTop);
  }

  // Residents against each other and against every other box of the node.
  const std::size_t resident_count = residents_.size();
  if (resident_count > 0) {
    TestAllPairs(region, residents_.data(), resident_count);
    for (std::uint32_t r : residents_) {
      const AABB& a = boxes_[r];
      for (std::size_t k = begin; k < end; ++k) {
        if (quadrants_[k - begin] == 0) continue;
        const AABB& b = boxes_[items[k]];
        if (!Overlaps(a, b)) continue;
        const Vec2 p = OverlapCorner(a, b);
        if (p.x >= region.lower.x && p.x < region.upper.x && p.y >= region.lower.y && p.y < region.upper.y) {
          pairs_->push_back(detail::MakePair(r, items[k]));
        }
      }
    }
  }

  // When a split would not shrink the work (a clump of mutually overlapping boxes, or one side
  // receiving everything), this node is a leaf for the boxes that remain.
  const std::size_t rest = count - resident_count;
  const std::size_t largest = *std::max_element(child_counts, child_counts + 4);
  if (rest <= kLeafCapacity || largest == rest) {
    if (resident_count == 0) {
      TestAllPairs(region, items.data() + begin, count);
      return;
    }
    residents_.clear();
    for (std::size_t k = begin; k < end; ++k) {
      if (quadrants_[k - begin] != 0) residents_.push_back(items[k]);
    }
    TestAllPairs(region, residents_.data(), residents_.size());
    return;
  }

  // The four children's lists, side by side in the next level's buffer.
  std::vector<std::uint32_t>& next = levels_[depth + 1];
  next.clear();
  std::size_t child_begin[5];
  const std::uint8_t need[4] = {kLeft | kBottom, kRight | kBottom, kLeft | kTop, kRight | kTop};
  for (int c = 0; c < 4; ++c) {
    child_begin[c] = next.size();
    for (std::size_t k = begin; k < end; ++k) {
      if ((quadrants_[k - begin] & need[c]) == need[c]) next.push_back(items[k]);
    }
  }
  child_begin[4] = next.size();
  const Region children[4] = {
      {region.lower, mid},
      {{mid.x, region.lower.y}, {region.upper.x, mid.y}},
      {{region.lower.x, mid.y}, {mid.x, region.upper.y}},
      {mid, region.upper},
  };
  for (int c = 0; c < 4; ++c) {
    if (child_begin[c + 1] - child_begin[c] >= 2) Build(depth + 1, children[c], child_begin[c], child_begin[c + 1]);
  }
}

}  // namespace engine
