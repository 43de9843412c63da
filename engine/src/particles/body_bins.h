// The solid bodies' bounds binned in a uniform grid, rebuilt each step, so a point (an effect
// particle) finds the few bodies near it without looking at all of them. Bodies are few and
// particles many, so the bodies are binned, not the particles: the particles are then visited
// in index order. Deterministic: each cell lists its bodies in slot order. Cells are as wide as
// a typical body, but there are at most about 4 per body: bodies scattered far apart (one a
// kilometre off) make the cells coarse, and a particle then tests more bodies' bounds. Internal.
#pragma once

#include <cstdint>
#include <vector>

#include "bodies.h"
#include "engine/math.h"

namespace engine::detail {

class BodyBins {
 public:
  /// Bins the live, enabled bodies that are not sensors, each by its bounds grown by `margin`:
  /// the most a query's box may reach past its anchor.
  void Build(const Bodies& bodies, double margin);
  bool Empty() const { return slots_.empty(); }

  /// Calls visit(body) for each binned body whose bounds overlap `box`: those of the anchor's
  /// cell in slot order, then the wide ones in slot order. `box` lies within Build's margin of
  /// `anchor`, so the anchor's cell lists every such body.
  template <typename Visit>
  void ForEachOverlapping(Vec2 anchor, const AABB& box, Visit&& visit) const;

 private:
  // The four comparisons with & rather than &&: one branch, not four hard to predict (they
  // were a quarter of the effect particles' collision pass).
  static bool Holds(const AABB& box, Vec2 p) {
    return (p.x >= box.lower.x) & (p.x <= box.upper.x) & (p.y >= box.lower.y) & (p.y <= box.upper.y);
  }
  static bool Overlap(const AABB& a, const AABB& b) {
    return (a.lower.x <= b.upper.x) & (b.lower.x <= a.upper.x) & (a.lower.y <= b.upper.y) & (b.lower.y <= a.upper.y);
  }
  /// The cell of a coordinate `offset` past the grid's corner, clamped into the grid (a NaN,
  /// too). Truncation is the floor once below zero is ruled out, and costs no libm call.
  static std::uint32_t CellIndex(double offset, double inverse_cell, std::uint32_t count) {
    const double q = offset * inverse_cell;
    if (!(q > 0.0)) return 0;
    return q >= static_cast<double>(count - 1) ? count - 1 : static_cast<std::uint32_t>(q);
  }
  std::uint32_t CellOf(Vec2 point) const {
    return CellIndex(point.y - area_.lower.y, inverse_cell_, rows_) * columns_ +
           CellIndex(point.x - area_.lower.x, inverse_cell_, columns_);
  }
  void ChooseCells(double median_side);

  std::vector<BodyIndex> slots_;  ///< the binned bodies, in slot order
  std::vector<AABB> bounds_;      ///< each binned body's bounds
  AABB area_;                     ///< all of them together, grown by the margin
  double cell_ = 1.0;
  double inverse_cell_ = 1.0;  ///< multiplied by, not divided by: a point's cell costs no division
  std::uint32_t columns_ = 1, rows_ = 1;
  std::vector<std::uint32_t> cell_starts_;  ///< into entries_, one more than the cells
  std::vector<std::uint32_t> entries_;      ///< indices into slots_, cell by cell, ascending
  /// Bodies covering too many cells (a long ground, or all of them if every body is huge) are
  /// kept aside and tested at every point instead. Indices into slots_, ascending.
  std::vector<std::uint32_t> wide_;

  struct CellRange {
    std::uint32_t c0 = 0, c1 = 0, r0 = 0, r1 = 0;
    bool wide = false;
  };
  std::vector<CellRange> ranges_;  ///< Build's scratch
  std::vector<std::uint32_t> cursor_;
  std::vector<double> sides_;
};

template <typename Visit>
void BodyBins::ForEachOverlapping(Vec2 anchor, const AABB& box, Visit&& visit) const {
  if (slots_.empty() || !Holds(area_, anchor)) return;
  const std::uint32_t cell = CellOf(anchor);
  for (std::uint32_t a = cell_starts_[cell]; a < cell_starts_[cell + 1]; ++a) {
    if (Overlap(bounds_[entries_[a]], box)) visit(slots_[entries_[a]]);
  }
  for (const std::uint32_t k : wide_) {
    if (Overlap(bounds_[k], box)) visit(slots_[k]);
  }
}

}  // namespace engine::detail
