// Levels by breadth-first search from the static bodies; a counting sort keeps ties in
// constraint order, so the pass is deterministic.
#include "shock_propagation.h"

#include <algorithm>
#include <limits>

namespace engine::detail {

namespace {

constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();

// Breadth-first levels from the static bodies through the contacts; returns how many bodies
// were reached.
template <typename C>
std::size_t BuildLevels(std::span<const C> constraints, std::span<const BodyInfo> infos,
                        ShockScratch* s) {
  const std::size_t n = infos.size();
  s->level.assign(n, kUnreached);
  // Adjacency as a compressed list, built in constraint order.
  s->start.assign(n + 1, 0);
  s->neighbours.resize(2 * constraints.size());
  for (const C& c : constraints) ++s->start[c.a + 1], ++s->start[c.b + 1];
  for (std::size_t i = 0; i < n; ++i) s->start[i + 1] += s->start[i];
  s->fill.assign(s->start.begin(), s->start.end() - 1);
  for (const C& c : constraints) {
    s->neighbours[s->fill[c.a]++] = c.b;
    s->neighbours[s->fill[c.b]++] = c.a;
  }
  s->queue.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    if (infos[i].is_static) s->level[i] = 0, s->queue.push_back(i);
  }
  for (std::size_t head = 0; head < s->queue.size(); ++head) {
    const std::uint32_t body = s->queue[head];
    for (std::uint32_t k = s->start[body]; k < s->start[body + 1]; ++k) {
      const std::uint32_t other = s->neighbours[k];
      if (s->level[other] != kUnreached) continue;
      s->level[other] = s->level[body] + 1;
      s->queue.push_back(other);
    }
  }
  return s->queue.size();
}

}  // namespace

template <typename C>
void BuildShockRows(std::span<const C> constraints, std::span<const BodyInfo> infos,
                    Vec2 up, ShockScratch* scratch, std::vector<ShockRow>* rows) {
  const std::size_t reached = BuildLevels(constraints, infos, scratch);
  const std::span<const std::uint32_t> level = scratch->level;
  // Which constraints support: the lower body (by level) below the upper one.
  auto supports = [&](const C& c) {
    if (Turns(c)) return false;
    const double support = Dot(c.normal, up) * (level[c.a] <= level[c.b] ? 1.0 : -1.0);
    return support >= 0.70710678118654752;
  };
  // Counting sort by the lower level of each pair: linear, and stable, so ties stay in
  // constraint order. Pairs touching nothing static come last.
  auto lower = [&](const C& c) {
    const std::uint32_t l = std::min(level[c.a], level[c.b]);
    return l == kUnreached ? static_cast<std::uint32_t>(reached) : l;
  };
  std::vector<std::uint32_t>& first = scratch->first;
  first.assign(reached + 2, 0);
  for (const C& c : constraints) {
    if (supports(c)) ++first[lower(c) + 1];
  }
  for (std::size_t l = 1; l < first.size(); ++l) first[l] += first[l - 1];
  rows->resize(first.back());
  for (const C& c : constraints) {
    if (!supports(c)) continue;
    // Which body gives: the upper one alone, or both by mass on one level.
    const std::uint32_t level_a = level[c.a], level_b = level[c.b];
    (*rows)[first[lower(c)]++] = {c.a, c.b, c.normal, level_a < level_b ? 0.0 : c.inv_mass_a,
                                  level_b < level_a ? 0.0 : c.inv_mass_b, Point(c, 0).base_separation};
  }
}

template void BuildShockRows(std::span<const SubstepConstraint>, std::span<const BodyInfo>, Vec2,
                             ShockScratch*, std::vector<ShockRow>*);
template void BuildShockRows(std::span<const LinearConstraint>, std::span<const BodyInfo>, Vec2,
                             ShockScratch*, std::vector<ShockRow>*);

void PropagateShock(std::span<const ShockRow> rows, std::span<BodyState> states,
                    std::span<const Vec2> start_positions, double inv_h, double linear_slop) {
  for (const ShockRow& row : rows) {
    BodyState& a = states[row.a];
    BodyState& b = states[row.b];
    const Vec2 n = row.normal;
    // Overlap still being pushed out is the solver's (its push-out speed, carried up a stack
    // here, could not be taken back later); a gap may close this far.
    const Vec2 moved = (b.position - start_positions[row.b]) - (a.position - start_positions[row.a]);
    const double s = row.base_separation + Dot(moved, n);
    if (s < -linear_slop) continue;
    const double min_vn = -std::max(s, 0.0) * inv_h;
    // Sinking is a motion of the centres, and the solve's residue here is pure sinking: it is
    // caught whole.
    const double vn = Dot(b.velocity - a.velocity, n);
    if (vn >= min_vn) continue;
    const double impulse = (min_vn - vn) / (row.inv_mass_a + row.inv_mass_b);
    a.velocity -= (impulse * row.inv_mass_a) * n;
    b.velocity += (impulse * row.inv_mass_b) * n;
  }
}

}  // namespace engine::detail
