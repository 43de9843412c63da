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
                    const StepStart& start, double inv_h, double linear_slop) {
  for (std::uint32_t index : order) {
    const SubstepConstraint& sc = constraints[index];
    BodyState& a = states[sc.a];
    BodyState& b = states[sc.b];
    const Vec2 n = sc.normal;
    // Which body gives: the upper one alone, or both by mass on one level.
    const std::uint32_t level_a = level[sc.a], level_b = level[sc.b];
    const double inv_a = level_a < level_b ? 0.0 : sc.inv_mass_a;
    const double inv_b = level_b < level_a ? 0.0 : sc.inv_mass_b;
    const double inv_ia = level_a < level_b ? 0.0 : sc.inv_inertia_a;
    const double inv_ib = level_b < level_a ? 0.0 : sc.inv_inertia_b;
    for (int k = 0; k < sc.point_count; ++k) {
      const SubstepPoint& p = sc.points[k];
      const double s = CurrentSeparation(sc, p, states, start);
      // Overlap still being pushed out is the solver's: its push-out speed, carried up a stack
      // here, could not be taken back later.
      if (s < -linear_slop) continue;
      const double min_vn = -std::max(s, 0.0) * inv_h;
      if (!sc.angular) {
        const double vn = Dot(b.velocity - a.velocity, n);
        if (vn >= min_vn) continue;
        const double impulse = (min_vn - vn) / (inv_a + inv_b);
        a.velocity -= (impulse * inv_a) * n;
        b.velocity += (impulse * inv_b) * n;
        continue;
      }
      const Vec2 relative = (b.velocity + Cross(b.angular_velocity, p.anchor_b)) -
                            (a.velocity + Cross(a.angular_velocity, p.anchor_a));
      const double vn = Dot(relative, n);
      if (vn >= min_vn) continue;
      const double ra = Cross(p.anchor_a, n), rb = Cross(p.anchor_b, n);
      const double impulse = (min_vn - vn) / (inv_a + inv_b + inv_ia * ra * ra + inv_ib * rb * rb);
      a.velocity -= (impulse * inv_a) * n;
      a.angular_velocity -= inv_ia * Cross(p.anchor_a, impulse * n);
      b.velocity += (impulse * inv_b) * n;
      b.angular_velocity += inv_ib * Cross(p.anchor_b, impulse * n);
    }
  }
}

}  // namespace engine::detail
