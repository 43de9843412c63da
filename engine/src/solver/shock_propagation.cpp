// Levels by breadth-first search from the static bodies; a counting sort keeps ties in
// constraint order, so the pass is deterministic.
#include "solver/shock_propagation.h"

#include <algorithm>
#include <limits>

namespace engine::detail {

namespace {

constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();

}  // namespace

template <typename C>
void BuildShockLevels(std::span<const C> constraints, std::span<const BodyInfo> infos, ShockScratch* s) {
  const std::size_t n = infos.size();
  s->level.assign(n, kUnreached);
  // Adjacency as a compressed list.
  s->start.assign(n + 1, 0);
  s->neighbours.resize(2 * constraints.size());
  for (const C& c : constraints) ++s->start[c.a + 1], ++s->start[c.b + 1];
  for (std::size_t i = 0; i < n; ++i) s->start[i + 1] += s->start[i];
  s->fill.assign(s->start.begin(), s->start.end() - 1);
  for (const C& c : constraints) {
    s->neighbours[s->fill[c.a]++] = c.b;
    s->neighbours[s->fill[c.b]++] = c.a;
  }
  // Whether a neighbour was reached already is as good as random, and mispredicted branches
  // cost most of the search: a neighbour is visited without one (every body enters the queue
  // at most once; one slot more takes the write past the last).
  s->queue.resize(n + 1);
  std::uint32_t* level = s->level.data();
  std::uint32_t* queue = s->queue.data();
  std::size_t tail = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (HasInfiniteMass(infos[i])) level[i] = 0, queue[tail++] = i;
  }
  for (std::size_t head = 0; head < tail; ++head) {
    const std::uint32_t body = queue[head];
    const std::uint32_t next = level[body] + 1;
    for (std::uint32_t k = s->start[body]; k < s->start[body + 1]; ++k) {
      const std::uint32_t other = s->neighbours[k];
      // A reached neighbour's level is at most `next`, so the minimum leaves it alone; written
      // as a minimum, the compiler keeps it branch-free (a select became a branch).
      const std::uint32_t was = level[other];
      level[other] = std::min(was, next);
      queue[tail] = other;
      tail += was == kUnreached;
    }
  }
  s->levels = tail == 0 ? 0 : level[queue[tail - 1]] + 1;  // the queue holds the bodies by level
}

template void BuildShockLevels(std::span<const BodyPair>, std::span<const BodyInfo>, ShockScratch*);
template void BuildShockLevels(std::span<const SubstepConstraint>, std::span<const BodyInfo>, ShockScratch*);
template void BuildShockLevels(std::span<const LinearConstraint>, std::span<const BodyInfo>, ShockScratch*);

template <typename C>
void BuildShockRows(std::span<const C> constraints, std::span<const BodyInfo> infos,
                    Vec2 up, ShockScratch* scratch, std::vector<ShockRow>* rows) {
  BuildShockLevels(constraints, infos, scratch);
  WriteShockRows(constraints, up, scratch);
  SortShockRows(scratch, rows);
}

template <typename C>
ShockRowWriter<C>::ShockRowWriter(std::span<const C> constraints, Vec2 up, ShockScratch* scratch)
    : constraints_(constraints), up_(up), scratch_(scratch) {
  scratch->bucket.resize(constraints.size());
  scratch->unsorted.resize(constraints.size());
}

template <typename C>
void ShockRowWriter<C>::Write(std::uint32_t begin, std::uint32_t end) const {
  const std::span<const std::uint32_t> level = scratch_->level;
  const Vec2 up = up_;
  ShockScratch* scratch = scratch_;
  // Each constraint's bucket: the lower level of a supporting pair (pairs touching nothing
  // static after all levels), or one past that for the rest. A counting sort by bucket is
  // linear and stable, so ties stay in constraint order, and the supporting rows come first.
  // Every constraint gets a row, without a branch on whether it supports or on which body is
  // the lower: either is as good as random, and mispredicted branches cost more than writing
  // the rows and choosing by bits (ChooseBits, masks).
  const auto unreached_bucket = static_cast<std::uint32_t>(scratch->levels);
  const std::uint32_t other_bucket = unreached_bucket + 1;
  for (std::uint32_t j = begin; j < end; ++j) {
    const C& c = constraints_[j];
    const std::uint32_t level_a = level[c.a], level_b = level[c.b];
    // Support (the header says why only this): the normal within 45° of up, from the lower
    // body (by level) to the upper one, between bodies that cannot turn.
    const double support = Dot(c.normal, up) * ChooseBits(level_a <= level_b, 1.0, -1.0);
    const bool supports = !Turns(c) & (support >= 0.70710678118654752);
    const std::uint32_t lower = std::min(level_a, level_b);
    const std::uint32_t reached = lower == kUnreached ? unreached_bucket : lower;
    const std::uint32_t keep = 0u - static_cast<std::uint32_t>(supports);  // all ones where it supports
    scratch->bucket[j] = (reached & keep) | (other_bucket & ~keep);
    // Which body gives: the upper one alone, or both by mass on one level.
    scratch->unsorted[j] = {c.a, c.b, c.normal, ChooseBits(level_a < level_b, 0.0, c.inv_mass_a),
                            ChooseBits(level_b < level_a, 0.0, c.inv_mass_b), Point(c, 0).base_separation};
  }
}

template <typename C>
void WriteShockRows(std::span<const C> constraints, Vec2 up, ShockScratch* scratch, WorkerPool* pool) {
  const ShockRowWriter<C> rows(constraints, up, scratch);
  // In constraint order, each run's constraints and rows one stretch of memory; in runs, to
  // whichever thread is free: the levels were found on another thread, and the half that reads
  // them cold is slower.
  const auto n = static_cast<std::uint32_t>(constraints.size());
  ForEachRun(pool, n, kMinSharedContacts, RunLength(pool, n, kMinSharedContacts),
             [&](std::uint32_t begin, std::uint32_t end) { rows.Write(begin, end); });
}

// A counting sort by bucket, stable, so ties stay in constraint order: the runs of the
// constraints count their buckets side by side; then each thread places the rows of its own
// buckets (the sorted list cut where the threads' parts hold as many rows), gathering which
// constraints those are in one pass over the buckets, then copying them. Each thread writes one
// stretch of the sorted rows: threads placing runs of the constraints wrote a little of every
// bucket each, side by side in memory, and on two cores the sort took longer than on one. The
// last bucket's rows (pairs that do not support) are not placed: the list ends before them.
void SortShockRows(ShockScratch* scratch, std::vector<ShockRow>* rows, WorkerPool* pool) {
  const std::span<const std::uint32_t> bucket = scratch->bucket;
  const auto n = static_cast<std::uint32_t>(bucket.size());
  const auto buckets = static_cast<std::uint32_t>(scratch->levels) + 2;  // levels, unreached, the rest
  const std::uint32_t run = RunLength(pool, n, kMinSharedContacts);
  const std::uint32_t runs = (n + run - 1) / run;
  std::vector<std::uint32_t>& counts = scratch->first;  // runs × buckets
  counts.assign(std::size_t{runs} * buckets, 0);
  ForEachRun(pool, n, kMinSharedContacts, run, [&](std::uint32_t begin, std::uint32_t end) {
    std::uint32_t* count = counts.data() + std::size_t{begin / run} * buckets;
    for (std::uint32_t j = begin; j < end; ++j) ++count[bucket[j]];
  });
  // Where each bucket starts in the sorted list; the last one's start is where the list ends.
  std::vector<std::uint32_t>& place = scratch->bucket_start;
  place.assign(buckets + 1, 0);
  for (std::uint32_t b = 0; b < buckets; ++b) {
    std::uint32_t total = 0;
    for (std::uint32_t r = 0; r < runs; ++r) total += counts[std::size_t{r} * buckets + b];
    place[b + 1] = place[b] + total;
  }
  const std::uint32_t supporting = place[buckets - 1];
  rows->resize(supporting);
  const int parts = runs > 1 ? pool->Threads() : 1;
  const auto place_part = [&](int part) {
    // This part's buckets: from the first whose rows start at or past its share of the list.
    const auto first_bucket = [&](int p) {
      const std::uint64_t target = std::uint64_t{supporting} * static_cast<std::uint64_t>(p) /
                                   static_cast<std::uint64_t>(parts);
      std::uint32_t b = 0;
      while (b < buckets - 1 && place[b] < target) ++b;
      return b;
    };
    const std::uint32_t low = first_bucket(part), high = part + 1 == parts ? buckets - 1 : first_bucket(part + 1);
    if (low >= high) return;
    std::vector<std::uint32_t>& mine = scratch->part_constraints[static_cast<std::size_t>(part)];
    mine.resize(std::size_t{n} + 1);  // one slot past: every constraint is written, kept or not
    std::uint32_t kept = 0;
    for (std::uint32_t j = 0; j < n; ++j) {  // branch-free: whose a bucket is is as good as random
      mine[kept] = j;
      kept += bucket[j] - low < high - low;
    }
    std::vector<std::uint32_t>& next = scratch->part_next[static_cast<std::size_t>(part)];
    next.assign(place.begin(), place.end());
    for (std::uint32_t k = 0; k < kept; ++k) {
      const std::uint32_t j = mine[k];
      (*rows)[next[bucket[j]]++] = scratch->unsorted[j];
    }
  };
  scratch->part_constraints.resize(static_cast<std::size_t>(parts));
  scratch->part_next.resize(static_cast<std::size_t>(parts));
  if (parts == 1) {
    place_part(0);
  } else {
    pool->RunOnAll(place_part);
  }
}

template void BuildShockRows(std::span<const SubstepConstraint>, std::span<const BodyInfo>, Vec2,
                             ShockScratch*, std::vector<ShockRow>*);
template void BuildShockRows(std::span<const LinearConstraint>, std::span<const BodyInfo>, Vec2,
                             ShockScratch*, std::vector<ShockRow>*);
template class ShockRowWriter<SubstepConstraint>;
template class ShockRowWriter<LinearConstraint>;
template void WriteShockRows(std::span<const SubstepConstraint>, Vec2, ShockScratch*, WorkerPool*);
template void WriteShockRows(std::span<const LinearConstraint>, Vec2, ShockScratch*, WorkerPool*);

std::size_t PropagateShock(std::span<const ShockRow> rows, std::span<BodyState> states, std::span<const Vec2> moved,
                           double inv_h, double linear_slop, bool branch_free) {
  PushChanges changes;
  if (branch_free) {
    for (const ShockRow& row : rows) changes.Add(PropagateRow<true>(row, states, moved, inv_h, linear_slop));
  } else {
    for (const ShockRow& row : rows) changes.Add(PropagateRow<false>(row, states, moved, inv_h, linear_slop));
  }
  return changes.count;
}

}  // namespace engine::detail
