// The uniform grid: boxes binned into square cells sized from the boxes, each pair reported by
// one cell; boxes too big for the cells tested on their own.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "broad_phase/pair_collector.h"
#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"
#include "engine/math.h"

namespace engine {

/// A uniform grid, hashed: each box goes into every cell it touches, and a pair is reported only
/// by the cell holding the lower corner of the two boxes' overlap, so a pair spanning several
/// shared cells comes out once. The cell size follows the boxes (twice their median extent) and is
/// chosen again only when the median drifts by more than a factor of two. Boxes that would touch
/// many cells (floors, walls) stay out of the cells and are tested on their own. O(n + pairs) for
/// similar-sized boxes. Pairs come out sorted by (a, b).
class UniformGrid {
 public:
  /// `pool`: the threads to share the search among (none: the calling thread alone). The pairs
  /// and the budget's choices are the same whatever the pool.
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const PairQuota> quotas = {}, detail::WorkerPool* pool = nullptr);
  const PairCollector& Collector() const { return collector_; }

  /// m; 0 before the first call.
  double CellSize() const { return cell_size_; }
  /// Boxes the last call kept out of the cells because they touch too many.
  std::size_t LargeCount() const { return large_.size(); }

 private:
  struct CellRange {
    std::int32_t x0, y0, x1, y1;
    std::int64_t Count() const { return (std::int64_t{x1} - x0 + 1) * (std::int64_t{y1} - y0 + 1); }
  };
  struct Entry {
    AABB box;
    std::int32_t x, y;  ///< the cell
    std::uint32_t body;
    std::uint8_t first;  ///< bit 0: the box's leftmost column of cells; bit 1: its bottom row
  };
  bool CellSizeFits(std::span<const AABB> boxes, detail::WorkerPool* pool);
  void ChooseCellSize(std::span<const AABB> boxes);
  CellRange Cells(const AABB& box) const;
  std::uint32_t Bucket(std::int32_t x, std::int32_t y) const;
  /// Which cells each box touches, the large boxes set apart and the occupied cells' bounds;
  /// returns how many (cell, box) entries the other boxes make.
  std::int64_t FindCellRanges(std::span<const AABB> boxes, detail::WorkerPool* pool);
  static CellRange Cover(const CellRange& a, const CellRange& b);
  /// Dense or hashed buckets for the entries; returns how many.
  std::size_t ChooseBuckets(std::int64_t entry_count);
  void FillBuckets(std::span<const AABB> boxes, std::int64_t entry_count, std::size_t bucket_count,
                   detail::WorkerPool* pool);
  /// The binned pairs, then large_pairs_, to the collector.
  void FindBinnedPairs(std::size_t bucket_count, detail::WorkerPool* pool);
  /// The pairs of the buckets [first, last), in bucket order, into the front of `found` (grown
  /// as needed, never shrunk); returns how many, or kStop when `full` stopped it.
  template <typename Full>
  std::size_t ScanBuckets(std::size_t first, std::size_t last, std::vector<BodyPair>* found, Full&& full) const;
  static constexpr std::size_t kStop = static_cast<std::size_t>(-1);
  /// The large boxes' pairs, among themselves and with the binned boxes, into large_pairs_ (after
  /// FillBuckets): the collector takes them after the binned pairs, in one sort with them.
  void FindLargePairs(std::span<const AABB> boxes);
  void FindLargeBinnedPairs(std::uint32_t large, std::span<const AABB> boxes);
  void AddLargePairs();

  double cell_size_ = 0.0;
  double inv_cell_size_ = 0.0;
  std::vector<CellRange> ranges_;       ///< per body
  std::vector<std::uint32_t> large_;    ///< bodies tested on their own, in id order
  std::vector<std::uint32_t> small_;    ///< bodies in the cells, in id order
  std::vector<BodyPair> large_pairs_;   ///< FindLargePairs' pairs, in the order it finds them
  // The occupied cells' bounds; when they hold few cells more than entries, buckets are the cells
  // themselves (dense), otherwise a hash of the cell picks the bucket.
  CellRange occupied_{};
  bool dense_ = false;
  std::uint32_t hash_shift_ = 0;
  /// After FillBuckets, bucket b spans [bucket_start_[b - 1], bucket_start_[b]) (0 for b = 0).
  std::vector<std::uint32_t> bucket_start_;
  std::vector<Entry> entries_;
  std::vector<double> extent_scratch_;
  /// A run's share of CellSizeFits' count and of FindCellRanges' lists, when shared.
  struct SizeRun {
    std::size_t bigger = 0, smaller = 0;
  };
  struct RangeRun {
    std::vector<std::uint32_t> small, large;
    std::int64_t entries = 0;
    CellRange occupied{};
  };
  std::vector<detail::PerThread<SizeRun>> size_runs_;
  std::vector<detail::PerThread<RangeRun>> range_runs_;
  /// A thread's pairs: the first `count` of `pairs`.
  struct FoundRun {
    std::vector<BodyPair> pairs;
    std::size_t count = 0;
  };
  std::vector<detail::PerThread<FoundRun>> found_;
  std::vector<std::span<const BodyPair>> found_runs_;  ///< found_'s, for the collector
  /// FillBuckets' runs, when shared: each run's count per bucket, then its next place there.
  std::vector<detail::PerThread<std::vector<std::uint32_t>>> run_next_;
  PairCollector collector_;
};

}  // namespace engine
