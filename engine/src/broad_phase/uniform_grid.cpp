// The uniform-grid broad phase: boxes binned into square cells sized from the boxes, a pair
// reported once by the cell that holds the lower corner of its overlap.
#include "broad_phase/uniform_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace engine {

namespace {

// Cell coordinates are clamped here, so that far-away boxes stay countable in 64 bits. The clamp
// keeps the map from coordinates to cells monotone, which is all the one-cell rule needs.
constexpr double kCellLimit = 1 << 29;
// A box touching more cells than this is "large": binning it would cost more than testing it
// alone. With cells twice the median extent, a typical box touches one to four.
constexpr std::int64_t kMaxCellsPerBox = 16;
// Fewer entries than this are scanned on one thread, and fewer boxes measured and placed in cells
// on one: the hand-off would cost more.
constexpr std::size_t kMinSharedEntries = 4096;
constexpr std::uint32_t kMinSharedBoxes = 2048;
// A scan hands its pairs over (or checks them against the limit) once it holds this many.
constexpr std::size_t kPairsPerHandOff = 4096;
// Shared, a thread's pairs past this many an entry (and kPairsPerHandOff) stop its scan: solid
// boxes of one size give a few an entry; only boxes piled in a cell give more.
constexpr std::size_t kPairsPerEntry = 16;

double Extent(const AABB& box) { return std::max(box.upper.x - box.lower.x, box.upper.y - box.lower.y); }

}  // namespace

// The size is kept while the median extent stays within a factor of two of the one it was chosen
// for; the test costs a pass of comparisons (shared out in runs), a new choice a selection
// (nth_element).
bool UniformGrid::CellSizeFits(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  if (cell_size_ == 0.0) return false;
  const double median = 0.5 * cell_size_;
  const auto n = static_cast<std::uint32_t>(boxes.size());
  const std::uint32_t run = detail::RunLength(pool, n, kMinSharedBoxes);
  size_runs_.resize((n + run - 1) / run);
  detail::ForEachRun(pool, n, kMinSharedBoxes, run, [&](std::uint32_t begin, std::uint32_t end) {
    SizeRun& counts = size_runs_[begin / run].value;
    counts = {};
    for (std::uint32_t i = begin; i < end; ++i) {
      const double e = Extent(boxes[i]);
      counts.bigger += e > 2.0 * median;
      counts.smaller += e < 0.5 * median;
    }
  });
  std::size_t bigger = 0;
  std::size_t smaller = 0;
  for (const auto& counts : size_runs_) {
    bigger += counts.value.bigger;
    smaller += counts.value.smaller;
  }
  return 2 * bigger <= boxes.size() && 2 * smaller <= boxes.size();
}

void UniformGrid::ChooseCellSize(std::span<const AABB> boxes) {
  extent_scratch_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) extent_scratch_[i] = Extent(boxes[i]);
  const auto middle = extent_scratch_.begin() + static_cast<std::ptrdiff_t>(boxes.size() / 2);
  std::nth_element(extent_scratch_.begin(), middle, extent_scratch_.end());
  double size = 2.0 * *middle;
  if (!(size > 0.0 && std::isfinite(size))) {
    // Points (or nothing finite to go by): about one box per cell over the area they cover.
    AABB bounds = boxes[0];
    for (const AABB& box : boxes) {
      bounds.lower = {std::min(bounds.lower.x, box.lower.x), std::min(bounds.lower.y, box.lower.y)};
      bounds.upper = {std::max(bounds.upper.x, box.upper.x), std::max(bounds.upper.y, box.upper.y)};
    }
    size = Extent(bounds) / std::sqrt(static_cast<double>(boxes.size()));
    if (!(size > 0.0 && std::isfinite(size))) size = 1.0;
  }
  cell_size_ = size;
  inv_cell_size_ = 1.0 / size;
}

UniformGrid::CellRange UniformGrid::Cells(const AABB& box) const {
  auto cell = [this](double v) {
    const double c = std::floor(v * inv_cell_size_);
    if (!(c > -kCellLimit)) return static_cast<std::int32_t>(-kCellLimit);
    if (c > kCellLimit) return static_cast<std::int32_t>(kCellLimit);
    return static_cast<std::int32_t>(c);
  };
  return {cell(box.lower.x), cell(box.lower.y), cell(box.upper.x), cell(box.upper.y)};
}

std::uint32_t UniformGrid::Bucket(std::int32_t x, std::int32_t y) const {
  if (dense_) {
    const auto width = static_cast<std::uint32_t>(occupied_.x1 - occupied_.x0 + 1);
    return static_cast<std::uint32_t>(y - occupied_.y0) * width + static_cast<std::uint32_t>(x - occupied_.x0);
  }
  // Fibonacci hashing of the packed cell: neighbouring cells land in unrelated buckets.
  const std::uint64_t key = (std::uint64_t{static_cast<std::uint32_t>(x)} << 32) | static_cast<std::uint32_t>(y);
  return static_cast<std::uint32_t>((key * 0x9E3779B97F4A7C15ull) >> hash_shift_);
}

void UniformGrid::FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                            std::span<const PairQuota> quotas, detail::WorkerPool* pool) {
  collector_.Begin(boxes, quotas, pairs);
  large_.clear();
  small_.clear();
  if (boxes.size() < 2) {
    collector_.Finish();
    return;
  }
  if (!CellSizeFits(boxes, pool)) ChooseCellSize(boxes);
  const std::int64_t entry_count = FindCellRanges(boxes, pool);
  if (small_.empty()) {
    FindLargePairs(boxes);
    AddLargePairs();
  } else {
    const std::size_t bucket_count = ChooseBuckets(entry_count);
    FillBuckets(boxes, entry_count, bucket_count, pool);
    FindLargePairs(boxes);
    FindBinnedPairs(bucket_count, pool);
  }
  collector_.Finish();
}

// Shared, each run of the bodies finds its boxes' cells into lists of its own, joined in run order
// (so in id order, as one thread's).
std::int64_t UniformGrid::FindCellRanges(std::span<const AABB> boxes, detail::WorkerPool* pool) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  ranges_.resize(n);
  const std::uint32_t run = detail::RunLength(pool, n, kMinSharedBoxes);
  range_runs_.resize((n + run - 1) / run);
  detail::ForEachRun(pool, n, kMinSharedBoxes, run, [&](std::uint32_t begin, std::uint32_t end) {
    RangeRun& part = range_runs_[begin / run].value;
    part.small.clear();
    part.large.clear();
    part.entries = 0;
    part.occupied = {std::numeric_limits<std::int32_t>::max(), std::numeric_limits<std::int32_t>::max(),
                     std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::min()};
    for (std::uint32_t i = begin; i < end; ++i) {
      const CellRange r = Cells(boxes[i]);
      ranges_[i] = r;
      const std::int64_t cells = r.Count();
      if (cells > kMaxCellsPerBox) {
        part.large.push_back(i);
        continue;
      }
      part.small.push_back(i);
      part.entries += cells;
      part.occupied = Cover(part.occupied, r);
    }
  });
  std::int64_t entry_count = 0;
  occupied_ = range_runs_.front().value.occupied;
  for (const auto& run_part : range_runs_) {
    const RangeRun& part = run_part.value;
    small_.insert(small_.end(), part.small.begin(), part.small.end());
    large_.insert(large_.end(), part.large.begin(), part.large.end());
    entry_count += part.entries;
    occupied_ = Cover(occupied_, part.occupied);
  }
  return entry_count;
}

UniformGrid::CellRange UniformGrid::Cover(const CellRange& a, const CellRange& b) {
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// The cells themselves when the occupied area is compact, else a hash table at load one or less,
// so that bodies spread thin or flung far cost no memory for empty space.
std::size_t UniformGrid::ChooseBuckets(std::int64_t entry_count) {
  const std::int64_t occupied_cells = occupied_.Count();
  dense_ = occupied_cells <= 2 * entry_count + 64;
  if (dense_) return static_cast<std::size_t>(occupied_cells);
  const std::size_t bucket_count = std::bit_ceil(static_cast<std::size_t>(std::max<std::int64_t>(entry_count, 2)));
  hash_shift_ = 64 - static_cast<std::uint32_t>(std::countr_zero(bucket_count));
  return bucket_count;
}

// A counting sort of the (cell, box) entries into buckets: linear, and into buffers kept from call
// to call rather than a map of cells. Shared, each thread counts, then places, the entries of a
// run of the bodies; a bucket holds the runs' entries run after run, so in body order, as one
// thread would place them.
void UniformGrid::FillBuckets(std::span<const AABB> boxes, std::int64_t entry_count, std::size_t bucket_count,
                              detail::WorkerPool* pool) {
  // Every entry is written below: kept from the last call, the list is zeroed only where it
  // grows. (Cleared at each call's start and zeroed whole, 40 bytes an entry, it kept the
  // 4 000-circle pour's calling thread alone 39-43 kcyc a grid call before the threads' counting.)
  entries_.resize(static_cast<std::size_t>(entry_count));
  const int threads = pool && static_cast<std::size_t>(entry_count) >= kMinSharedEntries ? pool->Threads() : 1;
  const auto for_each_entry = [&](int run, auto&& visit) {
    const std::size_t n = small_.size();
    const auto part = static_cast<std::size_t>(run), parts = static_cast<std::size_t>(threads);
    for (std::size_t k = n * part / parts; k < n * (part + 1) / parts; ++k) {
      const std::uint32_t i = small_[k];
      const CellRange& r = ranges_[i];
      for (std::int32_t y = r.y0; y <= r.y1; ++y) {
        for (std::int32_t x = r.x0; x <= r.x1; ++x) visit(i, r, x, y);
      }
    }
  };
  const auto place = [&](int run, std::vector<std::uint32_t>& next) {
    for_each_entry(run, [&](std::uint32_t i, const CellRange& r, std::int32_t x, std::int32_t y) {
      // Field by field into its place: built whole and copied, the entry went through the stack,
      // and the copy's 16-byte load over the small stores that made it waited for them (half
      // of FillBuckets' time).
      Entry& entry = entries_[next[Bucket(x, y)]++];
      entry.box = boxes[i];
      entry.x = x;
      entry.y = y;
      entry.body = i;
      entry.first = static_cast<std::uint8_t>((x == r.x0 ? 1 : 0) | (y == r.y0 ? 2 : 0));
    });
  };
  bucket_start_.assign(bucket_count + 1, 0);
  if (threads == 1) {
    for_each_entry(0, [&](std::uint32_t, const CellRange&, std::int32_t x, std::int32_t y) {
      ++bucket_start_[Bucket(x, y) + 1];
    });
    for (std::size_t b = 1; b <= bucket_count; ++b) bucket_start_[b] += bucket_start_[b - 1];
    place(0, bucket_start_);
    // The placing advanced each start to the next bucket's, which is where bucket b now ends.
    return;
  }
  run_next_.resize(static_cast<std::size_t>(threads));
  pool->RunOnAll([&](int t) {
    std::vector<std::uint32_t>& counts = run_next_[static_cast<std::size_t>(t)].value;
    counts.assign(bucket_count, 0);
    for_each_entry(t, [&](std::uint32_t, const CellRange&, std::int32_t x, std::int32_t y) { ++counts[Bucket(x, y)]; });
  });
  // Each run's first place in each bucket, and where each bucket ends.
  std::uint32_t next = 0;
  for (std::size_t b = 0; b < bucket_count; ++b) {
    for (auto& run : run_next_) {
      const std::uint32_t count = run.value[b];
      run.value[b] = next;
      next += count;
    }
    bucket_start_[b] = next;
  }
  bucket_start_[bucket_count] = next;
  pool->RunOnAll([&](int t) { place(t, run_next_[static_cast<std::size_t>(t)].value); });
}

// Two boxes sharing a cell are a pair there only if it is the cell of their overlap's lower
// corner: the corner's column is the larger of the two first columns, so one of the boxes must
// start in this column, and likewise for the row. The tests are joined without a branch and
// every pair is written, the count advancing only past one that passes: in a pile, which pairs
// pass is as good as random, and mispredicted branches cost most of the scan. The buffer grows
// ahead by what a box's row of tests could give; once it holds kPairsPerHandOff or more, `full`
// is told the count and returns the count to go on from (kStop: stop the scan).
template <typename Full>
std::size_t UniformGrid::ScanBuckets(std::size_t first, std::size_t last, std::vector<BodyPair>* found,
                                     Full&& full) const {
  std::size_t count = 0;
  std::uint32_t begin = first == 0 ? 0 : bucket_start_[first - 1];
  for (std::size_t b = first; b < last; ++b) {
    const std::uint32_t end = bucket_start_[b];
    for (std::uint32_t i = begin; i + 1 < end; ++i) {
      const std::size_t most = end - i - 1;
      if (found->size() < count + most) found->resize(std::max(count + most, 2 * found->size()));
      BodyPair* out = found->data();
      const Entry& p = entries_[i];
      for (std::uint32_t j = i + 1; j < end; ++j) {
        const Entry& q = entries_[j];
        const bool pair = (p.x == q.x) & (p.y == q.y) & ((p.first | q.first) == 3) &
                          (p.box.lower.x <= q.box.upper.x) & (q.box.lower.x <= p.box.upper.x) &
                          (p.box.lower.y <= q.box.upper.y) & (q.box.lower.y <= p.box.upper.y);
        out[count] = {p.body, q.body};
        count += pair ? 1 : 0;
      }
      if (count >= kPairsPerHandOff) {
        count = full(count);
        if (count == kStop) return kStop;
      }
    }
    begin = end;
  }
  return count;
}

// Shared, each thread scans a run of buckets holding about as many entries as the others' and
// keeps its pairs; the runs' pairs then go to the collector in bucket order, as one thread's
// would, so the budget sees them in the same order. A run past the pair limit (boxes piled in a
// cell) stops, and one thread scans again, handing its pairs to the collector as it goes, which
// bounds them: the memory stays linear in the boxes.
void UniformGrid::FindBinnedPairs(std::size_t bucket_count, detail::WorkerPool* pool) {
  const int threads = pool && entries_.size() >= kMinSharedEntries ? pool->Threads() : 1;
  found_.resize(static_cast<std::size_t>(threads));
  const auto hand_over = [this](const FoundRun& run) {
    for (std::size_t k = 0; k < run.count; ++k) collector_.Add(run.pairs[k].a, run.pairs[k].b);
  };
  bool stopped = false;
  if (threads > 1) {
    // The first bucket beginning at or past entry e: bucket b begins where b − 1 ends.
    const auto bucket_at = [&](std::size_t e) {
      const auto ends = std::span<const std::uint32_t>(bucket_start_).first(bucket_count);
      const auto k = static_cast<std::size_t>(std::lower_bound(ends.begin(), ends.end(), e) - ends.begin());
      return e == 0 ? std::size_t{0} : std::min(k + 1, bucket_count);
    };
    const std::size_t total = entries_.size();
    const std::size_t limit = kPairsPerEntry * total + kPairsPerHandOff;
    pool->RunOnAll([&](int t) {
      const auto part = static_cast<std::size_t>(t);
      const std::size_t first = bucket_at(total * part / threads);
      const std::size_t last = t + 1 == threads ? bucket_count : bucket_at(total * (part + 1) / threads);
      FoundRun& run = found_[part].value;
      run.count = ScanBuckets(first, last, &run.pairs,
                              [limit](std::size_t count) { return count > limit ? kStop : count; });
    });
    stopped = std::any_of(found_.begin(), found_.end(), [](const auto& run) { return run.value.count == kStop; });
    if (!stopped) {
      // The large boxes' pairs last, as one at a time would add them; sorted with the rest.
      found_runs_.clear();
      for (const auto& run : found_) found_runs_.emplace_back(run.value.pairs.data(), run.value.count);
      found_runs_.emplace_back(large_pairs_);
      collector_.AddRuns(found_runs_, pool, PairCollector::RunOrder::kUnsorted);
      return;
    }
  }
  FoundRun& run = found_[0].value;
  run.count = ScanBuckets(0, bucket_count, &run.pairs, [&](std::size_t count) {
    run.count = count;
    hand_over(run);
    return std::size_t{0};
  });
  hand_over(run);
  AddLargePairs();
}

void UniformGrid::AddLargePairs() {
  for (const BodyPair& p : large_pairs_) collector_.Add(p.a, p.b);
}

void UniformGrid::FindLargePairs(std::span<const AABB> boxes) {
  large_pairs_.clear();
  for (std::size_t i = 0; i < large_.size(); ++i) {
    const std::uint32_t a = large_[i];
    const AABB& box = boxes[a];
    for (std::size_t j = i + 1; j < large_.size(); ++j) {
      if (Overlaps(box, boxes[large_[j]])) large_pairs_.push_back({a, large_[j]});
    }
    if (!small_.empty()) FindLargeBinnedPairs(a, boxes);
  }
}

// Walks the occupied cells under the large box when they are fewer than the binned boxes (a floor
// covers one row of cells), else tests each binned box.
void UniformGrid::FindLargeBinnedPairs(std::uint32_t large, std::span<const AABB> boxes) {
  const AABB& box = boxes[large];
  const CellRange& r = ranges_[large];
  const CellRange walk{std::max(r.x0, occupied_.x0), std::max(r.y0, occupied_.y0),
                       std::min(r.x1, occupied_.x1), std::min(r.y1, occupied_.y1)};
  if (walk.x0 > walk.x1 || walk.y0 > walk.y1) return;
  if (walk.Count() > static_cast<std::int64_t>(small_.size())) {
    for (std::uint32_t s : small_) {
      if (Overlaps(box, boxes[s])) large_pairs_.push_back({large, s});
    }
    return;
  }
  for (std::int32_t y = walk.y0; y <= walk.y1; ++y) {
    for (std::int32_t x = walk.x0; x <= walk.x1; ++x) {
      const std::uint32_t b = Bucket(x, y);
      const std::uint32_t end = bucket_start_[b];
      for (std::uint32_t k = b == 0 ? 0 : bucket_start_[b - 1]; k < end; ++k) {
        const Entry& e = entries_[k];
        // The same one-cell rule, with the large box's first column and row.
        if (e.x == x && e.y == y && (r.x0 == x || (e.first & 1)) && (r.y0 == y || (e.first & 2)) &&
            Overlaps(box, e.box)) {
          large_pairs_.push_back({large, e.body});
        }
      }
    }
  }
}

}  // namespace engine
