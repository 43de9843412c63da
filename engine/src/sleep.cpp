// Islands by union-find over touching contacts, in body-id order, so sleep is deterministic;
// waking, by island.
#include "sleep.h"

#include "union_find.h"

#include <algorithm>
#include <vector>

#include "parallel/per_thread.h"
#include "parallel/worker_pool.h"

namespace engine::detail {

namespace {

// Fewer pairs than this are looked over on the calling thread alone.
constexpr std::size_t kMinSharedPairs = 4096;

// One of the two bodies is awake and the other is a sleeper that an awake body wakes (not
// static, not kinematic, not disabled).
bool WakesSleeper(BodyIndex a, BodyIndex b, std::span<const BodyInfo> infos, SleepState sleep) {
  if ((sleep.awake[a] != 0) == (sleep.awake[b] != 0)) return false;
  const BodyIndex sleeper = sleep.awake[a] ? b : a;
  return !HasInfiniteMass(infos[sleeper]) && sleep.island[sleeper] != kNoBody;
}

bool Resting(BodyPair p, SleepState sleep) { return !sleep.awake[p.a] && !sleep.awake[p.b]; }

}  // namespace

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

// Shared, each thread looks over a part of the pairs for a sleeper to wake and counts the pairs
// where nothing moves. Waking is rare (an island touched): then, or when a spring or joint joins
// a sleeper to a body awake, everything goes on one thread, in pair order. Otherwise each thread
// copies the pairs it keeps into place in `scratch`, which becomes the list.
void WakeTouchedIslands(std::vector<BodyPair>* pairs, std::span<const Spring> springs,
                        std::span<const BodyPair> joint_links, std::span<const BodyInfo> infos, SleepState sleep,
                        WorkerPool* pool, std::vector<BodyPair>* scratch) {
  const std::size_t n = pairs->size();
  if (pool && scratch && pool->Threads() > 1 && n >= kMinSharedPairs) {
    const auto threads = static_cast<std::size_t>(pool->Threads());
    struct Part {
      bool wakes = false;
      std::size_t resting = 0;
    };
    std::vector<PerThread<Part>> parts(threads);
    const BodyPair* const all = pairs->data();
    pool->RunOnAll([&](int thread) {
      const auto t = static_cast<std::size_t>(thread);
      Part part;
      for (std::size_t k = n * t / threads; k < n * (t + 1) / threads; ++k) {
        part.wakes = part.wakes || WakesSleeper(all[k].a, all[k].b, infos, sleep);
        part.resting += Resting(all[k], sleep) ? 1 : 0;
      }
      parts[t].value = part;
    });
    const bool linked_sleeper =
        std::any_of(springs.begin(), springs.end(),
                    [&](const Spring& s) { return s.body_b && WakesSleeper(s.body_a, *s.body_b, infos, sleep); }) ||
        std::any_of(joint_links.begin(), joint_links.end(),
                    [&](const BodyPair& link) { return WakesSleeper(link.a, link.b, infos, sleep); });
    const bool wakes =
        linked_sleeper || std::any_of(parts.begin(), parts.end(), [](const auto& part) { return part.value.wakes; });
    if (!wakes) {
      std::size_t resting = 0;
      for (const auto& part : parts) resting += part.value.resting;
      if (resting == 0) return;
      scratch->resize(n - resting);
      pool->RunOnAll([&](int thread) {
        const auto t = static_cast<std::size_t>(thread);
        std::size_t out = n * t / threads;
        for (std::size_t u = 0; u < t; ++u) out -= parts[u].value.resting;
        for (std::size_t k = n * t / threads; k < n * (t + 1) / threads; ++k) {
          if (!Resting(all[k], sleep)) (*scratch)[out++] = all[k];
        }
      });
      pairs->swap(*scratch);
      return;
    }
  }
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
  std::erase_if(*pairs, [&](BodyPair p) { return Resting(p, sleep); });
}

}  // namespace engine::detail
