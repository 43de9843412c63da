// All pairs: the n(n - 1)/2 tests, in (i, j) order, so the pairs come out already sorted.
#include "broad_phase/all_pairs.h"

#include <cstdint>

namespace engine {

namespace {

template <typename Report>
void ForEachOverlappingPair(std::span<const AABB> boxes, Report report) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (Overlaps(boxes[i], boxes[j])) report(i, j);
    }
  }
}

}  // namespace

void FindPairsAllPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
  pairs->clear();
  ForEachOverlappingPair(boxes, [pairs](std::uint32_t i, std::uint32_t j) { pairs->push_back(MakePair(i, j)); });
}

void AllPairs::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                         std::span<const PairQuota> quotas) {
  collector_.Begin(boxes, quotas, pairs);
  ForEachOverlappingPair(boxes, [this](std::uint32_t i, std::uint32_t j) { collector_.Add(i, j); });
  collector_.Finish();
}

}  // namespace engine
