// The solid bodies' bounds binned in a uniform grid, rebuilt each step, so a point (an effect
// particle) finds the few bodies near it without looking at all of them. Bodies are few and
// particles many, so the bodies are binned, not the particles: the particles are then visited
// in index order. Deterministic: each cell lists its bodies in slot order. Internal.
#pragma once

#include <cstdint>
#include <vector>

#include "bodies.h"
#include "engine/math.h"

namespace engine::detail {

class BodyBins {
 public:
  /// Bins the live, enabled bodies that are not sensors, each by its bounds grown by `margin`.
  void Build(const Bodies& bodies, double margin);
  bool Empty() const { return slots_.empty(); }

  /// Calls visit(body) for each binned body whose grown bounds hold `point`, in slot order.
  template <typename Visit>
  void ForEachAt(Vec2 point, Visit&& visit) const;

 private:
  static bool Holds(const AABB& box, Vec2 p) {
    return p.x >= box.lower.x && p.x <= box.upper.x && p.y >= box.lower.y && p.y <= box.upper.y;
  }
  std::uint32_t CellOf(Vec2 point) const;
  void ChooseCells(double median_side);

  std::vector<BodyIndex> slots_;  ///< the binned bodies, in slot order
  std::vector<AABB> bounds_;      ///< each binned body's grown bounds
  AABB area_;                     ///< all of them together
  double cell_ = 1.0;
  std::uint32_t columns_ = 1, rows_ = 1;
  std::vector<std::uint32_t> cell_starts_;  ///< into entries_, one more than the cells
  std::vector<std::uint32_t> entries_;      ///< indices into slots_, cell by cell, ascending
  /// Bodies covering more cells than this would fill many cells each: they are kept aside and
  /// tested at every point instead (a ground, a wall). Indices into slots_, ascending.
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
void BodyBins::ForEachAt(Vec2 point, Visit&& visit) const {
  if (slots_.empty() || !Holds(area_, point)) return;
  const std::uint32_t cell = CellOf(point);
  std::uint32_t a = cell_starts_[cell];
  const std::uint32_t a_end = cell_starts_[cell + 1];
  std::size_t w = 0;
  // Merge the cell's list with the wide bodies', both ascending, so bodies come in slot order.
  while (a < a_end || w < wide_.size()) {
    const bool from_cell = w == wide_.size() || (a < a_end && entries_[a] < wide_[w]);
    const std::uint32_t k = from_cell ? entries_[a++] : wide_[w++];
    if (Holds(bounds_[k], point)) visit(slots_[k]);
  }
}

}  // namespace engine::detail
