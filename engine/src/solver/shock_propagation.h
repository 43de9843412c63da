// Shock propagation (Guendelman, Bridson and Fedkiw, "Nonconvex Rigid Bodies with Stacking",
// SIGGRAPH 2003): contacts visited from the ground up with the lower body held fixed, so that a
// stack cannot sink whatever its mass ratios. Internal to the engine.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "body_pair.h"
#include "engine/body.h"
#include "engine/contact.h"
#include "engine/spring.h"
#include "engine/world_def.h"
#include "parallel/worker_pool.h"
#include "solver/substep_passes.h"

namespace engine::detail {

/// One supporting contact as the pass needs it, in the order the pass visits it. Written once a
/// step and read every substep in order: the pass walks memory straight through instead of
/// jumping about the constraints.
struct ShockRow {
  BodyIndex a;
  BodyIndex b;
  Vec2 normal;             ///< from a to b
  double inv_mass_a;       ///< 0 when a is the lower body, held fixed
  double inv_mass_b;       ///< 0 when b is the lower body
  double base_separation;  ///< as in SubstepPoint: the separation follows from it and the centres
};

/// Scratch for BuildShockRows, kept between steps so a step allocates nothing.
struct ShockScratch {
  std::vector<std::uint32_t> level;  ///< per body: graph distance from a static body
  std::vector<std::uint32_t> start, neighbours, fill, queue, first;
  std::vector<std::uint32_t> bucket;  ///< per constraint: its bucket in the rows' counting sort
  std::vector<ShockRow> unsorted;     ///< per constraint: its row, in constraint order
  std::vector<std::uint32_t> bucket_start;  ///< per bucket, and one past: where its rows go
  /// SortShockRows' per thread: the constraints whose rows it places, and each bucket's next place.
  std::vector<std::vector<std::uint32_t>> part_constraints, part_next;
  std::size_t levels = 0;             ///< how many levels there are (the highest one's, plus one)
};

/// Each body's level (graph distance through the contacts from a static body), and how many
/// levels there are. `constraints`: anything with bodies a and b, one per contact, in any order: the
/// levels are distances, the same whatever order the search meets the contacts in.
template <typename C>
void BuildShockLevels(std::span<const C> constraints, std::span<const BodyInfo> infos, ShockScratch* scratch);

/// Each body's level (graph distance through contacts from a static body: static bodies 0,
/// bodies touching nothing static the highest), then the rows of the supporting contacts (normal
/// within 45° of `up`, the unit vector against gravity, from the lower body to the upper) of
/// pairs that cannot turn, ordered by their lower level, ties in constraint order: breadth-first
/// in body-id order, so the pass is deterministic.
///
/// Side contacts are left to the solver: pushing rocking neighbours apart here would fight it.
/// Between turning bodies the pass stays out: holding a centre up would stop a box balanced on a
/// corner from toppling, and one-sided pushes rectify rocking into a pumping jitter. Their
/// contacts are solved by more passes instead (World's automatic settings).
/// BuildShockLevels, WriteShockRows and SortShockRows in one, on one thread (the solver calls
/// the three apart, to share them among its threads).
template <typename C>
void BuildShockRows(std::span<const C> constraints, std::span<const BodyInfo> infos,
                    Vec2 up, ShockScratch* scratch, std::vector<ShockRow>* rows);

/// Writes constraints' rows and buckets in the order (BuildShockRows) into `scratch`, whose
/// levels are this step's, a range of constraints at a time: for a pass over the constraints
/// that can write their rows as it goes (each range writes only its own). Made once a step,
/// after the levels: it sizes the scratch for the constraints.
template <typename C>
class ShockRowWriter {
 public:
  ShockRowWriter(std::span<const C> constraints, Vec2 up, ShockScratch* scratch);
  /// The rows of constraints [begin, end).
  void Write(std::uint32_t begin, std::uint32_t end) const;

 private:
  std::span<const C> constraints_;
  Vec2 up_;
  ShockScratch* scratch_;
};

/// Each constraint's row and its bucket (ShockRowWriter), all of them; with a pool, in runs of
/// the constraints shared among its threads.
template <typename C>
void WriteShockRows(std::span<const C> constraints, Vec2 up, ShockScratch* scratch, WorkerPool* pool = nullptr);

/// The supporting rows WriteShockRows wrote, in the order BuildShockRows gives; with a pool,
/// sorted in runs shared among its threads (the same rows).
void SortShockRows(ShockScratch* scratch, std::vector<ShockRow>* rows, WorkerPool* pool = nullptr);

/// One pass over the rows: no contact within the slop may approach faster than its gap allows
/// this substep; the lower body of a pair is held fixed, bodies on one level share the impulse
/// by mass. Leaves the accumulated impulses alone: this pass only keeps stacks from sinking.
/// `moved`: each body's move since the step's start (MeasureMoves), made from the positions now.
/// `branch_free`: which form of PropagateRow takes the rows (the same bits either way). Returns
/// how often a row pushed where the row before it had not, or the other way round.
std::size_t PropagateShock(std::span<const ShockRow> rows, std::span<BodyState> states, std::span<const Vec2> moved,
                           double inv_h, double linear_slop, bool branch_free);

/// `if_set` where `set` holds, else `if_clear`: chosen by bits, not by a branch.
inline double ChooseBits(bool set, double if_set, double if_clear) {
  const std::uint64_t mask = std::uint64_t{0} - static_cast<std::uint64_t>(set);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(if_set) & mask) |
                               (std::bit_cast<std::uint64_t>(if_clear) & ~mask));
}

/// The part of a row that reads no velocity: how fast its pair may approach this substep, and
/// whether it is within the slop at all. Worked out from the moves alone, so a thread waiting
/// for the rows below its own can work out its rows' gaps meanwhile (ShockSchedule::Run).
struct ShockGap {
  double min_vn;  ///< the least relative normal velocity allowed
  bool live;      ///< the pair is not past the slop apart, so the row may push
};

/// `moved`: each body's move since the step's start (MeasureMoves), made from the positions now.
inline ShockGap GapOf(const ShockRow& row, std::span<const Vec2> moved, double inv_h, double linear_slop) {
  const double s = row.base_separation + Dot(moved[row.b] - moved[row.a], row.normal);
  // Overlap still being pushed out is the solver's (its push-out speed, carried up a stack
  // here, could not be taken back later); a gap may close this far.
  return {-std::max(s, 0.0) * inv_h, !(s < -linear_slop)};
}

/// One row of PropagateShock given its gap (GapOf); returns whether it pushed. A body the row
/// holds fixed (inverse mass 0) keeps its velocity, so that threads may share the bodies a pile
/// stands on.
///
/// Two forms, the same bits. Where whether a row pushes is as good as random (in the settled
/// 4 000-circle pour a quarter of the rows push, and 29 % push where the row before did not or
/// the other way round), the mispredicted branch costs more than working out every row's impulse
/// and choosing the velocities by bits (`kBranchFree`: that pass 575 -> 461 kcyc a step on one
/// thread). Where the rows that push come in long runs (a pyramid of base 40: half push, but
/// the answer changes at 7 % of the rows), the branch is nearly always right and the
/// branch-free form only costs (that pyramid took 6 % longer a step with it).
template <bool kBranchFree>
inline bool PushRow(const ShockRow& row, ShockGap gap, std::span<BodyState> states) {
  BodyState& a = states[row.a];
  BodyState& b = states[row.b];
  const Vec2 n = row.normal;
  const double min_vn = gap.min_vn;
  // Sinking is a motion of the centres, and the solve's residue here is pure sinking: it is
  // caught whole.
  const Vec2 va = a.velocity, vb = b.velocity;
  const double vn = Dot(vb - va, n);
  // Written as negations, so that a NaN pushes (it compares false both ways).
  const bool push = gap.live & !(vn >= min_vn);
  if constexpr (!kBranchFree) {
    if (!push) return false;
  }
  const double impulse = (min_vn - vn) / (row.inv_mass_a + row.inv_mass_b);
  const Vec2 pushed_a = va - (impulse * row.inv_mass_a) * n;
  const Vec2 pushed_b = vb + (impulse * row.inv_mass_b) * n;
  if constexpr (kBranchFree) {
    // A body the row holds fixed is not written even with its own velocity: other bands read it
    // meanwhile (a race), and a static body is never written. Its write goes aside instead.
    Vec2 aside;
    Vec2* const into_a = row.inv_mass_a != 0.0 ? &a.velocity : &aside;
    Vec2* const into_b = row.inv_mass_b != 0.0 ? &b.velocity : &aside;
    *into_a = {ChooseBits(push, pushed_a.x, va.x), ChooseBits(push, pushed_a.y, va.y)};
    *into_b = {ChooseBits(push, pushed_b.x, vb.x), ChooseBits(push, pushed_b.y, vb.y)};
  } else {
    if (row.inv_mass_a != 0.0) a.velocity = pushed_a;
    if (row.inv_mass_b != 0.0) b.velocity = pushed_b;
  }
  return push;
}

/// One row of PropagateShock, its gap and its push.
template <bool kBranchFree>
inline bool PropagateRow(const ShockRow& row, std::span<BodyState> states, std::span<const Vec2> moved,
                         double inv_h, double linear_slop) {
  return PushRow<kBranchFree>(row, GapOf(row, moved, inv_h, linear_slop), states);
}

/// How often, along the rows, whether a row pushes changes: about how often a branch on it is
/// mispredicted.
struct PushChanges {
  std::size_t count = 0;
  bool last = false;
  void Add(bool push) {
    count += push != last ? 1 : 0;
    last = push;
  }
};

/// Which form of PropagateRow the next pass takes, from the last pass's PushChanges: branch-free
/// where the answer changed at a fifth of the rows or more (the pour above: 29 %; pyramids of
/// base 20 and 40, faster branching: 14 % and 7 %).
class ShockRowForm {
 public:
  bool BranchFree() const { return branch_free_; }
  void Saw(std::size_t changes, std::size_t rows) { branch_free_ = 5 * changes >= rows; }

 private:
  bool branch_free_ = true;
};

}  // namespace engine::detail
