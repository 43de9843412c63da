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

// The body a row moves: the upper one, or b of two on one level (both move).
BodyIndex MovedBody(const ShockRow& row) { return row.inv_mass_b != 0.0 ? row.b : row.a; }

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
void ShockSchedule::AssignBands(std::span<const ShockRow> rows, std::size_t body_count) {
  const std::size_t n = rows.size();
  const auto bands = static_cast<std::size_t>(bands_);
  shares_.Reset(body_count, bands_);
  const auto share_of = [&](BodyIndex body) { return static_cast<std::uint32_t>(shares_.Of(body)); };
  band_of_.resize(n);
  touches_.resize(n);
  crossings_.clear();
  band_start_.assign(bands + 1, 0);
  for (std::uint32_t r = 0; r < n; ++r) {
    const ShockRow& row = rows[r];
    touches_[r] = {row.a, row.b, row.inv_mass_a != 0.0, row.inv_mass_b != 0.0};
    const std::uint32_t share_a = share_of(row.a), share_b = share_of(row.b);
    const std::uint32_t band = MovedBody(row) == row.b ? share_b : share_a;
    band_of_[r] = band;
    ++band_start_[band + 1];
    if (share_a != share_b) crossings_.push_back(r);
  }
  for (std::size_t b = 0; b < bands; ++b) band_start_[b + 1] += band_start_[b];
  band_rows_.resize(n);
  position_of_.resize(n);
  fill_.assign(band_start_.begin(), band_start_.end() - 1);
  for (std::uint32_t r = 0; r < n; ++r) {
    const std::uint32_t band = band_of_[r];
    position_of_[r] = fill_[band] - band_start_[band];
    band_rows_[fill_[band]++] = r;
  }
}

// The waits: before a row reads a body another band's earlier row wrote, or writes a body
// another band's earlier row touched. Only bodies that some row moves and rows of two bands
// touch can need one; the rest are passed over. A wait that an earlier wait of the same band on
// the same band covers is left out.
void ShockSchedule::FindWaits(std::size_t body_count) {
  const std::size_t n = touches_.size();
  const auto bands = static_cast<std::size_t>(bands_);
  awaited_.assign(n, 0);
  waits_by_band_.resize(bands);
  for (auto& waits : waits_by_band_) waits.clear();
  if (crossings_.empty()) return;  // every body touched by one band alone
  // The crossings' bodies, then every row that touches one, in row order, and which bands touch
  // and write each of those bodies.
  crossing_body_.assign(body_count, 0);
  for (const std::uint32_t r : crossings_) crossing_body_[touches_[r].a] = crossing_body_[touches_[r].b] = 1;
  touched_by_.assign(body_count, 0);
  written_by_.assign(body_count, 0);
  rows_touching_.clear();
  for (std::uint32_t r = 0; r < n; ++r) {
    const Touch& row = touches_[r];
    if (!crossing_body_[row.a] && !crossing_body_[row.b]) continue;
    rows_touching_.push_back(r);
    const std::uint64_t bit = std::uint64_t{1} << band_of_[r];
    touched_by_[row.a] |= bit;
    touched_by_[row.b] |= bit;
    if (row.writes_a) written_by_[row.a] |= bit;
    if (row.writes_b) written_by_[row.b] |= bit;
  }
  const auto shared = [&](BodyIndex body) {
    const std::uint64_t t = touched_by_[body];
    return written_by_[body] != 0 && (t & (t - 1)) != 0;
  };
  last_write_.assign(body_count, kNone);
  last_touch_.assign(body_count * bands, kNone);
  waited_.assign(bands * bands, kNone);
  need_.resize(bands);
  for (const std::uint32_t r : rows_touching_) {  // the others touch no body two bands touch
    const Touch& row = touches_[r];
    const std::uint32_t band = band_of_[r];
    const std::uint32_t position = position_of_[r];
    const bool share[2] = {shared(row.a), shared(row.b)};
    if (!share[0] && !share[1]) continue;
    std::fill(need_.begin(), need_.end(), kNone);
    const auto need_row = [&](std::uint32_t other_row) {
      if (other_row == kNone) return;
      const std::uint32_t other = band_of_[other_row];
      if (other != band && (need_[other] == kNone || other_row > need_[other])) need_[other] = other_row;
    };
    const BodyIndex bodies[2] = {row.a, row.b};
    const bool writes[2] = {row.writes_a, row.writes_b};
    for (int k = 0; k < 2; ++k) {
      if (!share[k]) continue;
      need_row(last_write_[bodies[k]]);
      if (writes[k]) {
        for (std::size_t other = 0; other < bands; ++other) need_row(last_touch_[bodies[k] * bands + other]);
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
      last_touch_[bodies[k] * bands + band] = r;
      if (writes[k]) last_write_[bodies[k]] = r;
    }
  }
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
