// bench_soak: the default scene for 10⁶ steps (about 4.6 hours of game time) with random clicks
// from a fixed seed; prints energy, memory (heap in use, RSS, peak RSS) at intervals and fails
// on a non-finite number, energy above what clicks put in, or heap growth after warm-up.
//   bench_soak [STEPS] [SEED]      (defaults 1000000 and 1)
#include <sys/utsname.h>

#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>

#include "bench/bench_args.h"
#include "bench/soak.h"

int main(int argc, char** argv) {
  std::int64_t steps = 1'000'000;
  std::uint64_t seed = 1;
  bench::Args args("bench_soak", "The default scene for STEPS steps with random clicks: fails on a non-finite "
                                 "number, energy above what clicks put in, or heap growth after warm-up.");
  args.Positional("STEPS", &steps, "steps to run, at least 10 (default 1000000)")
      .Positional("SEED", &seed, "seed of the random clicks (default 1)");
  if (const std::optional<int> exit_code = args.Parse(argc, argv)) return *exit_code;
  if (steps < 10) return args.Error("STEPS is " + std::to_string(steps) + "; it must be at least 10");
  utsname machine{};
  uname(&machine);
  std::printf("bench_soak: default scene, %" PRId64 " steps, click every 30 steps, seed %" PRIu64
              "\nmachine: %s %s, build %s\n\n",
              steps, seed, machine.sysname, machine.machine, BALLBOX_BUILD_TYPE);

  soak::Soak run(seed);
  // Memory is judged after a warm-up: containers reach their working size in the first steps.
  const std::int64_t warm_up = steps / 10;
  std::size_t heap_after_warm_up = 0;
  std::size_t heap_max_after_warm_up = 0;
  double worst_excess = -1e300;
  const auto start = std::chrono::steady_clock::now();

  std::printf("%10s %8s %6s %14s %14s %12s %10s %10s %6s\n", "step", "clicks", "hits", "energy J",
              "injected J", "excess J", "heap KiB", "RSS KiB", "in box");
  auto report = [&](std::int64_t step) {
    std::printf("%10" PRId64 " %8" PRId64 " %6" PRId64 " %14.6g %14.6g %12.3g %10zu %10" PRId64
                " %6d\n",
                step, run.Clicks(), run.Hits(), soak::MechanicalEnergy(run.Session().World()),
                run.InjectedEnergy(), run.EnergyExcess(), soak::HeapBytesInUse() / 1024,
                soak::ProcStatusKiB("VmRSS"), run.BodiesInTheBox());
    std::fflush(stdout);
  };
  report(0);
  for (std::int64_t step = 1; step <= steps; ++step) {
    if (const std::optional<std::string> bad = run.Step()) {
      std::printf("FAIL: %s\n", bad->c_str());
      return 1;
    }
    worst_excess = std::max(worst_excess, run.EnergyExcess());
    if (step == warm_up) heap_after_warm_up = soak::HeapBytesInUse();
    if (step > warm_up) heap_max_after_warm_up = std::max(heap_max_after_warm_up, soak::HeapBytesInUse());
    if (step % (steps / 10) == 0) report(step);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const long long growth = static_cast<long long>(heap_max_after_warm_up) -
                           static_cast<long long>(heap_after_warm_up);
  std::printf("\n%" PRId64 " steps in %.1f s (%.1f µs/step); peak RSS %" PRId64
              " KiB; heap growth after warm-up %lld bytes; worst energy excess %.3g J\n",
              steps, seconds, 1e6 * seconds / steps, soak::ProcStatusKiB("VmHWM"), growth,
              worst_excess);
  // The limits the short soak test asserts too (tests/test_robustness_soak.cpp).
  const bool energy_ok = worst_excess <= 1.0;
  const bool memory_ok = growth <= 64 * 1024;
  std::printf("%s: no non-finite number, energy %s, memory %s\n",
              energy_ok && memory_ok ? "PASS" : "FAIL", energy_ok ? "bounded" : "ABOVE its bound",
              memory_ok ? "flat" : "GROWING");
  return energy_ok && memory_ok ? 0 : 1;
}
