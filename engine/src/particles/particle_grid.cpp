// The particle grid: a sort by cell, then runs of cells looked up by binary search.
#include "particles/particle_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#if defined(__x86_64__)
#include <immintrin.h>

#include "particles/keep_table.h"
#define BALLBOX_AVX2_AT_RUN_TIME 1
#endif

namespace engine::detail {

namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

// Appends to out[count...] the pairs (i − shift, j − shift) for the candidates j = order[b], b in
// [begin, end), with j > i and |x[j] − x[i]|² ≤ r2, in that order; returns the new count.
// Every candidate is written and kept or overwritten by the next: whether j > i and whether it
// is near are coin tosses a branch would mispredict.
std::size_t NearRunBy1(const Vec2* x, const std::uint32_t* order, std::uint32_t begin, std::uint32_t end,
                       std::uint32_t i, double r2, std::uint32_t shift, Pair* out, std::size_t count) {
  const Vec2 xi = x[i];
  for (std::uint32_t b = begin; b < end; ++b) {
    const std::uint32_t j = order[b];
    out[count] = {i - shift, j - shift};
    count += (j > i) & (LengthSquared(x[j] - xi) <= r2);
  }
  return count;
}

#ifdef BALLBOX_AVX2_AT_RUN_TIME

// NearRunBy1 four candidates at a time: each lane's distance is the same IEEE operations, and
// the kept pairs are packed in order, so the same pairs. Candidates numbered one after another
// (a fluid's, in the grid's order) have their positions loaded together.
__attribute__((target("avx2"))) std::size_t NearRunBy4(const Vec2* x, const std::uint32_t* order,
                                                       std::uint32_t begin, std::uint32_t end, std::uint32_t i,
                                                       double r2, std::uint32_t shift, Pair* out, std::size_t count) {
  const __m256d limit = _mm256_set1_pd(r2);
  const __m256d xi = _mm256_set1_pd(x[i].x), yi = _mm256_set1_pd(x[i].y);
  const __m128i above = _mm_set1_epi32(static_cast<std::int32_t>(i ^ 0x80000000u));
  const __m128i flip = _mm_set1_epi32(static_cast<std::int32_t>(0x80000000u));
  const __m128i steps = _mm_setr_epi32(0, 1, 2, 3);
  const __m128i lower = _mm_set1_epi32(static_cast<std::int32_t>(i - shift));
  const __m128i shifts = _mm_set1_epi32(static_cast<std::int32_t>(shift));
  std::uint32_t b = begin;
  for (; b + 4 <= end; b += 4) {
    const __m128i js = _mm_loadu_si128(reinterpret_cast<const __m128i*>(order + b));
    __m256d ab, cd;  // (x, y) of the first two candidates, and of the last two
    const std::uint32_t j0 = order[b];
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(js, _mm_add_epi32(_mm_set1_epi32(static_cast<std::int32_t>(j0)), steps))) ==
        0xffff) {
      ab = _mm256_loadu_pd(&x[j0].x);
      cd = _mm256_loadu_pd(&x[j0 + 2].x);
    } else {
      ab = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[order[b]].x)), _mm_loadu_pd(&x[order[b + 1]].x), 1);
      cd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[order[b + 2]].x)), _mm_loadu_pd(&x[order[b + 3]].x),
                                1);
    }
    // unpack gives lanes (0, 2, 1, 3); the permute puts them back in order.
    const __m256d xj = _mm256_permute4x64_pd(_mm256_unpacklo_pd(ab, cd), 0xd8);
    const __m256d yj = _mm256_permute4x64_pd(_mm256_unpackhi_pd(ab, cd), 0xd8);
    // LengthSquared(x[j] − x[i]), lane by lane.
    const __m256d dx = _mm256_sub_pd(xj, xi), dy = _mm256_sub_pd(yj, yi);
    const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const int near = _mm256_movemask_pd(_mm256_cmp_pd(d2, limit, _CMP_LE_OQ));
    const int higher = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpgt_epi32(_mm_xor_si128(js, flip), above)));
    const int keep = near & higher;
    // The four pairs (i − shift, j − shift), then the kept ones packed to the front.
    const __m128i ks = _mm_sub_epi32(js, shifts);
    const __m256i pairs = _mm256_set_m128i(_mm_unpackhi_epi32(lower, ks), _mm_unpacklo_epi32(lower, ks));
    const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kKeep.lanes[keep]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + count), _mm256_permutevar8x32_epi32(pairs, lanes));
    count += static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(keep)));
  }
  return NearRunBy1(x, order, b, end, i, r2, shift, out, count);
}
#endif

}  // namespace

std::int32_t ParticleGrid::Cell(double coordinate) const {
  // Clamped so a far-flung particle (or a huge box) cannot overflow the cell index.
  const double c = std::floor(coordinate / cell_);
  constexpr double kLimit = 1.0e9;
  return static_cast<std::int32_t>(std::clamp(c, -kLimit, kLimit));
}

void ParticleGrid::Build(std::span<const Vec2> positions, double cell) {
  cell_ = cell;
  const auto n = static_cast<std::uint32_t>(positions.size());
  order_.resize(n);
  cell_keys_.clear();
  cell_starts_.clear();
  if (n == 0) {
    cell_starts_.push_back(0);
    return;
  }
  columns_.resize(n);
  rows_.resize(n);
  std::int32_t c0 = std::numeric_limits<std::int32_t>::max(), c1 = std::numeric_limits<std::int32_t>::min();
  std::int32_t r0 = c0, r1 = c1;
  for (std::uint32_t i = 0; i < n; ++i) {
    columns_[i] = Cell(positions[i].x), rows_[i] = Cell(positions[i].y);
    c0 = std::min(c0, columns_[i]), c1 = std::max(c1, columns_[i]);
    r0 = std::min(r0, rows_[i]), r1 = std::max(r1, rows_[i]);
  }
  const auto width = static_cast<std::uint64_t>(std::int64_t{c1} - c0 + 1);
  const std::uint64_t area = width * static_cast<std::uint64_t>(std::int64_t{r1} - r0 + 1);
  if (area > 4 * std::uint64_t{n} + 1024) {
    // Spread thin (a particle flung far away): sorted by key and index.
    scratch_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) scratch_[i] = {Key(columns_[i], rows_[i]), i};
    std::sort(scratch_.begin(), scratch_.end());
    for (std::uint32_t k = 0; k < n; ++k) {
      if (cell_keys_.empty() || cell_keys_.back() != scratch_[k].first) {
        cell_keys_.push_back(scratch_[k].first);
        cell_starts_.push_back(k);
      }
      order_[k] = scratch_[k].second;
    }
    cell_starts_.push_back(n);
    return;
  }
  // A counting sort over the cells of the particles' bounding box, row by row: the same
  // order as sorting by (key, index), since particles are entered in index order.
  counts_.assign(area + 1, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    ++counts_[(rows_[i] - r0) * width + static_cast<std::uint64_t>(columns_[i] - c0) + 1];
  }
  for (std::uint64_t c = 0; c < area; ++c) {
    if (counts_[c + 1] > 0) {
      cell_keys_.push_back(Key(c0 + static_cast<std::int32_t>(c % width), r0 + static_cast<std::int32_t>(c / width)));
      cell_starts_.push_back(counts_[c]);
    }
    counts_[c + 1] += counts_[c];
  }
  cell_starts_.push_back(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    order_[counts_[(rows_[i] - r0) * width + static_cast<std::uint64_t>(columns_[i] - c0)]++] = i;
  }
}

void ParticleGrid::RenumberFrom(std::uint32_t first, std::vector<std::uint32_t>* old_of_new,
                                std::vector<std::uint32_t>* row_starts) {
  // Within a cell the lower numbers (before `first`) come first and keep theirs, and the others
  // get rising numbers in the order they are met: the list stays sorted by (cell, number).
  old_of_new->clear();
  row_starts->clear();
  for (std::size_t c = 0; c < cell_keys_.size(); ++c) {
    if (c == 0 || cell_keys_[c] >> 32 != cell_keys_[c - 1] >> 32) {
      row_starts->push_back(static_cast<std::uint32_t>(old_of_new->size()));
    }
    for (std::uint32_t k = cell_starts_[c]; k < cell_starts_[c + 1]; ++k) {
      if (order_[k] < first) continue;
      old_of_new->push_back(order_[k] - first);
      order_[k] = first + static_cast<std::uint32_t>(old_of_new->size() - 1);
    }
  }
}

std::pair<std::size_t, std::size_t> ParticleGrid::RowRun(std::int32_t row, std::int32_t first,
                                                         std::int32_t last) const {
  const auto lo = std::lower_bound(cell_keys_.begin(), cell_keys_.end(), Key(first, row));
  const auto hi = std::upper_bound(lo, cell_keys_.end(), Key(last, row));
  return {static_cast<std::size_t>(lo - cell_keys_.begin()), static_cast<std::size_t>(hi - cell_keys_.begin())};
}

std::span<const std::pair<std::uint32_t, std::uint32_t>> ParticleGrid::FindNeighbours(
    std::span<const Vec2> positions, double radius, WorkerPool& pool, std::vector<std::uint32_t>* offsets,
    std::vector<std::uint32_t>* neighbours, std::uint32_t ordered_from, std::uint32_t lists_below,
    [[maybe_unused]] int lanes) const {
  const std::size_t n = positions.size();
  const double r2 = radius * radius;
  // Each pair once (i < j), found per cell against the 3×3 cells around it in cell order, then
  // entered in both particles' lists in that order: deterministic, and half the distance tests.
  const auto threads = static_cast<std::uint32_t>(cell_keys_.size() < 64 ? 1 : pool.Threads());
  auto near_run = &NearRunBy1;
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && lanes != 1) near_run = &NearRunBy4;
#endif
  pairs_.resize(threads);
  ordered_pairs_.resize(threads);
  pair_counts_.assign(threads, 0);
  ordered_counts_.assign(threads, 0);
  pool.ParallelFor(threads, 2, [&](std::uint32_t t) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs = pairs_[t];
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& ordered = ordered_pairs_[t];
    std::size_t count = 0, ordered_count = 0;
    const std::size_t first_cell = cell_keys_.size() * t / threads;
    const std::size_t last_cell = cell_keys_.size() * (t + 1) / threads;
    const std::uint32_t* const order = order_.data();
    const Vec2* const x = positions.data();
    // Every candidate is written and kept or overwritten by the next: whether j > i and whether
    // it is near are coin tosses a branch would mispredict.
    const auto reserve = [](std::vector<std::pair<std::uint32_t, std::uint32_t>>& list, std::size_t count,
                            std::size_t more) {
      if (list.size() < count + more) list.resize(2 * (count + more));
    };
    // The runs of cells beside each cell in the rows below, of and above it only move on as
    // the cells go by in order: found once by binary search, then stepped along.
    std::size_t run_first[3], run_last[3];
    const std::size_t cells = cell_keys_.size();
    for (std::size_t c = first_cell; c < last_cell; ++c) {
      const auto column = static_cast<std::int32_t>(static_cast<std::uint32_t>(cell_keys_[c]) ^ 0x80000000u);
      const auto row = static_cast<std::int32_t>(static_cast<std::uint32_t>(cell_keys_[c] >> 32) ^ 0x80000000u);
      std::uint32_t b0[3], b1[3];  // the candidates in the rows below, of and above the cell
      for (std::int32_t dr = -1; dr <= 1; ++dr) {
        std::size_t& first = run_first[dr + 1];
        std::size_t& last = run_last[dr + 1];
        if (c == first_cell) {
          std::tie(first, last) = RowRun(row + dr, column - 1, column + 1);
        } else {
          const std::uint64_t from = Key(column - 1, row + dr), to = Key(column + 1, row + dr);
          while (first < cells && cell_keys_[first] < from) ++first;
          last = std::max(last, first);
          while (last < cells && cell_keys_[last] <= to) ++last;
        }
        b0[dr + 1] = cell_starts_[first], b1[dr + 1] = cell_starts_[last];
      }
      const std::uint32_t a0 = cell_starts_[c], a1 = cell_starts_[c + 1];
      // The cell's particles numbered before `ordered_from` come first in it.
      const std::uint32_t mid = static_cast<std::uint32_t>(
          std::partition_point(order + a0, order + a1, [&](std::uint32_t i) { return i < ordered_from; }) - order);
      for (std::int32_t dr = -1; dr <= 1 && mid > a0; ++dr) {
        reserve(pairs, count, std::size_t{mid - a0} * (b1[dr + 1] - b0[dr + 1]));
        std::pair<std::uint32_t, std::uint32_t>* const out = pairs.data();
        for (std::uint32_t a = a0; a < mid; ++a) {
          const std::uint32_t i = order[a];
          const Vec2 xi = x[i];
          for (std::uint32_t b = b0[dr + 1]; b < b1[dr + 1]; ++b) {
            const std::uint32_t j = order[b];
            out[count] = {i, j};
            count += (j > i) & (LengthSquared(x[j] - xi) <= r2);
          }
        }
      }
      // A particle numbered in the grid's order has only lower numbers in the row below and
      // before it in its own row: none of them can pair with it, so they are skipped. Its pairs
      // are found together (its own row, then the row above), so that they come sorted by their
      // lower particle; each particle's pairs are in the order the loop above would find them.
      if (mid == a1) continue;
      // Four more, as the four-lane loop writes a whole vector of four pairs.
      reserve(ordered, ordered_count, std::size_t{a1 - mid} * (b1[1] - b0[1] + b1[2] - b0[2]) + 4);
      std::pair<std::uint32_t, std::uint32_t>* const out = ordered.data();
      for (std::uint32_t a = mid; a < a1; ++a) {
        const std::uint32_t i = order[a];
        ordered_count = near_run(x, order, a + 1, b1[1], i, r2, ordered_from, out, ordered_count);
        ordered_count = near_run(x, order, b0[2], b1[2], i, r2, ordered_from, out, ordered_count);
      }
    }
    pair_counts_[t] = count;
    ordered_counts_[t] = ordered_count;
  });
  // The lists, from the pairs with a particle numbered before `ordered_from`, then from the
  // others' where lists are wanted.
  const std::uint32_t lists_of_ordered = lists_below > ordered_from ? lists_below - ordered_from : 0;
  std::vector<std::uint32_t>& counts = counts_;
  counts.assign(n + 1, 0);
  for (std::uint32_t t = 0; t < threads; ++t) {
    for (std::size_t q = 0; q < pair_counts_[t]; ++q) {
      const auto [i, j] = pairs_[t][q];
      counts[i] += i < lists_below;
      counts[j] += j < lists_below;
    }
    for (std::size_t q = 0; q < ordered_counts_[t] && lists_of_ordered > 0; ++q) {
      const auto [i, j] = ordered_pairs_[t][q];
      counts[ordered_from + i] += i < lists_of_ordered;
      counts[ordered_from + j] += j < lists_of_ordered;
    }
  }
  offsets->assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) (*offsets)[i + 1] = (*offsets)[i] + counts[i];
  neighbours->resize(offsets->back());
  std::vector<std::uint32_t>& fill = counts;
  std::copy(offsets->begin(), offsets->end() - 1, fill.begin());
  for (std::uint32_t t = 0; t < threads; ++t) {
    for (std::size_t q = 0; q < pair_counts_[t]; ++q) {
      const auto [i, j] = pairs_[t][q];
      if (i < lists_below) (*neighbours)[fill[i]++] = j;
      if (j < lists_below) (*neighbours)[fill[j]++] = i;
    }
  }
  for (std::uint32_t t = 0; t < threads && lists_of_ordered > 0; ++t) {
    for (std::size_t q = 0; q < ordered_counts_[t]; ++q) {
      const auto [i, j] = ordered_pairs_[t][q];
      if (i < lists_of_ordered) (*neighbours)[fill[ordered_from + i]++] = ordered_from + j;
      if (j < lists_of_ordered) (*neighbours)[fill[ordered_from + j]++] = ordered_from + i;
    }
  }
  // The pairs of ordered particles, thread by thread (in cell order).
  if (threads == 1) return std::span(ordered_pairs_[0]).first(ordered_counts_[0]);
  std::size_t total = 0;
  for (std::uint32_t t = 0; t < threads; ++t) total += ordered_counts_[t];
  merged_pairs_.resize(total);
  std::size_t at = 0;
  for (std::uint32_t t = 0; t < threads; ++t) {
    std::copy_n(ordered_pairs_[t].begin(), ordered_counts_[t], merged_pairs_.begin() + static_cast<std::ptrdiff_t>(at));
    at += ordered_counts_[t];
  }
  return merged_pairs_;
}

}  // namespace engine::detail
