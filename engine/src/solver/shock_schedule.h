// Shock propagation shared among threads with the bits of one: each thread takes the rows that
// move its share of the bodies (its band), in row order, and before a row that touches a body
// another thread's earlier row touched, waits until that thread is past it. Every body then meets
// its rows in row order, with the same values, whatever the number of threads. Internal to the
// engine.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/body.h"
#include "parallel/worker_pool.h"
#include "solver/body_cut.h"
#include "solver/shock_propagation.h"

namespace engine::detail {

/// Fewer rows than this go on one thread: a pass over them takes a few microseconds, about what
/// handing it out and waiting at the bands' borders costs.
inline constexpr std::size_t kMinSharedShockRows = 2048;
/// At most this many bands (a bit each in a mask); further threads sit the pass out.
inline constexpr int kMaxShockBands = 64;

class ShockSchedule {
 public:
  /// Once a step, after the rows are built (SortShockRows): the rows split into `threads` bands (at
  /// most kMaxShockBands) by the body each row moves (the upper one), a band to each thread's
  /// share of the bodies as every other pass cuts them (BodyShares), and the waits between them.
  /// With one thread or fewer than kMinSharedShockRows rows, the pass stays on the calling thread.
  ///
  /// Bands by the bodies' share, not by place: the passes before and after this one move each body
  /// on the thread whose share holds it, so its lines stay in that core's cache. Bands side by side
  /// in x (before 2026-11-29) let a pile's columns go in parallel, but half the rows then moved
  /// bodies another core had last written: the pass cost 524 kcyc a step of the 4 000-circle pour
  /// on two threads, and the moves after it 114, against 489 and 36 by share, though a pile whose
  /// ids rise with its height then goes band after band (its rows hold up the rows above).
  void Plan(std::span<const ShockRow> rows, std::size_t body_count, int threads);
  /// The band Plan gave row r (0 when the pass stays on one thread).
  std::uint32_t BandOf(std::size_t r) const { return bands_ == 1 ? 0 : band_of_[r]; }
  /// How many waits Plan found (0 when the pass stays on one thread).
  std::size_t WaitCount() const;
  /// Whether Run shares the rows among all of `pool`'s threads, a band to each thread and a
  /// thread's band the rows that move its share of the bodies (BodyShares).
  bool SharedAmong(const WorkerPool& pool) const { return bands_ > 1 && bands_ == pool.Threads(); }
  /// PropagateShock over the rows Plan saw, on the pool's threads. With SharedAmong(pool),
  /// `after` (if any) is called on each band's thread, with the band, once its band is done and
  /// no other band's row will touch a body of its share again: a pass over that share's bodies
  /// that reads their velocities and writes anything but the velocities and the moves `moved`
  /// holds for the others can go there, while the later bands still run.
  void Run(WorkerPool& pool, std::span<const ShockRow> rows, std::span<BodyState> states,
           std::span<const Vec2> moved, double inv_h, double linear_slop, JobRef after = {});

 private:
  /// Before the thread's row at `position` in its list, thread `thread` must be past row `row`.
  struct Wait {
    std::uint32_t position;
    std::uint32_t thread;
    std::uint32_t row;
  };
  /// A thread's progress (the row after the last one others wait on), a cache line to itself.
  struct alignas(64) Progress {
    std::atomic<std::uint32_t> next{0};
    std::size_t push_changes = 0;  ///< the band's PushChanges in the last pass
  };

  /// What FindWaits reads of a row: its bodies and which it writes (a sixth of a ShockRow).
  struct Touch {
    BodyIndex a;
    BodyIndex b;
    bool writes_a;
    bool writes_b;
  };

  void AssignBands(std::span<const ShockRow> rows, std::size_t body_count);
  void FindWaits(std::size_t body_count);

  int bands_ = 1;
  std::vector<std::uint32_t> band_rows_;   ///< each band's rows in row order, band after band
  std::vector<std::uint32_t> band_start_;  ///< per band: where its rows begin (one past: the end)
  std::vector<std::vector<Wait>> waits_by_band_;  ///< each band's, in position order
  std::vector<std::uint8_t> awaited_;      ///< per row: another thread waits on it
  /// [band × bands + other]: the last row of band `other` that touches a body of `band`'s share
  /// (kNone: none), which `band`'s thread waits past before Run's `after`.
  std::vector<std::uint32_t> last_touch_of_share_;
  std::vector<ShockGap> gaps_;             ///< per row, in band_rows_' order: its gap (Run)
  std::unique_ptr<Progress[]> progress_;
  ShockRowForm form_;                      ///< the next pass's form, from the last one's rows
  std::size_t progress_count_ = 0;
  // Plan's scratch, kept between steps.
  std::vector<std::uint32_t> band_of_, fill_, last_write_, last_touch_, waited_, need_;
  std::vector<std::uint32_t> position_of_;  ///< per row: its place in its band's list
  BodyShares shares_;                       ///< the bands' shares of the bodies
  std::vector<Touch> touches_;              ///< per row
  std::vector<std::uint32_t> crossings_;    ///< the rows whose bodies lie in two shares
  std::vector<std::uint32_t> slot_of_;      ///< per body: its number among the crossings' bodies (0: none)
  std::vector<BodyIndex> slot_bodies_;      ///< the crossings' bodies, by number from 1
  std::vector<std::uint32_t> rows_touching_;  ///< the rows that touch a crossing's body
  std::vector<std::uint64_t> touched_by_, written_by_;  ///< per crossing body's number: a bit per band
};

}  // namespace engine::detail
