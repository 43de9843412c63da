// The soak in short: the default scene for 20 000 steps with random clicks (bench_soak runs 10⁶):
// no non-finite number, energy never above its start plus what the clicks put in, heap flat.
#include <catch2/catch.hpp>

#include "bench/soak.h"

TEST_CASE("soak: 20 000 steps of the default scene with random clicks stay finite, bounded, flat",
          "[robustness][soak]") {
  soak::Soak run(/*seed=*/1);
  std::size_t heap_after_warm_up = 0;
  std::size_t heap_max = 0;
  double worst_excess = -1e300;
  for (int step = 1; step <= 20'000; ++step) {
    const std::optional<std::string> bad = run.Step();
    if (bad) FAIL(*bad);
    worst_excess = std::max(worst_excess, run.EnergyExcess());
    // Containers reach their working size while the first clicks land; after that nothing grows.
    if (step == 2'000) heap_after_warm_up = soak::HeapBytesInUse();
    if (step > 2'000) heap_max = std::max(heap_max, soak::HeapBytesInUse());
  }
  INFO("clicks " << run.Clicks() << ", hits " << run.Hits() << ", injected " << run.InjectedEnergy()
                 << " J, initial " << run.InitialEnergy() << " J");
  // The run does something: the clicks hit balls and move energy in and out.
  CHECK(run.Hits() >= 100);
  // Contacts, friction and the integrator only remove energy; 1 J covers rounding in sums that
  // reach 10⁵ J once a ball thrown out of the box has fallen a while.
  CHECK(worst_excess <= 1.0);
  // Growth, not the level: other tests in this process hold memory of their own.
  CHECK(heap_max <= heap_after_warm_up + 64 * 1024);
}
