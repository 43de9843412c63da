// The pair budget every broad phase ends with, then the pairs sorted by (a, b), so that what the
// solver sees never depends on how the pairs were found.
#include "broad_phase/pair_collector.h"

#include <algorithm>
#include <cmath>

#include "broad_phase/pair_sort.h"

namespace engine {

void PairCollector::Begin(std::span<const AABB> boxes, std::span<const PairQuota> quotas,
                          std::vector<BodyPair>* pairs) {
  boxes_ = boxes;
  quotas_ = quotas;
  pairs_ = pairs;
  pairs->clear();
  crowd_of_.clear();
  crowd_body_.clear();
  kept_.clear();
  dropped_ = 0;
  most_charged_ = 0;
  if (!quotas.empty()) charged_.assign(boxes.size(), 0);
}

PairCollector::Rank PairCollector::RankOf(std::uint32_t body, std::uint32_t other) const {
  const AABB& b = boxes_[body];
  const AABB& o = boxes_[other];
  const double x = std::min(b.upper.x, o.upper.x) - std::max(b.lower.x, o.lower.x);
  const double y = std::min(b.upper.y, o.upper.y) - std::max(b.lower.y, o.lower.y);
  return {!std::isinf(quotas_[other].width), -std::min(x, y), other < body ? body - other : other - body, other};
}

void PairCollector::Keep(std::uint32_t body, const Rank& rank) {
  Rank* list = kept_.data() + std::size_t{crowd_of_[body]} * kCrowdPairs;
  if (!(rank < list[kCrowdPairs - 1])) return;
  std::uint32_t k = kCrowdPairs - 1;
  for (; k > 0 && rank < list[k - 1]; --k) list[k] = list[k - 1];
  list[k] = rank;
}

std::uint32_t PairCollector::GrownQuota(std::uint32_t body) const {
  const AABB& box = boxes_[body];
  const double growth = (box.upper.x - box.lower.x) * (box.upper.y - box.lower.y) / quotas_[body].area;
  // A NaN (a body of no area) or a growth past the limit both give the limit.
  const double quota = std::ceil(quotas_[body].quota * growth);
  return quota < PairQuota::kMaxQuota ? static_cast<std::uint32_t>(quota) : PairQuota::kMaxQuota;
}

void PairCollector::AddPastQuota(std::uint32_t body, std::uint32_t other) {
  if (crowd_of_.empty()) crowd_of_.assign(boxes_.size(), kNone);
  if (crowd_of_[body] == kNone) {
    // Only bodies past their own quota get here, few outside a pile: the grown quota is worked
    // out for them alone, each time (it only depends on the box).
    if (charged_[body] <= GrownQuota(body)) {
      pairs_->push_back(MakePair(body, other));
      return;
    }
    crowd_of_[body] = static_cast<std::uint32_t>(crowd_body_.size());
    crowd_body_.push_back(body);
    const Rank last{true, std::numeric_limits<double>::infinity(), kNone, kNone};
    kept_.insert(kept_.end(), kCrowdPairs, last);
  }
  Keep(body, RankOf(body, other));
}

void PairCollector::KeepCrowdsBest() {
  std::vector<BodyPair>& pairs = *pairs_;
  std::size_t write = 0;
  for (const BodyPair& p : pairs) {
    const std::uint32_t c = Charged(p);
    if (crowd_of_[c] == kNone) {
      pairs[write++] = p;
    } else {
      Keep(c, RankOf(c, OtherBody(p, c)));
    }
  }
  pairs.resize(write);
  for (std::size_t list = 0; list < crowd_body_.size(); ++list) {
    const std::uint32_t body = crowd_body_[list];
    for (std::uint32_t k = 0; k < kCrowdPairs; ++k) {
      const std::uint32_t other = kept_[list * kCrowdPairs + k].other;
      if (other == kNone) break;
      pairs.push_back(MakePair(body, other));
    }
  }
}

void PairCollector::Finish() {
  if (!quotas_.empty()) {
    std::uint64_t offered = 0;
    for (std::uint32_t c : charged_) {
      offered += c;
      most_charged_ = std::max(most_charged_, c);
    }
    if (!crowd_body_.empty()) KeepCrowdsBest();
    dropped_ = offered - pairs_->size();
  }
  // The tree finds its pairs in order already (but for a crowded body's, KeepCrowdsBest's).
  if (!std::is_sorted(pairs_->begin(), pairs_->end())) detail::SortPairs(boxes_.size(), pairs_, &scratch_, &counts_);
}

}  // namespace engine
