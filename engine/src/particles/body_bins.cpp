// The body bins: a dense grid over the bodies' bounds, cells about as wide as a typical body.
#include "particles/body_bins.h"

#include <algorithm>
#include <cmath>

#include "candidate_pairs.h"

namespace engine::detail {

namespace {

/// A body covering more cells than this is tested at every point instead of being binned: the
/// bins then hold at most this many entries per body. A ground 64 cells long is still binned,
/// sparing every particle far from it a test.
constexpr std::uint32_t kWideCells = 64;
/// At most this many columns or rows, however thin the bodies' area.
constexpr double kMaxSide = 256.0;

}  // namespace

void BodyBins::ChooseCells(double median_side) {
  const double width = area_.upper.x - area_.lower.x, height = area_.upper.y - area_.lower.y;
  // Cells as wide as a typical body, unless that would make many more cells than bodies.
  const double most_cells = 4.0 * static_cast<double>(slots_.size()) + 64.0;
  cell_ = std::max({median_side, std::sqrt(width * height / most_cells), std::max(width, height) / kMaxSide});
  if (!(cell_ > 0.0) || !std::isfinite(cell_)) {  // a lone point, or bounds too far apart to measure
    cell_ = inverse_cell_ = 1.0;
    columns_ = rows_ = 1;
    return;
  }
  inverse_cell_ = 1.0 / cell_;
  columns_ = static_cast<std::uint32_t>(std::min(std::floor(width / cell_), kMaxSide)) + 1;
  rows_ = static_cast<std::uint32_t>(std::min(std::floor(height / cell_), kMaxSide)) + 1;
}

void BodyBins::Build(const Bodies& bodies, double margin) {
  slots_.clear();
  bounds_.clear();
  wide_.clear();
  sides_.clear();
  for (const BodyId id : bodies.live_ids) {
    const BodyIndex b = id.index;
    if (!bodies.enabled[b] || bodies.infos[b].is_sensor) continue;
    const AABB box = BoundsOf(bodies, b);
    if (slots_.empty()) area_ = box;
    area_.lower = {std::min(area_.lower.x, box.lower.x), std::min(area_.lower.y, box.lower.y)};
    area_.upper = {std::max(area_.upper.x, box.upper.x), std::max(area_.upper.y, box.upper.y)};
    slots_.push_back(b);
    bounds_.push_back(box);
    sides_.push_back(std::max(box.upper.x - box.lower.x, box.upper.y - box.lower.y) + 2.0 * margin);
  }
  if (slots_.empty()) return;
  const Vec2 grow{margin, margin};
  area_ = {area_.lower - grow, area_.upper + grow};
  const auto middle = sides_.begin() + static_cast<std::ptrdiff_t>(sides_.size() / 2);
  std::nth_element(sides_.begin(), middle, sides_.end());
  ChooseCells(*middle);
  // Two passes, counting then filling, so each cell's list is one ascending run of entries_.
  cell_starts_.assign(static_cast<std::size_t>(columns_) * rows_ + 1, 0);
  ranges_.resize(slots_.size());
  for (std::uint32_t k = 0; k < slots_.size(); ++k) {
    CellRange& r = ranges_[k];
    const Vec2 lower = bounds_[k].lower - grow - area_.lower, upper = bounds_[k].upper + grow - area_.lower;
    r = {CellIndex(lower.x, inverse_cell_, columns_), CellIndex(upper.x, inverse_cell_, columns_),
         CellIndex(lower.y, inverse_cell_, rows_), CellIndex(upper.y, inverse_cell_, rows_)};
    if ((r.c1 - r.c0 + 1) * (r.r1 - r.r0 + 1) > kWideCells) {
      wide_.push_back(k);
      r.wide = true;
      continue;
    }
    for (std::uint32_t row = r.r0; row <= r.r1; ++row) {
      for (std::uint32_t c = r.c0; c <= r.c1; ++c) ++cell_starts_[row * columns_ + c + 1];
    }
  }
  for (std::size_t c = 1; c < cell_starts_.size(); ++c) cell_starts_[c] += cell_starts_[c - 1];
  entries_.resize(cell_starts_.back());
  cursor_.assign(cell_starts_.begin(), cell_starts_.end() - 1);
  for (std::uint32_t k = 0; k < slots_.size(); ++k) {
    const CellRange& r = ranges_[k];
    if (r.wide) continue;
    for (std::uint32_t row = r.r0; row <= r.r1; ++row) {
      for (std::uint32_t c = r.c0; c <= r.c1; ++c) entries_[cursor_[row * columns_ + c]++] = k;
    }
  }
}

}  // namespace engine::detail
