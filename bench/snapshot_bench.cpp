// Snapshots (issue 15): size per body, and the time to take and restore one, for a pour of
// 1 000 and 10 000 circles in a box, against the time of one step of the same world, measured in
// the same run. `bench_snapshot [--repeats N]`.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/stress_scenes.h"
#include "engine/world.h"

namespace {

struct Figures {
  std::size_t bodies, contacts, bytes;
  double take_us, restore_us, step_us;
};

template <typename F>
double MedianMicroseconds(int repeats, F&& run) {
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) {
    const auto start = bench::Clock::now();
    run();
    times.push_back(std::chrono::duration<double, std::micro>(bench::Clock::now() - start).count());
  }
  return bench::Median(times);
}

Figures Measure(int count, int repeats) {
  engine::WorldDef def;
  def.rotation = true;
  engine::World world(def);
  stress::AddBoxedPour(world, count);
  for (int i = 0; i < 120; ++i) world.Step();  // falling and piling: contacts to carry
  std::vector<std::uint8_t> bytes;
  const double take = MedianMicroseconds(repeats, [&] { world.TakeSnapshot(&bytes); });
  engine::World target(def);
  const double restore = MedianMicroseconds(repeats, [&] {
    if (!target.RestoreSnapshot(bytes)) std::abort();
  });
  engine::World stepped(def);
  if (!stepped.RestoreSnapshot(bytes)) std::abort();
  const double step = MedianMicroseconds(repeats, [&] { stepped.Step(); });
  return {world.BodyCount(), world.Contacts().size(), bytes.size(), take, restore, step};
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 21;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0 && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_snapshot [--repeats N]\n");
      return 2;
    }
  }
  if (repeats < 1) repeats = 1;
  bench::PrintMachine("");
  std::printf("\nsnapshot of a circle pour after 120 steps (rotation on), median of %d repeats\n\n", repeats);
  std::printf("| bodies | contacts | bytes | bytes/body | take, µs | restore, µs | one step, µs |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const int count : {1000, 10000}) {
    const Figures f = Measure(count, repeats);
    std::printf("| %zu | %zu | %zu | %.1f | %.0f | %.0f | %.0f |\n", f.bodies, f.contacts, f.bytes,
                static_cast<double>(f.bytes) / static_cast<double>(f.bodies), f.take_us, f.restore_us, f.step_us);
  }
  return 0;
}
