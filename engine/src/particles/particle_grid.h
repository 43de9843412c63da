// A uniform grid over particles, rebuilt each step: the particles sorted by cell, so the
// neighbours within one cell size of a particle, and the particles inside a box, are found by
// looking at a few runs of the sorted list. Deterministic: cells in (row, column) order,
// particles in index order within a cell. Internal.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/math.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

class ParticleGrid {
 public:
  /// Sorts `positions` into cells `cell` wide (> 0).
  void Build(std::span<const Vec2> positions, double cell);

  /// Renumbers the particles from `first` on in the grid's order (row by row, cell by cell, by
  /// number within a cell) and lists them by their new numbers, still in that order:
  /// `old_of_new[k]` is the old number of new number first + k, less first. `row_starts` gets,
  /// for each row of cells, the first new number (less first) in it or after it. The caller
  /// moves the particles' data to match.
  void RenumberFrom(std::uint32_t first, std::vector<std::uint32_t>* old_of_new,
                    std::vector<std::uint32_t>* row_starts);

  /// For each particle, the others within `radius` (≤ the cell size) of it: particle i's are
  /// neighbours[offsets[i] .. offsets[i + 1]).
  /// The pairs are sought on `pool`'s threads, each over its own run of cells, and entered in
  /// cell order: the same lists with any thread count. The particles from `ordered_from` on
  /// are numbered in the grid's order (RenumberFrom), which lets their search skip the cells
  /// with only lower numbers; the pairs of two of them are returned, each once (i < j, both
  /// less ordered_from), sorted by their lower particle and each particle's in the order found,
  /// so a quantity of a pair can be worked out once for both its particles; valid until the
  /// next call. Only the particles below `lists_below` get lists (the others' are empty), the
  /// pairs being all a fluid needs; an ordered particle's list has its neighbours numbered
  /// before `ordered_from` first, then the others in the order of the pairs. The ordered
  /// particles' pairs are sought four candidates at a time with AVX2 where the processor has it
  /// (`lanes` 1: one at a time), the same pairs either way.
  std::span<const std::pair<std::uint32_t, std::uint32_t>> FindNeighbours(
      std::span<const Vec2> positions, double radius, WorkerPool& pool, std::vector<std::uint32_t>* offsets,
      std::vector<std::uint32_t>* neighbours, std::uint32_t ordered_from, std::uint32_t lists_below,
      int lanes = 0) const;

  /// Calls visit(i) for every particle in a cell that `box` overlaps, in cell order.
  template <typename Visit>
  void ForEachInBox(const AABB& box, Visit&& visit) const;

 private:
  static std::uint64_t Key(std::int32_t column, std::int32_t row) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(row) ^ 0x80000000u) << 32) |
           (static_cast<std::uint32_t>(column) ^ 0x80000000u);
  }
  std::int32_t Cell(double coordinate) const;
  /// The cells with particles in [first, last] columns of `row`: indices into cells_.
  std::pair<std::size_t, std::size_t> RowRun(std::int32_t row, std::int32_t first, std::int32_t last) const;

  double cell_ = 1.0;
  std::vector<std::uint64_t> cell_keys_;    ///< the occupied cells, sorted
  std::vector<std::uint32_t> cell_starts_;  ///< into order_, one more than cell_keys_
  std::vector<std::uint32_t> order_;        ///< particle indices sorted by (cell, index)
  std::vector<std::pair<std::uint64_t, std::uint32_t>> scratch_;
  std::vector<std::int32_t> columns_, rows_;  ///< Build's: each particle's cell
  /// FindNeighbours' scratch: each thread's pairs, the first pair_counts_[t] of pairs_[t], and
  /// of ordered particles, ordered_counts_[t] of ordered_pairs_[t] (merged_pairs_ all together)
  mutable std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> pairs_, ordered_pairs_;
  mutable std::vector<std::pair<std::uint32_t, std::uint32_t>> merged_pairs_;
  mutable std::vector<std::size_t> pair_counts_, ordered_counts_;
  mutable std::vector<std::uint32_t> counts_;
};

template <typename Visit>
void ParticleGrid::ForEachInBox(const AABB& box, Visit&& visit) const {
  if (cell_keys_.empty()) return;
  const std::int32_t c0 = Cell(box.lower.x), c1 = Cell(box.upper.x);
  const std::int32_t r0 = Cell(box.lower.y), r1 = Cell(box.upper.y);
  const auto visit_cell = [&](std::size_t c) {
    for (std::uint32_t k = cell_starts_[c]; k < cell_starts_[c + 1]; ++k) visit(order_[k]);
  };
  // A box more rows tall than there are occupied cells (a body a billion cells tall) is cheaper
  // met by going through the cells; both ways visit the same cells in the same order.
  if (static_cast<std::int64_t>(r1) - r0 >= static_cast<std::int64_t>(cell_keys_.size())) {
    for (std::size_t c = 0; c < cell_keys_.size(); ++c) {
      const auto column = static_cast<std::int32_t>(static_cast<std::uint32_t>(cell_keys_[c]) ^ 0x80000000u);
      const auto row = static_cast<std::int32_t>(static_cast<std::uint32_t>(cell_keys_[c] >> 32) ^ 0x80000000u);
      if (row >= r0 && row <= r1 && column >= c0 && column <= c1) visit_cell(c);
    }
    return;
  }
  for (std::int32_t row = r0; row <= r1; ++row) {
    const auto [first, last] = RowRun(row, c0, c1);
    for (std::size_t c = first; c < last; ++c) visit_cell(c);
  }
}

}  // namespace engine::detail
