// bench_skip's pairs of worlds, each feature absent and present with nothing to do, step 10 times
// to the same state hash (the benchmark adds the cost; no timing here).
#include <catch2/catch.hpp>

#include "bench/skip_ablation_scenes.h"
#include "engine/world.h"

TEST_CASE("every skip-ablation pair steps 10 times to identical state hashes", "[bench]") {
  for (const skip_ablation::Ablation& a : skip_ablation::Ablations()) {
    INFO(a.feature);
    engine::World absent = a.absent();
    engine::World present = a.present();
    REQUIRE(absent.BodyCount() == present.BodyCount());
    for (int step = 0; step < 10; ++step) {
      absent.Step();
      present.Step();
    }
    CHECK(absent.StateHash() == present.StateHash());
  }
}
