// Milliseconds per step and stability figures of the sequential-impulse solver against the
// substep solver at 1, 2, 4 and 8 substeps, for every stress scene of issue 4, measured in one run.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/solver_scenes.h"
#include "engine/world.h"

namespace {

using bench::Median;
using bench::Number;
using bench::Progress;

struct Options : bench::RunOptions {
  Options() : RunOptions(5) {}
  int steps = 0;                                      // 0: each scene's own
  std::string scene_filter;                           // run only scenes whose name contains this
  std::optional<engine::ContactSolver> solver_filter;  // empty: both
  int substeps_filter = 0;                            // 0: every substep count
  bool rotation = false;                              // the scenes with turning bodies
  int passes = 0;                                     // substep solver's passes a substep; 0: automatic
};

bench::Args Arguments(Options& options) {
  bench::Args args("bench_solver", "Contact solvers side by side on the stress scenes: ms/step and stability "
                                   "figures, a table on stdout and CSV files.");
  options.AddTo(args, "at most 10 steps a scene, one repeat, no verdicts", "timed runs per setting");
  args.Value("--steps N", &options.steps, "steps per run (default: each scene's own)", 2)
      .Value("--scene TEXT", &options.scene_filter, "only the scenes whose name contains TEXT")
      .Choice("--solver NAME", &options.solver_filter,
              {{"sequential_impulse", engine::ContactSolver::kSequentialImpulse},
               {"seed", engine::ContactSolver::kSequentialImpulse},
               {"substep", engine::ContactSolver::kSubstep}},
              "only this solver; seed is the sequential-impulse solver's old name")
      .Value("--substeps N", &options.substeps_filter, "only this substep count (default 0: every one)", 0)
      .Value("--passes N", &options.passes,
             "the substep solver's velocity passes per substep (default 0: the world's automatic choice)", 0)
      .Flag("--rotation", &options.rotation, "the scenes with turning bodies");
  return args;
}

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

// The words scene files and --solver take (bench_solver printed "seed" before the engine's rename).
std::string SolverName(solver_bench::Setting s) {
  return s.solver == engine::ContactSolver::kSequentialImpulse ? "sequential_impulse" : "substep";
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
  if (options.solver_filter && *options.solver_filter != s.solver) return false;
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
    engine::World world = solver_bench::MakeWorld(scene, setting, options.rotation, options.passes);
    Result result{scene.name, steps, setting, scene.measure(world, steps), {}, {}, true};
    results.push_back(result);
    hashes.push_back(world.StateHash());
  }
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < results.size(); ++k) {
      Result& result = results[k];
      Progress(scene.name + ": " + SolverName(result.setting) + " " + SubstepsText(result.setting) +
               ", run " + std::to_string(r + 1) + "/" + std::to_string(repeats));
      engine::World world = solver_bench::MakeWorld(scene, result.setting, options.rotation, options.passes);
      // The first step sorts the broad phase from scratch; Box2D's benchmark leaves it out too.
      world.Step();
      const double cpu_start = bench::ThreadSeconds();
      const bench::Clock::time_point start = bench::Clock::now();
      for (int i = 1; i < steps; ++i) world.Step();
      const double seconds = bench::SecondsSince(start);
      const double cpu_seconds = bench::ThreadSeconds() - cpu_start;
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
  const bench::File csv_file = bench::OpenInFolder(dir, "solver_bench.csv");
  const bench::File runs_file = bench::OpenInFolder(dir, "solver_bench_runs.csv");
  if (!csv_file || !runs_file) return false;
  std::FILE* csv = csv_file.get();
  std::FILE* runs = runs_file.get();
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
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exit_code = Arguments(options).Parse(argc, argv)) return *exit_code;
  const std::string load_before = bench::LoadAverage();

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
  bench::PrintMachine(load_before);
  std::printf("\n");
  PrintTable(results, options.quick);
  // The settings left at 0 ("automatic") as the engine resolves them for these scenes.
  engine::WorldDef impulse_def;
  impulse_def.solver = engine::ContactSolver::kSequentialImpulse;
  impulse_def.rotation = options.rotation;
  const engine::World impulse_world(impulse_def);
  engine::WorldDef substep_def;
  substep_def.rotation = options.rotation;
  substep_def.velocity_iterations = options.passes;
  const engine::World substep_world(substep_def);
  std::printf("\nsequential_impulse (formerly seed): %d passes of impulses and a projection per step; substep: the "
              "default solver, %d pass%s per substep, %d substeps by default\n",
              impulse_world.Def().velocity_iterations,
              substep_world.Def().velocity_iterations, substep_world.Def().velocity_iterations == 1 ? "" : "es",
              substep_world.Def().substeps);

  int status = 0;
  for (const Result& r : results) {
    if (r.same_state) continue;
    std::fprintf(stderr, "error: %s, %s %s: a timed run ended in a different state\n", r.scene.c_str(),
                 SolverName(r.setting).c_str(), SubstepsText(r.setting).c_str());
    status = 1;
  }
  return bench::ReportCsv(WriteCsv(results, options.out_dir), options.out_dir,
                          {"solver_bench.csv (one row per figure)", "solver_bench_runs.csv (every timed run)"}, status);
}
