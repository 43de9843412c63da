// Levels by breadth-first search from the static bodies; a counting sort keeps ties in contact
// (body-pair) order, so the pass is deterministic.
#include "shock_propagation.h"


#include <algorithm>
#include <limits>

namespace engine::detail {

namespace {

constexpr std::uint32_t kUnreached = std::numeric_limits<std::uint32_t>::max();

}  // namespace

void BuildShockOrder(std::span<const SubstepConstraint> constraints, std::span<const BodyInfo> infos,
                     std::vector<std::uint32_t>* level, std::vector<std::uint32_t>* order) {
  const std::size_t n = infos.size();
  (*level).assign(n, kUnreached);
  // Adjacency as a compressed list, built in constraint order.
  std::vector<std::uint32_t> start(n + 1, 0), neighbours(2 * constraints.size());
  for (const SubstepConstraint& c : constraints) ++start[c.a + 1], ++start[c.b + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (const SubstepConstraint& c : constraints) {
    neighbours[fill[c.a]++] = c.b;
    neighbours[fill[c.b]++] = c.a;
  }
  std::vector<std::uint32_t> queue;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (infos[i].is_static) (*level)[i] = 0, queue.push_back(i);
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t body = queue[head];
    for (std::uint32_t k = start[body]; k < start[body + 1]; ++k) {
      const std::uint32_t other = neighbours[k];
      if ((*level)[other] != kUnreached) continue;
      (*level)[other] = (*level)[body] + 1;
      queue.push_back(other);
    }
  }
  // Counting sort by the lower level of each pair: linear, and stable, so ties stay in contact
  // (body-pair) order. Pairs touching nothing static come last.
  auto lower = [&](const SubstepConstraint& c) {
    const std::uint32_t l = std::min((*level)[c.a], (*level)[c.b]);
    return l == kUnreached ? static_cast<std::uint32_t>(queue.size()) : l;
  };
  std::vector<std::uint32_t> first(queue.size() + 2, 0);
  for (const SubstepConstraint& c : constraints) ++first[lower(c) + 1];
  for (std::size_t l = 1; l < first.size(); ++l) first[l] += first[l - 1];
  order->resize(constraints.size());
  for (std::uint32_t i = 0; i < constraints.size(); ++i) (*order)[first[lower(constraints[i])]++] = i;
}

void PropagateShock(std::span<const std::uint32_t> level, std::span<const std::uint32_t> order,
                    std::span<const SubstepConstraint> constraints, std::span<BodyState> states,
                    const StepStart& start, double inv_h, double linear_slop, Vec2 up,
                    double tolerance) {
  for (std::uint32_t index : order) {
    const SubstepConstraint& sc = constraints[index];
    // Only support: a contact whose normal is within 45° of up (from the lower body to the upper).
    // Side contacts are left to the solver: pushing rocking neighbours apart here would fight it.
    // Between turning bodies the pass stays out: holding a centre up would stop a box balanced
    // on a corner from toppling, and one-sided pushes rectify rocking into a pumping jitter.
    // Their contacts are solved by more passes instead (World's automatic settings).
    if (sc.angular) continue;
    const std::uint32_t level_a = level[sc.a], level_b = level[sc.b];
    const double support = Dot(sc.normal, up) * (level_a <= level_b ? 1.0 : -1.0);
    if (support < 0.70710678118654752) continue;
    BodyState& a = states[sc.a];
    BodyState& b = states[sc.b];
    const Vec2 n = sc.normal;
    // The tightest point decides: overlap still being pushed out is the solver's (its push-out
    // speed, carried up a stack here, could not be taken back later); a gap may close this far.
    double s = std::numeric_limits<double>::infinity();
    for (int k = 0; k < sc.point_count; ++k) s = std::min(s, CurrentSeparation(sc, sc.points[k], states, start));
    if (s < -linear_slop) continue;
    const double min_vn = -std::max(s, 0.0) * inv_h;
    // Sinking is a motion of the centres: judging approach at a corner instead would answer a
    // rocking box with a linear push and pump energy into a resting stack.
    const double vn = Dot(b.velocity - a.velocity, n);
    // Between turning bodies, small residues of the solve (rocking couples the contacts) are
    // the solver's to finish with impulses that have reactions; only sinking by more is caught
    // here. Without turning, the solve's residue is pure sinking and is caught whole.
    if (vn >= min_vn - (sc.angular ? tolerance : 0.0)) continue;
    // Which body gives: the upper one alone, or both by mass on one level.
    const double inv_a = level_a < level_b ? 0.0 : sc.inv_mass_a;
    const double inv_b = level_b < level_a ? 0.0 : sc.inv_mass_b;
    const double impulse = (min_vn - vn) / (inv_a + inv_b);
    a.velocity -= (impulse * inv_a) * n;
    b.velocity += (impulse * inv_b) * n;
  }
}

}  // namespace engine::detail
