// Scaling: whole-world ms/step against body count (1k to 64k) for a circle pour and a box pile,
// ballbox and every peer built in, with the fitted log-log slope per engine.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/peers/engines.h"
#include "bench/peers/scenes.h"

namespace {

struct Options : bench::RunOptions {
  Options() : RunOptions(3) {}
  int warmup = 30;  // untimed steps: the block of bodies has collapsed into a pile by then
  int steps = 30;   // timed steps
  std::vector<int> counts = {1000, 2000, 4000, 8000, 16000, 32000, 64000};
  /// ms/step of the first run above which one more run is all the size gets (Box2D's 64k box pile
  /// takes seconds a step: repeats would add minutes and no information)
  double slow_ms = 200;
  std::string engine_filter;
  int max_bodies = INT_MAX;  // sizes above it are left out
};

bench::Args Arguments(Options& options) {
  bench::Args args("bench_scaling", "Whole-world ms/step against body count (circle pour, box pile) for ballbox and "
                                    "the peers built in, a table on stdout and CSV files.");
  options.AddTo(args, "1000 and 2000 bodies, a few steps, one repeat", "timed runs per size and engine");
  args.Value("--max-bodies N", &options.max_bodies, "leave out the sizes above N (default: none; sizes 1000-64000)")
      .Value("--engine TEXT", &options.engine_filter, "only the engines whose name contains TEXT");
  return args;
}

struct Row {
  std::string scene;  // "circle pour" or "box pile"
  int count = 0;
  std::string engine;
  std::string settings;
  std::vector<double> ms_per_step;
  bool same_state = true;
  bool finite = true;
};

std::vector<std::pair<double, double>> Points(const std::vector<Row>& rows, const std::string& scene,
                                              const std::string& engine) {
  std::vector<std::pair<double, double>> points;
  for (const Row& r : rows) {
    if (r.scene == scene && r.engine == engine) points.push_back({static_cast<double>(r.count), bench::Median(r.ms_per_step)});
  }
  return points;
}

void PrintTable(const std::vector<Row>& rows, const std::vector<std::string>& engines, const Options& options) {
  for (const char* scene : {"circle pour", "box pile"}) {
    std::printf("\n**%s**: ms/step (median), and each peer's time ÷ ballbox's\n\n| bodies |", scene);
    for (const std::string& e : engines) std::printf(" %s |", e.c_str());
    for (std::size_t i = 1; i < engines.size(); ++i) std::printf(" %s ÷ ballbox |", engines[i].c_str());
    std::printf("\n|---:|");
    for (std::size_t i = 0; i < 2 * engines.size() - 1; ++i) std::printf("---:|");
    std::printf("\n");
    for (int count : options.counts) {
      std::printf("| %d |", count);
      std::vector<double> ms;
      for (const std::string& e : engines) {
        double value = std::nan("");
        for (const Row& r : rows) {
          if (r.scene == scene && r.engine == e && r.count == count) value = bench::Median(r.ms_per_step);
        }
        ms.push_back(value);
        std::printf(" %s |", bench::Number(value).c_str());
      }
      for (std::size_t i = 1; i < engines.size(); ++i) std::printf(" %s |", bench::Number(ms[i] / ms[0]).c_str());
      std::printf("\n");
    }
    std::printf("| log-log slope |");
    for (const std::string& e : engines) std::printf(" %s |", bench::Number(bench::LogLogSlope(Points(rows, scene, e)), "%.2f").c_str());
    for (std::size_t i = 1; i < engines.size(); ++i) std::printf(" |");
    std::printf("\n");
  }
}

bool WriteCsv(const std::vector<Row>& rows, const std::string& dir) {
  const bench::File csv_file = bench::OpenInFolder(dir, "scaling.csv");
  const bench::File slopes_file = bench::OpenInFolder(dir, "scaling_slopes.csv");
  if (!csv_file || !slopes_file) return false;
  std::FILE* csv = csv_file.get();
  std::FILE* slopes = slopes_file.get();
  std::fprintf(csv, "scene,bodies,engine,settings,repeats,ms_per_step_median,ms_per_step_min,same_state,finite\n");
  std::vector<std::pair<std::string, std::string>> series;
  for (const Row& r : rows) {
    std::fprintf(csv, "%s,%d,%s,%s,%zu,%.6g,%.6g,%d,%d\n", bench::Quoted(r.scene).c_str(), r.count,
                 bench::Quoted(r.engine).c_str(), bench::Quoted(r.settings).c_str(), r.ms_per_step.size(),
                 bench::Median(r.ms_per_step), bench::Min(r.ms_per_step), r.same_state ? 1 : 0, r.finite ? 1 : 0);
    if (std::find(series.begin(), series.end(), std::pair{r.scene, r.engine}) == series.end()) series.push_back({r.scene, r.engine});
  }
  std::fprintf(slopes, "scene,engine,slope\n");
  for (const auto& [scene, engine] : series) {
    std::fprintf(slopes, "%s,%s,%.4g\n", bench::Quoted(scene).c_str(), bench::Quoted(engine).c_str(),
                 bench::LogLogSlope(Points(rows, scene, engine)));
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  const bench::Args args = Arguments(options);
  if (const std::optional<int> exit_code = args.Parse(argc, argv)) return *exit_code;
  std::erase_if(options.counts, [&options](int n) { return n > options.max_bodies; });
  // --quick overrides the sizes, --max-bodies included.
  if (options.quick) options.counts = {1000, 2000}, options.repeats = 1, options.warmup = 2, options.steps = 3;
  if (options.counts.empty()) {
    return args.Error("--max-bodies " + std::to_string(options.max_bodies) + " leaves no size");
  }
  const std::string load_before = bench::LoadAverage();
  std::vector<peers::EngineEntry> engines;
  for (const peers::EngineEntry& e : peers::Engines()) {
    if (e.name.find(options.engine_filter) != std::string::npos) engines.push_back(e);
  }
  std::vector<std::string> names;
  for (const peers::EngineEntry& e : engines) names.push_back(e.name);

  std::vector<Row> rows;
  for (bool boxes : {false, true}) {
    for (int count : options.counts) {
      const peers::SceneSpec spec = peers::ScalingScene(count, boxes);
      std::vector<Row> scene_rows;
      std::vector<std::uint64_t> hashes(engines.size());
      // Repeats interleave the engines, so drifting machine load hits them all alike; the first
      // run of each engine is also its warm-up for the hash every later run must reach.
      std::vector<int> runs(engines.size(), options.repeats);
      for (int r = 0; r < options.repeats + 1; ++r) {
        for (std::size_t k = 0; k < engines.size(); ++k) {
          if (r > runs[k]) continue;
          bench::Progress(spec.name + ": " + engines[k].name + ", run " + std::to_string(r) + "/" + std::to_string(options.repeats));
          std::unique_ptr<peers::PhysicsEngine> engine = engines[k].make();
          const auto [ms, hash] = peers::TimeSteps(*engine, spec, options.warmup, options.steps);
          if (r == 0) {
            Row row{boxes ? "box pile" : "circle pour", count, engines[k].name, engine->Settings(spec), {}, true, true};
            std::vector<peers::State> states;
            engine->Read(states);
            for (const peers::State& s : states) row.finite = row.finite && peers::Finite(s);
            scene_rows.push_back(row);
            hashes[k] = hash;
            if (ms > options.slow_ms) runs[k] = 1;
            continue;
          }
          scene_rows[k].ms_per_step.push_back(ms);
          scene_rows[k].same_state = scene_rows[k].same_state && hash == hashes[k];
        }
      }
      for (Row& row : scene_rows) rows.push_back(std::move(row));
    }
  }
  bench::Progress("");

  std::printf("bench_scaling%s: whole-world ms/step against body count, one thread, sleeping off, 60 Hz\n",
              options.quick ? " --quick (smoke run)" : "");
  std::printf("scenes: circles of radius 0.25 m (pour) or boxes of 0.5 m (pile), friction 0.6, restitution 0.2, "
              "on a jittered grid at 1.15x their size in a square-ish closed container, up to 1 m/s each; "
              "nothing turns (peers: fixed rotation)\n");
  std::printf("timing: %d untimed steps (the block collapses into a pile), then %d timed steps; median of %d runs "
              "after a first run (1 run where the first took over %.0f ms/step), engines interleaved\n",
              options.warmup, options.steps, options.repeats, options.slow_ms);
  for (const Row& r : rows) {
    if (r.count == options.counts.front() && r.scene == "circle pour") std::printf("%s: %s\n", r.engine.c_str(), r.settings.c_str());
  }
  bench::PrintMachine(load_before);
  const std::string missing = peers::MissingPeers();
  if (!missing.empty()) std::printf("not in this build: %s (configure with -DBALLBOX_BENCH_PEERS=ON)\n", missing.c_str());
  PrintTable(rows, names, options);

  int status = 0;
  for (const Row& r : rows) {
    if (!r.finite) std::printf("note: %s %d, %s ended with non-finite bodies\n", r.scene.c_str(), r.count, r.engine.c_str());
    if (r.same_state || r.engine != "ballbox") continue;
    std::fprintf(stderr, "error: %s %d: a timed ballbox run ended in a different state\n", r.scene.c_str(), r.count);
    status = 1;
  }
  return bench::ReportCsv(WriteCsv(rows, options.out_dir), options.out_dir,
                          {"scaling.csv (every size and engine)", "scaling_slopes.csv (fitted slopes)"}, status);
}
