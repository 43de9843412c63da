// Islands by union-find over touching contacts, in body-id order, so sleep is deterministic;
// waking, by island.
#include "sleep.h"

#include "union_find.h"

#include <algorithm>
#include <vector>

namespace engine::detail {

void UpdateSleep(std::span<const Contact> contacts, std::span<const Spring> springs,
                 std::span<const BodyPair> joint_links,
                 std::span<const Vec2> accelerations, std::span<BodyState> states,
                 std::span<const BodyInfo> infos, const WorldDef& def, SleepState sleep) {
  const std::size_t n = states.size();
  auto touching = [&](const Contact& c) {
    for (int p = 0; p < c.manifold.point_count; ++p) {
      if (c.manifold.points[p].depth >= -def.linear_slop) return true;
    }
    return false;
  };
  // A slow body rests only when something holds it (a touching contact) or nothing pushes it:
  // a body sinking slowly through a fluid, or at the top of its arc, is moving, not resting.
  // One that a moving kinematic body touches goes with it, however slowly: never at rest.
  constexpr std::uint8_t kHeld = 1, kCarried = 2;
  std::vector<std::uint8_t> held(n, 0);
  auto hold = [&](BodyIndex body, BodyIndex by) {
    held[body] = std::max(held[body], sleep.awake[by] == kKinematicMoving ? kCarried : kHeld);
  };
  for (const Contact& c : contacts) {
    if (!touching(c)) continue;
    hold(c.a, c.b);
    hold(c.b, c.a);
  }
  // A joint holds its bodies as a touching contact does (a pendulum at rest hangs, held).
  for (const BodyPair& link : joint_links) {
    hold(link.a, link.b);
    hold(link.b, link.a);
  }
  const double speed_squared = def.sleep_speed * def.sleep_speed;
  for (std::size_t i = 0; i < n; ++i) {
    if (sleep.awake[i] != kAwake) continue;
    const bool resting = LengthSquared(states[i].velocity) <= speed_squared &&
                         states[i].angular_velocity * states[i].angular_velocity <= speed_squared &&
                         held[i] != kCarried && (held[i] || accelerations[i] == Vec2{});
    sleep.rest_time[i] = resting ? sleep.rest_time[i] + def.dt : 0.0;
  }

  // The root of each island is its smallest body id: union always keeps the smaller root.
  // Touching contacts and acting springs between dynamic bodies join islands.
  UnionFind islands;
  islands.Reset(n);
  for (const Contact& c : contacts) {
    if (HasInfiniteMass(infos[c.a]) || HasInfiniteMass(infos[c.b]) || !touching(c)) continue;
    islands.Join(c.a, c.b);
  }
  for (const Spring& spring : springs) {
    if (spring.body_b && !HasInfiniteMass(infos[spring.body_a]) && !HasInfiniteMass(infos[*spring.body_b])) {
      islands.Join(spring.body_a, *spring.body_b);
    }
  }
  for (const BodyPair& link : joint_links) {
    if (!HasInfiniteMass(infos[link.a]) && !HasInfiniteMass(infos[link.b])) islands.Join(link.a, link.b);
  }
  std::vector<double> island_rest(n, def.time_to_sleep);
  for (std::uint32_t i = 0; i < n; ++i) {
    if (sleep.awake[i] != kAwake) continue;
    const std::uint32_t root = islands.Find(i);
    island_rest[root] = std::min(island_rest[root], sleep.rest_time[i]);
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    if (sleep.awake[i] != kAwake) continue;
    const std::uint32_t root = islands.Find(i);
    // Half a step of tolerance: thirty sixtieths add up to a hair under 0.5.
    if (island_rest[root] < def.time_to_sleep - 0.5 * def.dt) continue;
    sleep.awake[i] = 0;
    sleep.island[i] = root;
    states[i].velocity = {};
    states[i].angular_velocity = 0.0;
  }
}

Wakefulness WakefulnessOf(const BodyInfo& info, const BodyState& state) {
  if (info.is_static) return kResting;
  if (!info.is_kinematic) return kAwake;
  return state.velocity == Vec2{} && state.angular_velocity == 0.0 ? kResting : kKinematicMoving;
}

void WakeIsland(BodyIndex body, std::span<const BodyInfo> infos, SleepState sleep) {
  if (sleep.awake[body] || HasInfiniteMass(infos[body]) || sleep.island[body] == kNoBody) return;
  const std::uint32_t island = sleep.island[body];
  for (std::size_t i = 0; i < infos.size(); ++i) {
    if (!sleep.awake[i] && !HasInfiniteMass(infos[i]) && sleep.island[i] == island) {
      sleep.awake[i] = kAwake;
      sleep.rest_time[i] = 0.0;
    }
  }
}

void WakeTouchedIslands(std::vector<BodyPair>* pairs, std::span<const Spring> springs,
                        std::span<const BodyPair> joint_links,
                        std::span<const BodyInfo> infos, SleepState sleep) {
  for (const BodyPair& p : *pairs) {
    if ((sleep.awake[p.a] != 0) != (sleep.awake[p.b] != 0)) {
      const BodyIndex sleeper = sleep.awake[p.a] ? p.b : p.a;
      WakeIsland(sleeper, infos, sleep);
    }
  }
  for (const Spring& spring : springs) {
    if (!spring.body_b || (sleep.awake[spring.body_a] != 0) == (sleep.awake[*spring.body_b] != 0)) continue;
    const BodyIndex sleeper = sleep.awake[spring.body_a] ? *spring.body_b : spring.body_a;
    WakeIsland(sleeper, infos, sleep);
  }
  for (const BodyPair& link : joint_links) {
    if ((sleep.awake[link.a] != 0) == (sleep.awake[link.b] != 0)) continue;
    WakeIsland(sleep.awake[link.a] ? link.b : link.a, infos, sleep);
  }
  std::erase_if(*pairs, [&](BodyPair p) { return !sleep.awake[p.a] && !sleep.awake[p.b]; });
}

}  // namespace engine::detail
