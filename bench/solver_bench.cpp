// Milliseconds per step and stability figures of the seed solver against the substep solver at
// 1, 2, 4 and 8 substeps, for every stress scene of issue 4, measured in one run.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.h"
#include "bench/solver_scenes.h"
#include "engine/world.h"

#ifndef BALLBOX_BUILD_TYPE
#define BALLBOX_BUILD_TYPE "unknown"
#endif

namespace {

using bench::Median;
using bench::CpuModel;
using bench::LoadAverage;
using bench::Compiler;
using bench::Number;
using bench::Progress;

using Clock = std::chrono::steady_clock;

struct Options {
  bool quick = false;
  int repeats = 5;
  int steps = 0;              // 0: each scene's own
  std::string scene_filter;   // run only scenes whose name contains this
  std::string solver_filter;  // "seed", "substep" or empty for both
  int substeps_filter = 0;    // 0: every substep count
  std::string out_dir = "bench-out";
  bool rotation = false;      // the scenes with turning bodies
};

// Quick mode: enough steps to touch every phase (contacts form in the first step), one repeat.
constexpr int kQuickSteps = 10;

struct Result {
  std::string scene;
  int steps = 0;
  solver_bench::Setting setting;
  std::vector<solver_bench::Figure> figures;
  std::vector<double> ms_per_step;      // wall time, one per timed repeat
  std::vector<double> cpu_ms_per_step;  // this thread's CPU time, one per timed repeat
  bool same_state = true;           // every timed run ended in the figure run's state
};

// CPU time of the calling thread: on a shared machine it leaves out the time other processes
// held the core, which wall time cannot.
double ThreadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string SolverName(solver_bench::Setting s) {
  return s.solver == engine::ContactSolver::kSequentialImpulse ? "seed" : "substep";
}

std::string SubstepsText(solver_bench::Setting s) {
  return s.solver == engine::ContactSolver::kSequentialImpulse ? "-" : std::to_string(s.substeps);
}

std::string FiguresText(const std::vector<solver_bench::Figure>& figures) {
  std::string text;
  for (const solver_bench::Figure& f : figures) {
    if (!text.empty()) text += "; ";
    text += f.name + " " + Number(f.value) + (f.unit.empty() ? "" : " " + f.unit) + " (" + f.threshold + ")";
  }
  return text;
}

std::string Verdict(const std::vector<solver_bench::Figure>& figures) {
  std::string failed;
  for (const solver_bench::Figure& f : figures) {
    if (f.pass) continue;
    failed += (failed.empty() ? "" : ", ") + f.name;
  }
  return failed.empty() ? "pass" : "FAIL: " + failed;
}

bool Selected(const Options& options, solver_bench::Setting s) {
  if (!options.solver_filter.empty() && options.solver_filter != SolverName(s)) return false;
  return s.solver == engine::ContactSolver::kSequentialImpulse || options.substeps_filter == 0 ||
         options.substeps_filter == s.substeps;
}

// One scene: a warm-up run per setting that also measures the figures (outside any timed
// region), then the timed repeats, settings interleaved so drifting machine load hits all alike.
std::vector<Result> RunScene(const solver_bench::Scene& scene, const Options& options) {
  const int steps = options.quick ? std::min(scene.steps, kQuickSteps)
                                  : (options.steps > 0 ? options.steps : scene.steps);
  const int repeats = options.quick ? 1 : options.repeats;
  std::vector<Result> results;
  std::vector<std::uint64_t> hashes;
  for (solver_bench::Setting setting : solver_bench::Settings()) {
    if (!Selected(options, setting)) continue;
    Progress(scene.name + ": " + SolverName(setting) + " " + SubstepsText(setting) + ", figures");
    engine::World world = solver_bench::MakeWorld(scene, setting, options.rotation);
    Result result{scene.name, steps, setting, scene.measure(world, steps), {}, {}, true};
    results.push_back(result);
    hashes.push_back(world.StateHash());
  }
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < results.size(); ++k) {
      Result& result = results[k];
      Progress(scene.name + ": " + SolverName(result.setting) + " " + SubstepsText(result.setting) +
               ", run " + std::to_string(r + 1) + "/" + std::to_string(repeats));
      engine::World world = solver_bench::MakeWorld(scene, result.setting, options.rotation);
      // The first step sorts the broad phase from scratch; Box2D's benchmark leaves it out too.
      world.Step();
      const double cpu_start = ThreadSeconds();
      const Clock::time_point start = Clock::now();
      for (int i = 1; i < steps; ++i) world.Step();
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      const double cpu_seconds = ThreadSeconds() - cpu_start;
      result.ms_per_step.push_back(1000.0 * seconds / std::max(1, steps - 1));
      result.cpu_ms_per_step.push_back(1000.0 * cpu_seconds / std::max(1, steps - 1));
      // The engine is deterministic: a timed run that ended elsewhere did other work.
      result.same_state = result.same_state && world.StateHash() == hashes[k];
    }
  }
  Progress("");
  return results;
}

void PrintTable(const std::vector<Result>& results, bool quick) {
  std::printf("| scene | steps | solver | substeps | ms/step median | ms/step min | CPU ms/step median "
              "| stability figures (test threshold) | verdict |\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---|---|\n");
  for (const Result& r : results) {
    const double min = *std::min_element(r.ms_per_step.begin(), r.ms_per_step.end());
    std::printf("| %s | %d | %s | %s | %s | %s | %s | %s | %s |\n", r.scene.c_str(), r.steps,
                SolverName(r.setting).c_str(), SubstepsText(r.setting).c_str(),
                Number(Median(r.ms_per_step)).c_str(), Number(min).c_str(),
                Number(Median(r.cpu_ms_per_step)).c_str(),
                FiguresText(r.figures).c_str(), quick ? "- (quick)" : Verdict(r.figures).c_str());
  }
}

bool WriteCsv(const std::vector<Result>& results, const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  std::FILE* csv = std::fopen((dir + "/solver_bench.csv").c_str(), "w");
  std::FILE* runs = std::fopen((dir + "/solver_bench_runs.csv").c_str(), "w");
  if (csv == nullptr || runs == nullptr) {
    if (csv) std::fclose(csv);
    if (runs) std::fclose(runs);
    return false;
  }
  // Long form, one row per figure, so scenes with different figures share one file.
  std::fprintf(csv, "scene,solver,substeps,steps,repeats,ms_per_step_median,ms_per_step_min,"
                    "cpu_ms_per_step_median,figure,value,unit,threshold,pass\n");
  std::fprintf(runs, "scene,solver,substeps,steps,repeat,ms_per_step,cpu_ms_per_step\n");
  for (const Result& r : results) {
    const double min = *std::min_element(r.ms_per_step.begin(), r.ms_per_step.end());
    for (const solver_bench::Figure& f : r.figures) {
      std::fprintf(csv, "\"%s\",%s,%s,%d,%zu,%.6g,%.6g,%.6g,\"%s\",%.9g,%s,\"%s\",%d\n",
                   r.scene.c_str(), SolverName(r.setting).c_str(), SubstepsText(r.setting).c_str(),
                   r.steps, r.ms_per_step.size(), Median(r.ms_per_step), min,
                   Median(r.cpu_ms_per_step), f.name.c_str(), f.value,
                   f.unit.c_str(), f.threshold.c_str(), f.pass ? 1 : 0);
    }
    for (std::size_t k = 0; k < r.ms_per_step.size(); ++k) {
      std::fprintf(runs, "\"%s\",%s,%s,%d,%zu,%.6g,%.6g\n", r.scene.c_str(),
                   SolverName(r.setting).c_str(), SubstepsText(r.setting).c_str(), r.steps, k,
                   r.ms_per_step[k], r.cpu_ms_per_step[k]);
    }
  }
  std::fclose(csv);
  std::fclose(runs);
  return true;
}

bool ParseArgs(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--quick") {
      options.quick = true;
    } else if (arg == "--repeats" && has_value) {
      options.repeats = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--steps" && has_value) {
      options.steps = std::max(2, std::atoi(argv[++i]));
    } else if (arg == "--scene" && has_value) {
      options.scene_filter = argv[++i];
    } else if (arg == "--solver" && has_value &&
               (std::string(argv[i + 1]) == "seed" || std::string(argv[i + 1]) == "substep")) {
      options.solver_filter = argv[++i];
    } else if (arg == "--substeps" && has_value) {
      options.substeps_filter = std::max(0, std::atoi(argv[++i]));
    } else if (arg == "--out" && has_value) {
      options.out_dir = argv[++i];
    } else if (arg == "--rotation") {
      options.rotation = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_solver [--quick] [--repeats R] [--out DIR] [--rotation]\n"
                   "                    [--scene TEXT] [--solver seed|substep] [--substeps N] [--steps N]\n");
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!ParseArgs(argc, argv, options)) return 2;
  const std::string load_before = LoadAverage();

  std::vector<Result> results;
  for (const solver_bench::Scene& scene : solver_bench::Scenes()) {
    if (scene.name.find(options.scene_filter) == std::string::npos) continue;
    for (Result& r : RunScene(scene, options)) results.push_back(std::move(r));
  }

  const int repeats = options.quick ? 1 : options.repeats;
  std::printf("bench_solver%s: contact solvers side by side on the %s stress scenes, 60 Hz, "
              "sleeping off\n", options.quick ? " --quick (smoke run: figures are not the tests')" : "",
              options.rotation ? "turning (rotation on)" : "axis-aligned");
  std::printf("timing: one thread; ms/step (wall, steady_clock) over steps 2..N (step 1 builds the broad "
              "phase from scratch); a warm-up run per row measures the figures, then median and min of %d "
              "timed run%s, settings interleaved; CPU ms/step is the thread's CPU time\n",
              repeats, repeats == 1 ? "" : "s");
  std::printf("machine: %s, %u cores; compiler: %s; build: %s\n", CpuModel().c_str(),
              std::thread::hardware_concurrency(), Compiler().c_str(), BALLBOX_BUILD_TYPE);
  std::printf("load average (1, 5, 15 min) at start: %s, at end: %s\n\n", load_before.c_str(),
              LoadAverage().c_str());
  PrintTable(results, options.quick);
  // The settings left at 0 ("automatic") as the engine resolves them for these scenes.
  engine::WorldDef seed_def;
  seed_def.solver = engine::ContactSolver::kSequentialImpulse;
  seed_def.rotation = options.rotation;
  const engine::World seed_world(seed_def);
  engine::WorldDef substep_def;
  substep_def.rotation = options.rotation;
  const engine::World substep_world(substep_def);
  std::printf("\nseed: %d passes of impulses and a projection per step; substep: the default solver, "
              "%d pass%s per substep, %d substeps by default\n", seed_world.Def().velocity_iterations,
              substep_world.Def().velocity_iterations, substep_world.Def().velocity_iterations == 1 ? "" : "es",
              substep_world.Def().substeps);

  int status = 0;
  for (const Result& r : results) {
    if (r.same_state) continue;
    std::fprintf(stderr, "error: %s, %s %s: a timed run ended in a different state\n", r.scene.c_str(),
                 SolverName(r.setting).c_str(), SubstepsText(r.setting).c_str());
    status = 1;
  }
  if (!WriteCsv(results, options.out_dir)) {
    std::fprintf(stderr, "error: cannot write CSV to %s\n", options.out_dir.c_str());
    return 1;
  }
  std::printf("CSV: %s/solver_bench.csv (one row per figure), %s/solver_bench_runs.csv (every timed run)\n",
              options.out_dir.c_str(), options.out_dir.c_str());
  return status;
}
