// The pair budget (engine::PairCollector, docs/limits.md) must never touch an ordinary scene: dense
// packings, big bodies carrying many small ones, long planks, turned boxes and crowds moving fast
// run bit for bit as without it, with no body near its quota. What it does to piles is tested in
// test_robustness.cpp; that every broad phase keeps the same pairs under it, in test_broadphase.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "world_builders.h"

namespace {

struct Run {
  std::uint64_t hash = 0;
  std::uint32_t most_charged = 0;   ///< over every step
  std::size_t crowded_steps = 0;    ///< steps with any body in a crowd
};

// Builds the bodies in a shuffled order when `shuffle` is set: ids then carry no geometry, so
// some bodies are charged with every neighbour (each pair goes to the higher id between equal
// widths), the worst case for the quota.
Run RunScene(const std::vector<engine::BodyDef>& bodies, engine::WorldDef def, int steps, bool budget) {
  def.pair_budget = budget;
  engine::World world(def);
  for (const engine::BodyDef& body : bodies) world.CreateBody(body);
  Run run;
  for (int i = 0; i < steps; ++i) {
    world.Step();
    run.most_charged = std::max(run.most_charged, world.MostChargedPairs());
    run.crowded_steps += world.CrowdedBodyCount() > 0;
  }
  REQUIRE_FALSE(world.Fault());
  run.hash = world.StateHash();
  return run;
}

// Runs the scene with and without the budget: the same hash, no crowd at any step, and the
// most pairs charged to one body no more than `most` (the geometry's answer), far below the quota.
void RequireUntouched(const std::string& name, const std::vector<engine::BodyDef>& bodies,
                      const engine::WorldDef& def, int steps, std::uint32_t most) {
  INFO(name << ", " << bodies.size() << " bodies, " << steps << " steps");
  const Run with = RunScene(bodies, def, steps, true);
  const Run without = RunScene(bodies, def, steps, false);
  INFO("most pairs charged to one body: " << with.most_charged);
  CHECK(with.crowded_steps == 0);
  CHECK(with.hash == without.hash);
  CHECK(with.most_charged <= most);
  CHECK(without.most_charged == 0);  // the budget off counts nothing
}

std::vector<engine::BodyDef> Shuffled(std::vector<engine::BodyDef> bodies, std::uint64_t seed) {
  // Statics first (the container), then the rest in a random order.
  const auto moving = std::stable_partition(bodies.begin(), bodies.end(),
                                            [](const engine::BodyDef& b) { return b.is_static; });
  std::mt19937_64 rng(seed);
  std::shuffle(moving, bodies.end(), rng);
  return bodies;
}

std::vector<engine::BodyDef> Container(double width, double height) {
  using testing::Box;
  using testing::Static;
  return {Static(Box({0, -0.5}, {width + 2, 1})), Static(Box({-0.5 * (width + 1), 0.5 * height}, {1, height})),
          Static(Box({0.5 * (width + 1), 0.5 * height}, {1, height}))};
}

}  // namespace

TEST_CASE("pair budget: a hexagonal packing of equal circles is untouched", "[budget]") {
  // 590 circles touching in rows offset by half a diameter, resting in a box they fill from wall
  // to wall: six neighbours each, the densest packing there is.
  std::vector<engine::BodyDef> bodies = Container(30, 40);
  for (int row = 0; row < 20; ++row) {
    const int n = row % 2 == 0 ? 30 : 29;
    for (int i = 0; i < n; ++i) {
      const double x = -14.5 + i + (row % 2 == 0 ? 0.0 : 0.5);
      bodies.push_back(testing::Circle({x, 0.5 + row * std::sqrt(3.0) / 2.0}, 0.5));
    }
  }
  // 6 circles and at most 2 walls: 8, whatever the ids.
  RequireUntouched("hexagonal packing", Shuffled(bodies, 1), engine::WorldDef{}, 180, 8);
}

TEST_CASE("pair budget: a square lattice of boxes is untouched", "[budget]") {
  // 25 x 25 unit boxes stacked edge to edge: each one's grown box meets all eight around it.
  std::vector<engine::BodyDef> bodies = Container(25, 40);
  for (int row = 0; row < 25; ++row) {
    for (int i = 0; i < 25; ++i) bodies.push_back(testing::Box({-12.0 + i, 0.5 + row}, {1, 1}));
  }
  RequireUntouched("square lattice", Shuffled(bodies, 2), engine::WorldDef{}, 180, 10);
}

TEST_CASE("pair budget: squares turned 45 degrees, packed edge to edge, are untouched", "[budget]") {
  // Diamonds in a lattice, turning freely, no gravity: a turned square's bounding box is √2 times
  // wider than it, and meets 12 others in this packing.
  std::vector<engine::BodyDef> bodies;
  const double d = std::sqrt(0.5);
  for (int row = 0; row < 24; ++row) {
    for (int i = 0; i < 24; ++i) {
      engine::BodyDef box = testing::Box({(i + row) * d, (i - row) * d}, {1, 1});
      box.angle = std::atan(1.0);
      bodies.push_back(box);
    }
  }
  engine::WorldDef def;
  def.gravity = {0, 0};
  def.rotation = true;
  RequireUntouched("turned squares", Shuffled(bodies, 3), def, 120, 12);
}

TEST_CASE("pair budget: a big box carrying many small circles is untouched", "[budget]") {
  // A 20 m dynamic slab on the floor with 400 circles of 5 cm on it: the slab touches all of
  // them, but each pair is charged to the narrower circle, which has a few neighbours only.
  std::vector<engine::BodyDef> bodies = Container(24, 10);
  bodies.push_back(testing::Box({0, 0.5}, {20, 1}));
  for (int row = 0; row < 2; ++row) {
    for (int i = 0; i < 200; ++i) {
      bodies.push_back(testing::Circle({-9.95 + 0.1 * i + 0.05 * row, 1.05 + 0.0866 * row}, 0.05));
    }
  }
  RequireUntouched("slab and small circles", Shuffled(bodies, 4), engine::WorldDef{}, 180, 8);
}

TEST_CASE("pair budget: a long plank under circles wider than it is untouched", "[budget]") {
  // A 10 m plank 10 cm thick (aspect 100: quota 256, the most) under a row of 80 circles
  // 12.5 cm across: every pair is charged to the plank, which holds them all (and the floor).
  std::vector<engine::BodyDef> bodies = Container(12, 10);
  bodies.push_back(testing::Box({0, 0.05}, {10, 0.1}));
  for (int i = 0; i < 80; ++i) bodies.push_back(testing::Circle({-4.9375 + 0.125 * i, 0.1625}, 0.0625));
  RequireUntouched("plank and circles", Shuffled(bodies, 5), engine::WorldDef{}, 120, 90);
}

TEST_CASE("pair budget: a dense crowd moving fast together is untouched", "[budget]") {
  // 400 touching circles flying together at half and at one and a half diameters a step: the
  // speculative margins grow every box by as much, so each meets the 24 in a 5 by 5 block around
  // it, or the 80 in a 9 by 9 one, and the quota grows with the box's area (from 16 to 66, or to
  // the most there is, 256).
  for (const int speed : {30, 90}) {
    std::vector<engine::BodyDef> bodies;
    for (int row = 0; row < 20; ++row) {
      for (int i = 0; i < 20; ++i) bodies.push_back(testing::Circle({1.0 * i, 1.0 * row}, 0.5, {1.0 * speed, 0}));
    }
    engine::WorldDef def;
    def.gravity = {0, 0};
    RequireUntouched("fast crowd at " + std::to_string(speed) + " m/s", Shuffled(bodies, 6), def, 60,
                     speed == 30 ? 24 : 80);
  }
}

TEST_CASE("pair budget: the stress scenes are untouched", "[budget]") {
  struct Scene {
    std::string name;
    std::function<void(engine::World&)> build;
    bool rotation;
  };
  const std::vector<Scene> scenes = {
      {"pyramid of 30", [](engine::World& w) { stress::AddPyramid(w, 30); }, false},
      {"pyramid of 20, turning", [](engine::World& w) { stress::AddPyramid(w, 20); }, true},
      {"overlapping pyramid", [](engine::World& w) { stress::AddPyramid(w, 20, 0.25); }, false},
      {"pour of 1000 circles", [](engine::World& w) {
         stress::AddContainer(w, 40, 60);
         stress::AddCirclePour(w, 1000, 0.25, 40);
       }, false},
  };
  for (const Scene& scene : scenes) {
    INFO(scene.name);
    std::uint64_t hashes[2];
    std::uint32_t most = 0;
    for (bool budget : {true, false}) {
      engine::WorldDef def;
      def.rotation = scene.rotation;
      def.pair_budget = budget;
      engine::World world(def);
      scene.build(world);
      for (int i = 0; i < 240; ++i) {
        world.Step();
        CHECK(world.CrowdedBodyCount() == 0);
        most = std::max(most, world.MostChargedPairs());
      }
      hashes[budget] = world.StateHash();
    }
    INFO("most pairs charged to one body: " << most);
    CHECK(hashes[0] == hashes[1]);
    CHECK(most <= 12);
  }
}
