// What particles cost beside the rigid bodies. Effects: about 10 000 live sparks and smoke puffs
// among 20 boxes (10 static, 10 dynamic) on a floor, with and without collisions, against the
// same world without emitters, so the difference is the effects' alone; and a pour of rigid
// circles in a box for the cost of one rigid body's step, measured in the same run. Times are
// the thread's CPU time (the machine is shared). Then the colliding effects on one thread and on
// two (WorldDef::threads), and dam breaks of 2 500 and 10 000 fluid particles on one
// and two, by the wall clock, since two threads share the work.
// `bench_particles [--steps N] [--repeats N] [--out DIR]`.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/stress_scenes.h"
#include "engine/world.h"

namespace {

struct Options {
  int steps = 60;
  int repeats = 9;
  std::string out_dir = "bench-out/particles";
};

enum class Effects { kNone, kPassThrough, kColliding };

// Floor, 10 static boxes at fixed places and 10 dynamic ones dropped on them, and optionally two
// spark showers (2 × 2500/s living 1.2 s) and a smoke column (2000/s living 2 s): about 10 000 live.
engine::World EffectsScene(Effects effects, int threads = 1, double rate_scale = 1.0) {
  engine::WorldDef def;
  def.rotation = true;
  def.threads = threads;
  engine::World world(def);
  world.CreateBody(stress::Ground({0, -0.5}, {40, 1}));
  for (int i = 0; i < 10; ++i) {
    const double x = -9.0 + 2.0 * i;
    world.CreateBody(stress::Ground({x, 1.0 + 0.6 * (i % 3)}, {0.8, 0.3}));
    world.CreateBody(stress::Box({x + 0.4, 4.0 + 0.5 * i}, {0.7, 0.7}));
  }
  if (effects == Effects::kNone) return world;
  engine::EmitterDef sparks;
  sparks.direction = -std::numbers::pi / 2;
  sparks.spread = 0.9;
  sparks.speed = 6.0;
  sparks.speed_spread = 2.0;
  sparks.rate = 2500.0 * rate_scale;
  sparks.max_particles = 1000000;
  sparks.lifetime = 1.2;
  sparks.size_start = 0.04;
  sparks.size_end = 0.02;
  sparks.restitution = 0.5;
  sparks.collide = effects == Effects::kColliding;
  for (const double x : {-5.0, 4.0}) {
    sparks.position = {x, 8.0};
    sparks.seed = static_cast<std::uint64_t>(x + 10.0);
    world.CreateEmitter(sparks);
  }
  engine::EmitterDef smoke = sparks;
  smoke.position = {0.0, 0.2};
  smoke.direction = std::numbers::pi / 2;
  smoke.spread = 0.4;
  smoke.speed = 1.0;
  smoke.speed_spread = 0.5;
  smoke.rate = 2000.0 * rate_scale;
  smoke.lifetime = 2.0;
  smoke.buoyancy = 1.3;
  smoke.drag = 1.0;
  smoke.size_start = 0.1;
  smoke.size_end = 0.4;
  smoke.blend = engine::EffectBlend::kAlpha;
  world.CreateEmitter(smoke);
  return world;
}

// µs per step: the median over repeats of `steps` steps each, by the thread's CPU time.
double MicrosecondsPerStep(engine::World& world, const Options& options) {
  std::vector<double> times;
  for (int r = 0; r < options.repeats; ++r) {
    const double start = bench::ThreadSeconds();
    for (int s = 0; s < options.steps; ++s) world.Step();
    times.push_back(1e6 * (bench::ThreadSeconds() - start) / options.steps);
  }
  return bench::Median(times);
}

struct Row {
  std::string scene;
  std::size_t bodies, particles;
  double us_per_step;
};

Row Measure(const std::string& name, engine::World world, const Options& options) {
  for (int i = 0; i < 180; ++i) world.Step();  // 3 s: the boxes settle, the effects fill up
  const double us = MicrosecondsPerStep(world, options);
  return {name, world.BodyCount(), world.Effects().size(), us};
}

engine::World CirclePour(int count) {
  engine::WorldDef def;
  def.rotation = true;
  engine::World world(def);
  stress::AddBoxedPour(world, count);
  return world;
}

// A dam break: a block of water `count` particles 0.05 m apart, twice as wide as tall, released
// in a tank three times its width. Stepped 1 s first, so the measured steps are mid-splash.
engine::World DamBreak(int count, int threads) {
  engine::WorldDef def;
  def.threads = threads;
  engine::World world(def);
  const double spacing = 0.05;
  const double height = std::round(std::sqrt(count / 2.0)) * spacing;
  const double width = 2.0 * height, tank = 3.0 * width;
  world.CreateBody(stress::Ground({0.0, -0.5}, {tank + 2.0, 1.0}));
  world.CreateBody(stress::Ground({-0.5 * tank - 0.5, 2.0 * height}, {1.0, 4.0 * height}));
  world.CreateBody(stress::Ground({0.5 * tank + 0.5, 2.0 * height}, {1.0, 4.0 * height}));
  engine::FluidDef water;
  water.spacing = spacing;
  water.viscosity = 0.02;
  water.region = {{-0.5 * tank, 0.0}, {-0.5 * tank + width, height}};
  world.AddFluid(water);
  return world;
}

// ms per step by the wall clock: the median over repeats of `steps` steps each.
double WallMillisecondsPerStep(engine::World& world, const Options& options) {
  std::vector<double> times;
  for (int r = 0; r < options.repeats; ++r) {
    const auto start = bench::Clock::now();
    for (int s = 0; s < options.steps; ++s) world.Step();
    times.push_back(1e3 * bench::SecondsSince(start) / options.steps);
  }
  return bench::Median(times);
}

// The colliding effects' wall time beyond the bodies', on `threads` threads.
struct EffectsThreadRow {
  int threads;
  std::size_t particles;
  double with_ms, bodies_ms;
};

EffectsThreadRow MeasureEffectsThreads(int threads, double rate_scale, const Options& options) {
  engine::World with = EffectsScene(Effects::kColliding, threads, rate_scale);
  engine::World bodies = EffectsScene(Effects::kNone, threads);
  for (int i = 0; i < 180; ++i) with.Step(), bodies.Step();
  return {threads, with.Effects().size(), WallMillisecondsPerStep(with, options),
          WallMillisecondsPerStep(bodies, options)};
}

struct FluidRow {
  std::size_t particles;
  int threads;
  double ms_per_step;
};

FluidRow MeasureFluid(int count, int threads, const Options& options) {
  engine::World world = DamBreak(count, threads);
  for (int i = 0; i < 60; ++i) world.Step();
  const double ms = WallMillisecondsPerStep(world, options);
  return {world.FluidPositions().size(), threads, ms};
}

bool ParseOptions(int argc, char** argv, Options* options) {
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--steps") == 0 && has_value) {
      options->steps = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--repeats") == 0 && has_value) {
      options->repeats = std::max(1, std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--out") == 0 && has_value) {
      options->out_dir = argv[++i];
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!ParseOptions(argc, argv, &options)) {
    std::fprintf(stderr, "usage: bench_particles [--steps N] [--repeats N] [--out DIR]\n");
    return 2;
  }
  const std::string load = bench::LoadAverage();
  std::vector<Row> rows;
  bench::Progress("effects: bodies alone");
  rows.push_back(Measure("20 boxes, no emitters", EffectsScene(Effects::kNone), options));
  bench::Progress("effects: passing through");
  rows.push_back(Measure("20 boxes + effects, collide off", EffectsScene(Effects::kPassThrough), options));
  bench::Progress("effects: colliding");
  rows.push_back(Measure("20 boxes + effects, colliding", EffectsScene(Effects::kColliding), options));
  bench::Progress("rigid circles");
  rows.push_back(Measure("1000 rigid circles poured", CirclePour(1000), options));
  std::vector<EffectsThreadRow> effects_threads;
  for (const double rate_scale : {1.0, 5.0}) {
    for (const int threads : {1, 2}) {
      bench::Progress("effects: colliding, " + std::to_string(threads) + " thread(s)");
      effects_threads.push_back(MeasureEffectsThreads(threads, rate_scale, options));
    }
  }
  std::vector<FluidRow> fluid;
  for (const int count : {2500, 10000}) {
    for (const int threads : {1, 2}) {
      bench::Progress("fluid: " + std::to_string(count) + " particles, " + std::to_string(threads) + " thread(s)");
      fluid.push_back(MeasureFluid(count, threads, options));
    }
  }
  bench::Progress("");
  bench::PrintMachine(load);
  std::printf("\nmedian of %d repeats of %d steps (dt 1/60, rotation on), after 180 steps to fill up\n\n",
              options.repeats, options.steps);
  std::printf("| scene | bodies | effect particles | µs/step |\n|---|---:|---:|---:|\n");
  for (const Row& r : rows) {
    std::printf("| %s | %zu | %zu | %.1f |\n", r.scene.c_str(), r.bodies, r.particles, r.us_per_step);
  }
  const double body_us = rows[3].us_per_step / static_cast<double>(rows[3].bodies);
  std::printf("\n| effect particles | µs/step beyond the bodies | ns per particle-step | particles/s stepped | "
              "× a rigid circle's cost |\n|---|---:|---:|---:|---:|\n");
  for (int k = 1; k <= 2; ++k) {
    const double extra = rows[k].us_per_step - rows[0].us_per_step;
    const double per_particle = extra / static_cast<double>(rows[k].particles);
    std::printf("| %s | %.1f | %.1f | %s | %.3f |\n", k == 1 ? "collide off" : "colliding", extra, 1e3 * per_particle,
                bench::Number(1e6 / per_particle, "%.3g").c_str(), per_particle / body_us);
  }
  std::printf("\none rigid circle in a pour of 1000: %.2f µs/step\n", body_us);
  std::printf("\neffects colliding, wall clock: the bodies alone step on one thread either way\n\n"
              "| threads | effect particles | ms/step | bodies alone | effects' ms | particle-steps/s | speed-up |\n"
              "|---:|---:|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < effects_threads.size(); ++k) {
    const EffectsThreadRow& e = effects_threads[k];
    const EffectsThreadRow& one_thread = effects_threads[k - k % 2];
    const double effects_ms = e.with_ms - e.bodies_ms;
    const double one = one_thread.with_ms - one_thread.bodies_ms;
    std::printf("| %d | %zu | %.3f | %.3f | %.3f | %s | %.2f |\n", e.threads, e.particles, e.with_ms, e.bodies_ms,
                effects_ms, bench::Number(1e3 * static_cast<double>(e.particles) / effects_ms, "%.3g").c_str(),
                one / effects_ms);
  }
  std::printf("\nfluid: a dam break 1 s in, substeps of 1/480 s (8 a step), wall clock\n\n"
              "| fluid particles | threads | ms/step | particle-steps/s | speed-up |\n|---:|---:|---:|---:|---:|\n");
  for (std::size_t k = 0; k < fluid.size(); ++k) {
    const FluidRow& f = fluid[k];
    const double one_thread = fluid[k - k % 2].ms_per_step;
    std::printf("| %zu | %d | %.2f | %s | %.2f |\n", f.particles, f.threads, f.ms_per_step,
                bench::Number(1e3 * static_cast<double>(f.particles) / f.ms_per_step, "%.3g").c_str(),
                one_thread / f.ms_per_step);
  }
  bench::File csv = bench::OpenInFolder(options.out_dir, "effects.csv");
  if (csv) {
    std::fprintf(csv.get(), "scene,bodies,effect_particles,us_per_step\n");
    for (const Row& r : rows) {
      std::fprintf(csv.get(), "%s,%zu,%zu,%.3f\n", bench::Quoted(r.scene).c_str(), r.bodies, r.particles,
                   r.us_per_step);
    }
  }
  bench::File fluid_csv = bench::OpenInFolder(options.out_dir, "fluid.csv");
  if (fluid_csv) {
    std::fprintf(fluid_csv.get(), "fluid_particles,threads,ms_per_step\n");
    for (const FluidRow& f : fluid) std::fprintf(fluid_csv.get(), "%zu,%d,%.4f\n", f.particles, f.threads, f.ms_per_step);
  }
  bench::File threads_csv = bench::OpenInFolder(options.out_dir, "effects_threads.csv");
  if (threads_csv) {
    std::fprintf(threads_csv.get(), "threads,effect_particles,ms_per_step,bodies_alone_ms_per_step\n");
    for (const EffectsThreadRow& e : effects_threads) {
      std::fprintf(threads_csv.get(), "%d,%zu,%.4f,%.4f\n", e.threads, e.particles, e.with_ms, e.bodies_ms);
    }
  }
  return bench::ReportCsv(csv != nullptr && fluid_csv != nullptr && threads_csv != nullptr, options.out_dir,
                          {"effects.csv (µs per step of each scene)", "fluid.csv (ms per step, by thread count)",
                           "effects_threads.csv (colliding effects' ms per step, by thread count)"},
                          0);
}
