// The groups of a colour order cut among threads by the bodies they move: each thread takes the
// constraints whose body lies in its share of the bodies, the share the passes over the bodies
// give it. Internal to the engine.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/ids.h"
#include "solver/contact_order.h"

namespace engine::detail {

/// Where thread t's share of `body_count` bodies among `threads` begins: as ForEachIndex cuts
/// the passes over the bodies (and a pool's ParallelFor), [n·t/T, n·(t+1)/T).
inline BodyIndex ShareBegin(std::size_t body_count, int threads, int t) {
  return static_cast<BodyIndex>(std::uint64_t{body_count} * static_cast<std::uint64_t>(t) /
                                static_cast<std::uint64_t>(threads));
}

/// The threads' shares of the bodies (ShareBegin's), found once: then the share that holds a
/// body read from a byte per body. (A division for each of the shock plan's rows had cost 86
/// kcyc a step of the 4 000-circle pour; a comparison with each share's start, which the
/// compiler made a loop of unknown length, 44 kcyc for the plan's `AssignBands` run twice in a
/// row, its second run, against 26 with the byte.)
class BodyShares {
 public:
  BodyShares() = default;
  BodyShares(std::size_t body_count, int threads) { Reset(body_count, threads); }
  void Reset(std::size_t body_count, int threads) {
    assert(threads >= 1 && threads <= 256);  // a share's number fits in a byte
    share_of_.resize(body_count);
    for (int t = 0; t < threads; ++t) {
      std::fill(share_of_.begin() + ShareBegin(body_count, threads, t),
                share_of_.begin() + ShareBegin(body_count, threads, t + 1), static_cast<std::uint8_t>(t));
    }
  }
  /// The thread whose share holds `body`.
  int Of(BodyIndex body) const { return share_of_[body]; }

 private:
  std::vector<std::uint8_t> share_of_;  ///< per body
};

/// Groups of fewer units than this go whole to the first thread: a meeting of the threads
/// (about a microsecond) would cost more than the few bodies such a group sends across. Not
/// tuned: in the 4 000-circle pour the groups it keeps whole hold one or two blocks, and the
/// one of 24 blocks it cuts (which had gone whole to the first thread) touches bodies of both
/// threads' shares.
inline constexpr std::uint32_t kMinCutGroupUnits = 8;

/// Each thread's part of each group of a colour order (in units: blocks of the wide solver), cut
/// by the body each unit's first constraint moves (its lead). Thread t takes the units whose lead
/// lies in [n·t/T, n·(t+1)/T) of the n bodies: what ForEachIndex gives thread t in the passes
/// over the bodies, so a body's lines stay in one core's cache from pass to pass. Cut instead in
/// the middle of each group's constraints, the cut fell at a different body in every group, and
/// the first thread took the contacts with the walls (whose ids come first) and the groups too
/// small to share: the bodies those touched went to the other core and back every pass.
///
/// Within a group the constraints are in pair order (by a, then b): the leads ascend within each
/// run of units whose a moves, and within each run whose a is one fixed body (then the lead is
/// b). Each run is cut apart, so a thread's part of a group is one range a run.
class BodyCut {
 public:
  struct Range {
    std::uint32_t begin;
    std::uint32_t end;
  };

  /// Cuts `order`'s groups for `threads` threads among `body_count` bodies. `lead_body[u]`: the
  /// body unit u's first constraint moves; `lead_fixed[u]`: its a where a is held fixed, else
  /// kNoBody. A group from order.parallel_groups on (it may share a body), or of fewer than
  /// kMinCutGroupUnits units, goes whole to the first thread.
  void Cut(const ContactOrder& order, std::span<const BodyIndex> lead_body, std::span<const BodyIndex> lead_fixed,
           std::size_t body_count, int threads);

  int Threads() const { return threads_; }
  std::size_t Groups() const { return whole_.size(); }
  /// Whether group g goes whole to the first thread.
  bool Whole(std::size_t g) const { return whole_[g] != 0; }
  /// Thread `thread`'s ranges of group g (none for a whole group but the first thread's).
  std::span<const Range> Part(std::size_t g, int thread) const {
    const std::size_t at = g * static_cast<std::size_t>(threads_) + static_cast<std::size_t>(thread);
    return std::span<const Range>(ranges_).subspan(first_[at], first_[at + 1] - first_[at]);
  }

 private:
  int threads_ = 1;
  std::vector<Range> ranges_;
  std::vector<std::uint32_t> first_;  ///< per (group, thread), and one past: where its ranges start
  std::vector<std::uint8_t> whole_;   ///< per group
  std::vector<std::vector<Range>> scratch_;  ///< per thread, the group's ranges being cut
};

}  // namespace engine::detail
