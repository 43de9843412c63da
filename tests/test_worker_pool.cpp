// The worker pool: every index visited exactly once, at any thread count and loop size, and the
// fluid's and the effects' answers the same bits on one thread or several.
#include <catch2/catch.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
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

namespace {

// Calls share(body) with a body(begin, end) that counts its visits, then requires every index of
// [0, count) visited once, in runs that start at multiples of `run` and are at most that long.
template <typename Share>
void RequireRunsCoverOnce(std::uint32_t count, std::uint32_t run, Share&& share) {
  std::vector<int> visits(count, 0);
  std::atomic<int> bad_runs{0};
  share([&](std::uint32_t begin, std::uint32_t end) {
    if (begin % run != 0 || end <= begin || end - begin > run || end > count) ++bad_runs;
    for (std::uint32_t i = begin; i < end; ++i) ++visits[i];
  });
  REQUIRE(bad_runs == 0);
  REQUIRE(std::count(visits.begin(), visits.end(), 1) == static_cast<long>(count));
}

}  // namespace

TEST_CASE("ParallelRuns and ForEachIndexInRuns visit every index once, in runs of the size asked", "[parallel]") {
  for (const int threads : {1, 2, 3}) {
    engine::detail::WorkerPool pool(threads);
    for (const std::uint32_t count : {0u, 1u, 63u, 64u, 65u, 5000u}) {
      for (const std::uint32_t run : {1u, 64u, 1000u}) {
        INFO(threads << " threads, " << count << " indices in runs of " << run);
        RequireRunsCoverOnce(count, run, [&](const auto& body) { pool.ParallelRuns(count, 1, run, body); });
      }
      std::vector<int> visits(count, 0);
      engine::detail::ForEachIndexInRuns(&pool, count, 1, [&](std::uint32_t i) { ++visits[i]; });
      REQUIRE(std::count(visits.begin(), visits.end(), 1) == static_cast<long>(count));
    }
  }
}

TEST_CASE("ForEachRun deals out runs of RunLength: one run unshared, about three a thread shared", "[parallel]") {
  // Below the threshold, on one thread or without a pool, a loop is one run (its per-run results
  // one slot); shared, 2 and 3 threads get 3 runs each (kRunsPerThread), give or take the last.
  for (const int threads : {1, 2, 3}) {
    engine::detail::WorkerPool pool(threads);
    for (const std::uint32_t count : {0u, 1u, 99u, 100u, 5000u}) {
      INFO(threads << " threads, " << count << " indices");
      const std::uint32_t run = engine::detail::RunLength(&pool, count, 100);
      const std::uint32_t runs = (count + run - 1) / run;
      const bool shared = threads > 1 && count >= 100;
      const std::uint32_t expected_runs =
          shared ? engine::detail::kRunsPerThread * static_cast<std::uint32_t>(threads) : std::min(count, 1u);
      CHECK(runs == expected_runs);
      RequireRunsCoverOnce(count, run, [&](const auto& body) {
        engine::detail::ForEachRun(&pool, count, 100, run, body);
      });
      const std::uint32_t alone = engine::detail::RunLength(nullptr, count, 100);
      CHECK(alone == std::max(count, 1u));
      RequireRunsCoverOnce(count, alone, [&](const auto& body) {
        engine::detail::ForEachRun(nullptr, count, 100, alone, body);
      });
    }
  }
}

TEST_CASE("RunSideBySideThenShare runs each task once and visits every shared index once", "[parallel]") {
  for (const int threads : {1, 2, 3}) {
    engine::detail::WorkerPool pool(threads);
    for (const std::uint32_t count : {0u, 1u, 63u, 64u, 65u, 1000u}) {
      for (const std::uint32_t run : {1u, 7u, 64u}) {
        for (int repeat = 0; repeat < 3; ++repeat) {  // the pool's threads are reused
          INFO(threads << " threads, " << count << " indices in runs of " << run);
          int firsts = 0, seconds = 0;
          RequireRunsCoverOnce(count, run, [&](const auto& body) {
            pool.RunSideBySideThenShare([&] { ++firsts; }, [&] { ++seconds; }, count, run, body);
          });
          REQUIRE(firsts == 1);
          REQUIRE(seconds == 1);
        }
      }
    }
  }
}

TEST_CASE("RunSideBySideThenShareAfterFirst: the shared runs see everything the first task wrote", "[parallel]") {
  // The first task writes every index slowly, the second does nothing: a shared run must never
  // start before the first task is done, whichever thread takes it.
  for (const int threads : {1, 2, 3}) {
    engine::detail::WorkerPool pool(threads);
    for (int repeat = 0; repeat < 20; ++repeat) {
      INFO(threads << " threads, repeat " << repeat);
      constexpr std::uint32_t kCount = 4096;
      std::vector<std::uint32_t> written(kCount, 0), seen(kCount, 0);
      int seconds = 0;
      const auto first = [&] {
        for (std::uint32_t i = 0; i < kCount; ++i) {
          volatile double slow = 1.0;
          for (int k = 0; k < 20; ++k) slow = slow * 1.0000001;
          written[i] = i + 1;
        }
      };
      pool.RunSideBySideThenShareAfterFirst(first, [&] { ++seconds; }, kCount, 64,
                                            [&](std::uint32_t begin, std::uint32_t end) {
                                              for (std::uint32_t i = begin; i < end; ++i) seen[i] = written[i];
                                            });
      REQUIRE(seconds == 1);
      for (std::uint32_t i = 0; i < kCount; ++i) REQUIRE(seen[i] == i + 1);
    }
  }
}

TEST_CASE("a pool whose worker does not run goes alone for a while, then shares again", "[parallel]") {
  // Steps (BeginStep to EndStep) whose calling thread waits nearly all of each for a worker that
  // stands still (here it sleeps 20 ms, as one whose core another program holds): after
  // kMissingWorkerSteps of them in a row the pool runs its jobs on the calling thread alone for
  // kAloneSteps steps, then shares them again, judging from the next step but one. The first
  // step is never judged (the workers may be asleep).
  using namespace std::chrono_literals;
  engine::detail::WorkerPool pool(2);
  REQUIRE(pool.Threads() == 2);
  std::vector<int> ran(2, 0);
  const auto stalled_step = [&] {
    pool.BeginStep();
    pool.RunOnAll([&](int thread) {
      ++ran[static_cast<std::size_t>(thread)];
      if (thread == 1) std::this_thread::sleep_for(20ms);
    });
    pool.EndStep();
  };
  const auto stalled_steps_until_alone = [&] {
    for (int step = 0; step < engine::detail::kMissingWorkerSteps; ++step) {
      REQUIRE(pool.Threads() == 2);
      stalled_step();
    }
  };
  stalled_step();  // the first step: not judged
  stalled_steps_until_alone();
  const int shared_steps = 1 + engine::detail::kMissingWorkerSteps;
  CHECK(ran == std::vector<int>{shared_steps, shared_steps});
  CHECK(pool.Threads() == 1);
  for (int step = 0; step < engine::detail::kAloneSteps; ++step) {
    REQUIRE(pool.Threads() == 1);
    pool.BeginStep();
    pool.RunOnAll([&](int thread) { ++ran[static_cast<std::size_t>(thread)]; });  // on the caller alone
    pool.EndStep();
  }
  CHECK(ran == std::vector<int>{shared_steps + engine::detail::kAloneSteps, shared_steps});
  CHECK(pool.Threads() == 2);
  stalled_step();  // the first step shared again: not judged
  stalled_steps_until_alone();
  CHECK(pool.Threads() == 1);
}

TEST_CASE("a fluid steps to the same bits on one, two and three threads", "[parallel][fluid]") {
  const auto run = [](int threads) {
    engine::WorldDef def;
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
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

TEST_CASE("two fluids of different densities step to the same bits on one, two and three threads",
          "[parallel][fluid]") {
  // Unequal masses take the fluid's other pair loop (masses looked up per pair): its chunks'
  // spill sums must add up the same with any thread count too.
  const auto run = [](int threads) {
    engine::WorldDef def;
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
    engine::World world(def);
    world.CreateBody(testing::Static(testing::Box({0.0, -0.5}, {6.0, 1.0})));
    engine::FluidDef oil;  // 2 400 particles in all: two chunks or more
    oil.region = {{-1.0, 0.0}, {1.0, 0.7}};
    oil.spacing = 0.035;
    oil.density = 600.0;
    oil.viscosity = 0.05;
    world.AddFluid(oil);
    engine::FluidDef water = oil;
    water.region = {{-1.0, 0.7}, {1.0, 1.5}};
    water.density = 1000.0;
    world.AddFluid(water);
    for (int s = 0; s < 30; ++s) world.Step();
    return world.StateHash();
  };
  const auto one = run(1);
  REQUIRE(run(2) == one);
  REQUIRE(run(3) == one);
}

TEST_CASE("20 000 effect particles move and bounce to the same bits on one, two and three threads", "[parallel][effects]") {
  const auto run = [](int threads) {
    engine::WorldDef def;
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
    engine::World world(def);
    world.CreateBody(testing::Static(testing::Box({0.0, -0.5}, {8.0, 1.0})));
    engine::BodyDef tilted = testing::Static(testing::Box({0.5, 1.0}, {2.0, 0.2}));
    tilted.angle = -0.4;
    world.CreateBody(tilted);
    engine::EmitterDef spray;  // about 20 000 alive at once: enough that every pass is split
    spray.position = {0.0, 3.0};
    spray.direction = -1.2;
    spray.spread = 1.0;
    spray.rate = 20000.0;
    spray.max_particles = 30000;
    spray.lifetime = 1.0;
    spray.size_start = spray.size_end = 0.02;
    world.CreateEmitter(spray);
    for (int s = 0; s < 90; ++s) world.Step();
    return std::vector<engine::EffectParticle>(world.Effects().begin(), world.Effects().end());
  };
  const auto one = run(1);
  REQUIRE(one.size() > 16384);
  // Some have bounced: they were turned upwards by the bodies, which nothing else does.
  REQUIRE(std::any_of(one.begin(), one.end(), [](const engine::EffectParticle& p) { return p.velocity.y > 0.5; }));
  for (const int threads : {2, 3}) {
    const auto other = run(threads);
    REQUIRE(other.size() == one.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      INFO(threads << " threads, particle " << i);
      REQUIRE(other[i].position.x == one[i].position.x);
      REQUIRE(other[i].position.y == one[i].position.y);
      REQUIRE(other[i].velocity.x == one[i].velocity.x);
      REQUIRE(other[i].velocity.y == one[i].velocity.y);
    }
  }
}
