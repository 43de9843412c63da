// The pair budget every broad phase ends with, then the pairs sorted by (a, b), so that what the
// solver sees never depends on how the pairs were found.
#include "broad_phase/pair_collector.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "broad_phase/pair_sort.h"
#include "parallel/spin_barrier.h"
#include "parallel/worker_pool.h"

namespace engine {

namespace {

// Fewer pairs than this are added one at a time: handing them to the threads and back costs
// about what adding a few thousand does.
constexpr std::size_t kMinSharedPairs = 4096;

}  // namespace

void PairCollector::Begin(std::span<const AABB> boxes, std::span<const PairQuota> quotas,
                          std::vector<BodyPair>* pairs) {
  boxes_ = boxes;
  quotas_ = quotas;
  pairs_ = pairs;
  size_ = 0;
  crowd_of_.clear();
  crowd_body_.clear();
  kept_.clear();
  dropped_ = 0;
  most_charged_ = 0;
  sorted_from_ = sorted_to_ = 0;
  offered_ = 0;
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
      Push(MakePair(body, other));
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
  std::size_t write = 0;
  for (std::size_t k = 0; k < size_; ++k) {
    const BodyPair p = list_[k];
    const std::uint32_t c = Charged(p);
    if (crowd_of_[c] == kNone) {
      list_[write++] = p;
    } else {
      Keep(c, RankOf(c, OtherBody(p, c)));
    }
  }
  size_ = write;
  for (std::size_t list = 0; list < crowd_body_.size(); ++list) {
    const std::uint32_t body = crowd_body_[list];
    for (std::uint32_t k = 0; k < kCrowdPairs; ++k) {
      const std::uint32_t other = kept_[list * kCrowdPairs + k].other;
      if (other == kNone) break;
      Push(MakePair(body, other));
    }
  }
}

// Shared, each thread takes a part of the pairs of the runs joined, copies it into place and
// counts the pairs it charges to each body; then each takes a part of the bodies, adds up their
// charges and checks them against the quotas, and a part of the pairs, to check their order.
// With no body past its quota, every pair is kept, in the order Add would keep them: the same
// list. Otherwise (a crowd) the charges are taken back and the pairs go through Add.
//
// Unsorted runs are sorted as they are joined instead: each thread deals its part of the pairs
// out by the range of the bodies their a lies in (a range to each thread), and after a barrier
// sorts the pairs of its own range from every thread's deal into place (SortPairsInto), after
// the lower ranges' pairs. The list is the one Finish's sort would give ((a, b) orders any list
// of pairs one way), without the step's longest stretch on one thread: 62 kcyc a call of
// the 4 000-circle pour's 11 000 pairs. A thread's part of the runs is mostly the pairs it found
// (a grid's run is a stretch of its cells) and, where ids rise with height, of its own range: it
// reads little that the other core wrote.
void PairCollector::AddRuns(std::span<const std::span<const BodyPair>> runs, detail::WorkerPool* pool,
                            RunOrder order) {
  std::size_t total = 0;
  for (const std::span<const BodyPair> run : runs) total += run.size();
  const auto add_each = [&] {
    for (const std::span<const BodyPair> run : runs) {
      for (const BodyPair& p : run) Add(p.a, p.b);
    }
  };
  if (!pool || pool->Threads() == 1 || total < kMinSharedPairs || !crowd_body_.empty()) {
    add_each();
    return;
  }
  const auto threads = static_cast<std::size_t>(pool->Threads());
  const std::size_t first = size_;
  if (list_.size() < first + total) list_.resize(first + total);  // only its growth is zeroed
  size_ = first + total;
  BodyPair* const out = list_.data() + first;
  // visit(k, pair) for the pairs [total·t/T, total·(t+1)/T) of the runs joined.
  const auto for_share = [&](std::size_t t, auto&& visit) {
    const std::size_t begin = total * t / threads, end = total * (t + 1) / threads;
    std::size_t at = 0;  // where the run starts in the join
    for (const std::span<const BodyPair> run : runs) {
      for (std::size_t k = std::max(begin, at); k < std::min(end, at + run.size()); ++k) visit(k, run[k - at]);
      at += run.size();
      if (at >= end) break;
    }
  };
  const bool charging = !quotas_.empty();
  const std::size_t bodies = boxes_.size();
  thread_charges_.resize(threads);
  shares_.resize(threads);
  const bool sorting = order == RunOrder::kUnsorted;
  const auto range_begin = [&](std::size_t t) { return static_cast<std::uint32_t>(bodies * t / threads); };
  if (sorting) {
    assert(threads <= 256);  // a range's number fits range_of_'s byte
    thread_sorts_.resize(threads);
    range_of_.resize(bodies);
    for (std::size_t t = 0; t < threads; ++t) {
      std::fill(range_of_.begin() + range_begin(t), range_of_.begin() + range_begin(t + 1),
                static_cast<std::uint8_t>(t));
    }
  }
  detail::SpinBarrier barrier(static_cast<int>(threads));
  pool->RunOnAll([&](int thread) {
    const auto t = static_cast<std::size_t>(thread);
    std::vector<std::uint32_t>& charges = thread_charges_[t].value;
    if (charging) charges.assign(bodies, 0);
    if (!sorting) {
      for_share(t, [&](std::size_t k, BodyPair found) {
        const BodyPair p = MakePair(found.a, found.b);
        out[k] = p;
        if (charging) ++charges[Charged(p)];
      });
      return;
    }
    ThreadSort& mine = thread_sorts_[t].value;
    const std::size_t room = total * (t + 1) / threads - total * t / threads;
    if (mine.boxes.size() < room * threads) mine.boxes.resize(room * threads);
    mine.box_counts.assign(threads, 0);
    for_share(t, [&](std::size_t, BodyPair found) {
      const BodyPair p = MakePair(found.a, found.b);
      const std::uint8_t range = range_of_[p.a];
      mine.boxes[range * room + mine.box_counts[range]++] = p;
      if (charging) ++charges[Charged(p)];
    });
    barrier.Wait();
    // Every thread's box for this thread's range, and how many pairs lie below the range.
    std::size_t below = 0;
    mine.parts.clear();
    for (std::size_t from = 0; from < threads; ++from) {
      const ThreadSort& deal = thread_sorts_[from].value;
      const std::size_t deal_room = total * (from + 1) / threads - total * from / threads;
      for (std::size_t range = 0; range < t; ++range) below += deal.box_counts[range];
      mine.parts.emplace_back(deal.boxes.data() + t * deal_room, deal.box_counts[t]);
    }
    detail::SortPairsInto(mine.parts, range_begin(t), range_begin(t + 1), bodies, out + below, &mine.scratch,
                          &mine.counts);
  });
  pool->RunOnAll([&](int thread) {
    const auto t = static_cast<std::size_t>(thread);
    Share share;
    if (charging) {
      for (std::size_t b = bodies * t / threads; b < bodies * (t + 1) / threads; ++b) {
        std::uint32_t c = charged_[b];
        for (const auto& charges : thread_charges_) c += charges.value[b];
        charged_[b] = c;
        share.fits = share.fits && c <= quotas_[b].quota;
        share.offered += c;
        share.most_charged = std::max(share.most_charged, c);
      }
    }
    const std::size_t begin = total * t / threads, end = total * (t + 1) / threads;
    share.sorted = sorting || std::is_sorted(out + (begin > 0 ? begin - 1 : 0), out + end);
    shares_[t].value = share;
  });
  Share all;
  for (const auto& share : shares_) {
    all.fits = all.fits && share.value.fits;
    all.sorted = all.sorted && share.value.sorted;
    all.offered += share.value.offered;
    all.most_charged = std::max(all.most_charged, share.value.most_charged);
  }
  if (!all.fits) {  // a crowd: the charges back, and one pair at a time
    for (std::size_t b = 0; b < bodies; ++b) {
      for (const auto& charges : thread_charges_) charged_[b] -= charges.value[b];
    }
    size_ = first;
    add_each();
    return;
  }
  if (all.sorted) {
    sorted_from_ = first;
    sorted_to_ = first + total;
  }
  offered_ = all.offered;
  most_charged_ = all.most_charged;
}

void PairCollector::Finish() {
  // AddRuns' tallies hold while nothing came after it.
  const bool tallied = sorted_to_ == size_ && sorted_to_ > 0 && crowd_body_.empty();
  if (!quotas_.empty()) {
    std::uint64_t offered = offered_;
    if (!tallied) {
      offered = 0;
      for (std::uint32_t c : charged_) {
        offered += c;
        most_charged_ = std::max(most_charged_, c);
      }
    }
    if (!crowd_body_.empty()) {
      KeepCrowdsBest();
      sorted_from_ = sorted_to_ = 0;
    }
    dropped_ = offered - size_;
  }
  list_.resize(size_);  // shorter or as long: nothing is zeroed
  // The tree finds its pairs in order already (but for a crowded body's, KeepCrowdsBest's);
  // what AddRuns saw in order is not looked at again.
  const auto in_order = [&](std::size_t begin, std::size_t end) {
    return end <= begin + 1 || std::is_sorted(list_.begin() + static_cast<std::ptrdiff_t>(begin),
                                              list_.begin() + static_cast<std::ptrdiff_t>(end));
  };
  const bool sorted = sorted_to_ > sorted_from_
                          ? in_order(0, sorted_from_ + 1) && in_order(sorted_to_ - 1, size_)
                          : in_order(0, size_);
  if (!sorted) detail::SortPairs(boxes_.size(), &list_, &scratch_, &counts_);
  // The caller's list takes these pairs; its old elements are the next call's to write over.
  pairs_->swap(list_);
}

}  // namespace engine
