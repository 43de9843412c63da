// The bands, the waits between them, and the pass that honours them.
#include "solver/shock_schedule.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "parallel/spin_wait.h"

namespace engine::detail {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
// How many rows' gaps a waiting band works out between looks at the row it waits for.
constexpr std::uint32_t kGapsBetweenLooks = 16;

}  // namespace

void ShockSchedule::Plan(std::span<const ShockRow> rows, std::size_t body_count, int threads) {
  bands_ = rows.size() < kMinSharedShockRows ? 1 : std::min(threads, kMaxShockBands);
  if (bands_ == 1) return;
  const auto bands = static_cast<std::size_t>(bands_);
  if (progress_count_ < bands) {
    progress_ = std::make_unique<Progress[]>(bands);
    progress_count_ = bands;
  }
  AssignBands(rows, body_count);
  FindWaits(body_count);
  // The last row of each band that touches a body of another band's share: awaited, so that
  // its band reports passing it.
  last_touch_of_share_.assign(bands * bands, kNone);
  for (const std::uint32_t r : crossings_) {
    const Touch& row = touches_[r];
    const std::uint32_t band = band_of_[r];
    for (const BodyIndex body : {row.a, row.b}) {
      const auto share = static_cast<std::size_t>(shares_.Of(body));
      if (share != band) last_touch_of_share_[share * bands + band] = r;  // crossings_ ascend
    }
  }
  for (const std::uint32_t r : last_touch_of_share_) {
    if (r != kNone) awaited_[r] = 1;
  }
}

// Each row to the band whose share of the bodies holds the body it moves; each band's rows in
// row order. A row whose two bodies lie in two shares is a crossing: only its bodies can be
// touched by two bands (a row touching a body of one share that crosses nowhere moves a body of
// the same share, so it is in that share's band).
//
// The bands' counts and places are kept in registers through each run of rows of one band (in
// a pile whose ids rise with its height, the rows go in long runs of one band): a count in
// memory, bumped every row, had each row wait for the last one's store.
void ShockSchedule::AssignBands(std::span<const ShockRow> rows, std::size_t body_count) {
  const auto n = static_cast<std::uint32_t>(rows.size());
  const auto bands = static_cast<std::size_t>(bands_);
  shares_.Reset(body_count, bands_);
  const auto share_of = [&](BodyIndex body) { return static_cast<std::uint32_t>(shares_.Of(body)); };
  band_of_.resize(n);
  touches_.resize(n);
  crossings_.clear();
  band_start_.assign(bands + 1, 0);
  std::uint32_t run_band = 0, run_length = 0;
  for (std::uint32_t r = 0; r < n; ++r) {
    const ShockRow& row = rows[r];
    // The body a row moves: the upper one, or b of two on one level (both move).
    const bool moves_b = row.inv_mass_b != 0.0;
    touches_[r] = {row.a, row.b, row.inv_mass_a != 0.0, moves_b};
    const std::uint32_t share_a = share_of(row.a), share_b = share_of(row.b);
    // Chosen by arithmetic, not a branch: which body of a row is the upper one is as good as
    // random along the rows.
    const std::uint32_t band = share_a + (share_b - share_a) * static_cast<std::uint32_t>(moves_b);
    band_of_[r] = band;
    if (band != run_band) {
      band_start_[run_band + 1] += run_length;
      run_band = band;
      run_length = 0;
    }
    ++run_length;
    if (share_a != share_b) crossings_.push_back(r);
  }
  band_start_[run_band + 1] += run_length;
  for (std::size_t b = 0; b < bands; ++b) band_start_[b + 1] += band_start_[b];
  band_rows_.resize(n);
  position_of_.resize(n);
  fill_.assign(band_start_.begin(), band_start_.end() - 1);
  run_band = 0;
  std::uint32_t fill = fill_[0];
  for (std::uint32_t r = 0; r < n; ++r) {
    const std::uint32_t band = band_of_[r];
    if (band != run_band) {
      fill_[run_band] = fill;
      run_band = band;
      fill = fill_[band];
    }
    position_of_[r] = fill - band_start_[run_band];
    band_rows_[fill++] = r;
  }
}

// The waits: before a row reads a body another band's earlier row wrote, or writes a body
// another band's earlier row touched. Only bodies that some row moves and rows of two bands
// touch can need one; the rest are passed over. A wait that an earlier wait of the same band on
// the same band covers is left out.
//
// The crossings' bodies (a few dozen to a few hundred) are numbered, and what the search keeps
// for a body is kept by that number: per body of the world it would fill and clear arrays of
// every body every step, for the few it reads.
void ShockSchedule::FindWaits(std::size_t body_count) {
  const std::size_t n = touches_.size();
  const auto bands = static_cast<std::size_t>(bands_);
  awaited_.assign(n, 0);
  waits_by_band_.resize(bands);
  for (auto& waits : waits_by_band_) waits.clear();
  if (crossings_.empty()) return;  // every body touched by one band alone
  // The crossings' bodies, numbered from 1 (0: none), then every row that touches one, in row
  // order, and which bands touch and write each of those bodies.
  slot_of_.resize(body_count, 0);  // all 0 between steps: the bodies numbered are cleared below
  slot_bodies_.clear();
  const auto number = [&](BodyIndex body) {
    if (slot_of_[body] != 0) return;
    slot_bodies_.push_back(body);
    slot_of_[body] = static_cast<std::uint32_t>(slot_bodies_.size());
  };
  for (const std::uint32_t r : crossings_) {
    number(touches_[r].a);
    number(touches_[r].b);
  }
  const std::size_t slots = slot_bodies_.size() + 1;
  touched_by_.assign(slots, 0);
  written_by_.assign(slots, 0);
  rows_touching_.clear();
  for (std::uint32_t r = 0; r < n; ++r) {
    const Touch& row = touches_[r];
    const std::uint32_t slot_a = slot_of_[row.a], slot_b = slot_of_[row.b];
    if ((slot_a | slot_b) == 0) continue;
    rows_touching_.push_back(r);
    const std::uint64_t bit = std::uint64_t{1} << band_of_[r];
    // Slot 0 gathers the bits of the bodies that are not numbered, and is never read.
    touched_by_[slot_a] |= bit;
    touched_by_[slot_b] |= bit;
    if (row.writes_a) written_by_[slot_a] |= bit;
    if (row.writes_b) written_by_[slot_b] |= bit;
  }
  const auto shared = [&](std::uint32_t slot) {
    const std::uint64_t t = touched_by_[slot];
    return slot != 0 && written_by_[slot] != 0 && (t & (t - 1)) != 0;
  };
  last_write_.assign(slots, kNone);
  last_touch_.assign(slots * bands, kNone);
  waited_.assign(bands * bands, kNone);
  need_.resize(bands);
  for (const std::uint32_t r : rows_touching_) {  // the others touch no body two bands touch
    const Touch& row = touches_[r];
    const std::uint32_t band = band_of_[r];
    const std::uint32_t position = position_of_[r];
    const std::uint32_t slot[2] = {slot_of_[row.a], slot_of_[row.b]};
    const bool share[2] = {shared(slot[0]), shared(slot[1])};
    if (!share[0] && !share[1]) continue;
    std::fill(need_.begin(), need_.end(), kNone);
    const auto need_row = [&](std::uint32_t other_row) {
      if (other_row == kNone) return;
      const std::uint32_t other = band_of_[other_row];
      if (other != band && (need_[other] == kNone || other_row > need_[other])) need_[other] = other_row;
    };
    const bool writes[2] = {row.writes_a, row.writes_b};
    for (int k = 0; k < 2; ++k) {
      if (!share[k]) continue;
      need_row(last_write_[slot[k]]);
      if (writes[k]) {
        for (std::size_t other = 0; other < bands; ++other) need_row(last_touch_[slot[k] * bands + other]);
      }
    }
    for (std::size_t other = 0; other < bands; ++other) {
      std::uint32_t& covered = waited_[band * bands + other];
      if (need_[other] == kNone || (covered != kNone && need_[other] <= covered)) continue;
      covered = need_[other];
      awaited_[need_[other]] = 1;
      waits_by_band_[band].push_back({position, static_cast<std::uint32_t>(other), need_[other]});
    }
    for (int k = 0; k < 2; ++k) {
      if (!share[k]) continue;
      last_touch_[slot[k] * bands + band] = r;
      if (writes[k]) last_write_[slot[k]] = r;
    }
  }
  for (const BodyIndex body : slot_bodies_) slot_of_[body] = 0;
}

std::size_t ShockSchedule::WaitCount() const {
  if (bands_ == 1) return 0;
  std::size_t count = 0;
  for (const std::vector<Wait>& waits : waits_by_band_) count += waits.size();
  return count;
}

void ShockSchedule::Run(WorkerPool& pool, std::span<const ShockRow> rows, std::span<BodyState> states,
                        std::span<const Vec2> moved, double inv_h, double linear_slop, JobRef after) {
  assert(!after || SharedAmong(pool));
  if (bands_ == 1 || pool.Threads() < bands_) {
    form_.Saw(PropagateShock(rows, states, moved, inv_h, linear_slop, form_.BranchFree()), rows.size());
    return;
  }
  for (int band = 0; band < bands_; ++band) progress_[band].next.store(0, std::memory_order_relaxed);
  gaps_.resize(rows.size());
  const auto run_band = [&]<bool kBranchFree>(int band) {
    const std::vector<Wait>& waits = waits_by_band_[static_cast<std::size_t>(band)];
    auto wait = waits.begin();
    std::atomic<std::uint32_t>& mine = progress_[band].next;
    const std::uint32_t first = band_start_[band], past = band_start_[band + 1];
    // While a band waits for another's rows (a pile's ids rise with its height, and so do the
    // bands: the later ones wait for the rows below theirs), it works out the gaps of the rows
    // ahead of it, a third of a row's work: [first, gapped) are known.
    std::uint32_t gapped = first;
    std::uint32_t position = 0;
    PushChanges changes;
    for (std::uint32_t k = first; k < past; ++k, ++position) {
      for (; wait != waits.end() && wait->position == position; ++wait) {
        const std::atomic<std::uint32_t>& theirs = progress_[wait->thread].next;
        const std::uint32_t row = wait->row;
        const auto passed = [&] { return theirs.load(std::memory_order_acquire) > row; };
        gapped = std::max(gapped, k);
        while (!passed()) {
          if (gapped == past) {
            SpinThenWait(theirs, passed);
            break;
          }
          const std::uint32_t end = std::min(past, gapped + kGapsBetweenLooks);
          for (; gapped < end; ++gapped) gaps_[gapped] = GapOf(rows[band_rows_[gapped]], moved, inv_h, linear_slop);
        }
      }
      const std::uint32_t r = band_rows_[k];
      const ShockGap gap = k < gapped ? gaps_[k] : GapOf(rows[r], moved, inv_h, linear_slop);
      changes.Add(PushRow<kBranchFree>(rows[r], gap, states));
      if (awaited_[r]) {
        mine.store(r + 1, std::memory_order_release);
        mine.notify_all();
      }
    }
    progress_[band].push_changes = changes.count;
    if (!after) return;
    for (int other = 0; other < bands_; ++other) {
      const std::uint32_t row = last_touch_of_share_[static_cast<std::size_t>(band * bands_ + other)];
      if (row == kNone) continue;
      const std::atomic<std::uint32_t>& theirs = progress_[other].next;
      SpinThenWait(theirs, [&] { return theirs.load(std::memory_order_acquire) > row; });
    }
    after(band);
  };
  const bool branch_free = form_.BranchFree();
  pool.RunOnAll([&](int band) {
    if (band >= bands_) return;
    if (branch_free) {
      run_band.template operator()<true>(band);
    } else {
      run_band.template operator()<false>(band);
    }
  });
  std::size_t changes = 0;
  for (int band = 0; band < bands_; ++band) changes += progress_[band].push_changes;
  form_.Saw(changes, rows.size());
}

}  // namespace engine::detail
