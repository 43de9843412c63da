// Disjoint sets of body ids, for islands. Internal to the engine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace engine::detail {

/// Each set's root is its smallest member (a join keeps the smaller root), so the roots, and
/// whatever is ordered by them, never depend on the order of the joins.
class UnionFind {
 public:
  /// Every id from 0 to count − 1 in a set of its own.
  void Reset(std::size_t count) {
    parent_.resize(count);
    std::iota(parent_.begin(), parent_.end(), 0u);
  }
  /// The root of i's set (path halving on the way).
  std::uint32_t Find(std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t ra = Find(a), rb = Find(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace engine::detail
