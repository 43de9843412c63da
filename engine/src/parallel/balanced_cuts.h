// Where to cut a loop among threads whose parts cost unlike amounts per item, learned from the
// last call's times. Only for loops whose results do not depend on the cuts (each part writes
// its own results, joined in order): the cuts move the work between threads, never the bits.
// Internal to the engine.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <span>
#include <vector>

namespace engine::detail {

class BalancedCuts {
 public:
  /// Where part `part` of `parts` begins in `count` items (part == parts: count): even cuts
  /// until Learn has seen `parts` parts.
  std::size_t Cut(std::size_t part, std::size_t parts, std::size_t count) const {
    assert(part <= parts);
    if (fractions_.size() != parts + 1) return count * part / parts;
    return std::min(count, static_cast<std::size_t>(fractions_[part] * static_cast<double>(count)));
  }

  /// After a call whose part p covered [cuts[p], cuts[p + 1]) of cuts.back() items and took
  /// seconds[p]: the next call's cuts give each part the same share of the cost, were each
  /// stretch of the items to cost per item what it cost this time, moved half way there so that
  /// one noisy call cannot swing them.
  void Learn(std::span<const std::size_t> cuts, std::span<const double> seconds) {
    const std::size_t parts = seconds.size();
    assert(cuts.size() == parts + 1);
    const double count = static_cast<double>(cuts.back());
    double total = 0.0;
    for (const double s : seconds) total += s;
    if (count <= 0.0 || !(total > 0.0)) return;
    std::vector<double>& next = scratch_;
    next.assign(parts + 1, 1.0);
    next[0] = 0.0;
    // Walk the cost, part by part, placing each new cut where its share of the total is reached.
    std::size_t p = 0;
    double cost_before = 0.0;  // the cost of the parts before part p
    for (std::size_t k = 1; k < parts; ++k) {
      const double target = total * static_cast<double>(k) / static_cast<double>(parts);
      while (p + 1 < parts && cost_before + seconds[p] < target) cost_before += seconds[p++];
      const double begin = static_cast<double>(cuts[p]), length = static_cast<double>(cuts[p + 1] - cuts[p]);
      const double within = seconds[p] > 0.0 ? std::clamp((target - cost_before) / seconds[p], 0.0, 1.0) : 0.5;
      next[k] = (begin + within * length) / count;
    }
    if (fractions_.size() != parts + 1) {
      fractions_.resize(parts + 1);
      for (std::size_t k = 0; k <= parts; ++k) fractions_[k] = static_cast<double>(k) / static_cast<double>(parts);
    }
    for (std::size_t k = 1; k < parts; ++k) fractions_[k] = 0.5 * (fractions_[k] + next[k]);
  }

 private:
  std::vector<double> fractions_;  ///< per part, and one past: where it begins, as a share of the items
  std::vector<double> scratch_;
};

}  // namespace engine::detail
