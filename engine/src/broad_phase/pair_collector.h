// The pair budget: PairCollector, where every broad phase hands its pairs, and PairQuota, what it
// needs to know of each body. It bounds what a pile of bodies costs and sorts the pairs by (a, b).
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/math.h"
#include "parallel/per_thread.h"

namespace engine::detail {
class WorkerPool;
}

namespace engine {

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
/// (plus that list) for a body, and n bodies piled at one point cost O(n) memory (the time stays
/// O(n²) while every pair overlaps: each is still looked at). docs/limits.md has the numbers.
/// Without quotas the collector only sorts. Pairs come out sorted by (a, b).
class PairCollector {
 public:
  /// What a body in a crowd keeps.
  static constexpr std::uint32_t kCrowdPairs = 4;

  /// Starts a call whose pairs Finish hands to `pairs` (whatever it held is dropped); `quotas`
  /// is empty or one per box.
  void Begin(std::span<const AABB> boxes, std::span<const PairQuota> quotas, std::vector<BodyPair>* pairs);
  void Add(std::uint32_t i, std::uint32_t j) {
    const BodyPair p = MakePair(i, j);
    if (quotas_.empty()) {
      Push(p);
      return;
    }
    const std::uint32_t charged = Charged(p);
    if (++charged_[charged] <= quotas_[charged].quota) {
      Push(p);
    } else {
      AddPastQuota(charged, OtherBody(p, charged));
    }
  }
  /// How the pairs of AddRuns' runs come: joined in order already, as the tree finds them (but
  /// where it is checked), or in no order, as the grid's buckets give them.
  enum class RunOrder { kMostlySorted, kUnsorted };
  /// The pairs of `runs`, run after run, as Add would take them one at a time; shared among the
  /// pool's threads (PairCollector::AddRuns in pair_collector.cpp says how). Unsorted runs are
  /// sorted there, by the threads, each its own range of a.
  void AddRuns(std::span<const std::span<const BodyPair>> runs, detail::WorkerPool* pool,
               RunOrder order = RunOrder::kMostlySorted);
  /// Applies the budget, sorts the pairs by (a, b) and hands them to Begin's `pairs`.
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
  /// Puts a pair at the list's end.
  void Push(BodyPair p) {
    if (size_ < list_.size()) {
      list_[size_] = p;
    } else {
      list_.push_back(p);
    }
    ++size_;
  }
  static std::uint32_t OtherBody(BodyPair p, std::uint32_t body) { return p.a == body ? p.b : p.a; }
  std::uint32_t Charged(BodyPair p) const { return quotas_[p.a].width < quotas_[p.b].width ? p.a : p.b; }
  Rank RankOf(std::uint32_t body, std::uint32_t other) const;
  /// The quota for `body`'s box as given: its own, grown with the box's area.
  std::uint32_t GrownQuota(std::uint32_t body) const;
  /// A pair past `body`'s own quota: kept while within the grown quota, past that into the list
  /// of its best, if it ranks there.
  void AddPastQuota(std::uint32_t body, std::uint32_t other);
  void Keep(std::uint32_t body, const Rank& rank);
  /// Crowded bodies' pairs from before they were past their quota compete for their lists too;
  /// then each list's pairs replace them.
  void KeepCrowdsBest();

  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

  std::span<const AABB> boxes_;
  std::span<const PairQuota> quotas_;
  std::vector<BodyPair>* pairs_ = nullptr;  ///< where Finish puts the pairs
  /// The call's pairs, list_[0, size_): the list keeps its length from call to call (it swaps
  /// with Begin's `pairs` at Finish), so that AddRuns' threads write into it without its growth
  /// being zeroed first on one thread (cleared at Begin, the calling thread was alone 28-33 kcyc
  /// a step of the 4 000-circle pour on two threads before AddRuns' job; 9-12 since).
  std::vector<BodyPair> list_;
  std::size_t size_ = 0;
  std::vector<std::uint32_t> charged_;  ///< per body: pairs charged to it in this call
  std::vector<std::uint32_t> crowd_of_;  ///< per body, once any is crowded: its list, or kNone
  std::vector<std::uint32_t> crowd_body_;  ///< per list: its body
  /// kCrowdPairs per crowded body, best first; the unused ends rank last.
  std::vector<Rank> kept_;
  std::uint64_t dropped_ = 0;
  std::uint32_t most_charged_ = 0;
  std::vector<BodyPair> scratch_;
  std::vector<std::uint32_t> counts_;
  /// AddRuns' scratch: per thread, the pairs its runs charge to each body.
  std::vector<detail::PerThread<std::vector<std::uint32_t>>> thread_charges_;
  /// AddRuns' scratch for unsorted runs, per thread: its part of the pairs dealt out into a box
  /// per range of a (each box with room for the whole part), and the sort's buffers.
  struct ThreadSort {
    std::vector<BodyPair> boxes;
    std::vector<std::size_t> box_counts;
    std::vector<std::span<const BodyPair>> parts;
    std::vector<BodyPair> scratch;
    std::vector<std::uint32_t> counts;
  };
  std::vector<detail::PerThread<ThreadSort>> thread_sorts_;
  std::vector<std::uint8_t> range_of_;  ///< per body: the thread whose range of a holds it
  /// What AddRuns found on its threads, for Finish: per thread, whether its bodies fit their
  /// quotas and what they were charged, and whether its pairs are in order.
  struct Share {
    bool fits = true;
    bool sorted = true;
    std::uint64_t offered = 0;
    std::uint32_t most_charged = 0;
  };
  std::vector<detail::PerThread<Share>> shares_;
  /// list_[sorted_from_, sorted_to_) are known to be sorted, and when the list still ends at
  /// sorted_to_ with no crowd, offered_ and most_charged_ are the charges' (AddRuns').
  std::size_t sorted_from_ = 0, sorted_to_ = 0;
  std::uint64_t offered_ = 0;
};

}  // namespace engine
