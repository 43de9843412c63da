// The worker pool: every index visited exactly once, at any thread count and loop size, and the
// fluid's answer the same bits on one thread or several.
#include <catch2/catch.hpp>
#include <vector>

#include "engine/world.h"
#include "parallel/worker_pool.h"
#include "world_builders.h"

TEST_CASE("ParallelFor visits every index once, whatever the threads and the count", "[parallel]") {
  for (const int threads : {1, 2, 3, 5}) {
    engine::detail::WorkerPool pool(threads);
    REQUIRE(pool.Threads() == threads);
    for (const std::uint32_t count : {0u, 1u, 2u, 7u, 1000u, 4099u}) {
      for (int repeat = 0; repeat < 3; ++repeat) {  // the pool's threads are reused
        std::vector<int> visits(count, 0);
        pool.ParallelFor(count, 1, [&](std::uint32_t i) { ++visits[i]; });
        INFO(threads << " threads, " << count << " indices");
        REQUIRE(std::count(visits.begin(), visits.end(), 1) == static_cast<long>(count));
      }
    }
  }
}

TEST_CASE("a fluid steps to the same bits on one, two and three threads", "[parallel][fluid]") {
  const auto run = [](int threads) {
    engine::WorldDef def;
    def.particles.threads = threads;
    engine::World world(def);
    world.CreateBody(testing::Static(testing::Box({0.0, -0.5}, {6.0, 1.0})));
    engine::FluidDef water;  // 2 400 particles: enough that every pass is split
    water.region = {{-1.0, 0.0}, {1.0, 1.5}};
    water.spacing = 0.035;
    water.viscosity = 0.05;
    water.vorticity = 0.1;
    world.AddFluid(water);
    for (int s = 0; s < 30; ++s) world.Step();
    return world.StateHash();
  };
  const auto one = run(1);
  REQUIRE(run(2) == one);
  REQUIRE(run(3) == one);
}
