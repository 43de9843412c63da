// ballbox beside Box2D 2.4.1 and Chipmunk 7.0.3 on the same scenes in the same run: ms/step and
// the same state-based figures for each, with the ratios to ballbox; confined circles also per
// ballbox solver setting (the one stress scene bench_solver does not have).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/peers/ballbox_engine.h"
#include "bench/peers/engines.h"
#include "bench/peers/scenes.h"

namespace {

struct Options : bench::RunOptions {
  Options() : RunOptions(5) {}
  std::string scene_filter;
};

bench::Args Arguments(Options& options) {
  bench::Args args("bench_peers", "ballbox beside the peers built in on the same scenes: ms/step and figures from "
                                  "body states, a table on stdout and CSV files.");
  options.AddTo(args, "at most 10 steps a scene, one repeat", "timed runs per engine");
  args.Value("--scene TEXT", &options.scene_filter, "only the scenes whose name contains TEXT");
  return args;
}

constexpr int kQuickSteps = 10;

struct Row {
  std::string scene;
  std::string engine;
  std::string settings;
  int steps = 0;
  std::vector<peers::Figure> figures;
  std::vector<double> ms_per_step;
  std::uint64_t hash = 0;
  bool same_state = true;
  bool is_ballbox = false;
  bool is_sweep = false;  ///< one of ballbox's non-default solver settings
};

// The engines of one scene: every engine built in, then ballbox's other solver settings where the
// scene asks for them.
std::vector<peers::EngineEntry> EnginesFor(const peers::Scene& scene) {
  std::vector<peers::EngineEntry> out = peers::Engines();
  if (!scene.sweep) return out;
  const peers::BallboxSetting settings[] = {{engine::ContactSolver::kSequentialImpulse, 0},
                                            {engine::ContactSolver::kSubstep, 1},
                                            {engine::ContactSolver::kSubstep, 2},
                                            {engine::ContactSolver::kSubstep, 4},
                                            {engine::ContactSolver::kSubstep, 8}};
  for (peers::BallboxSetting s : settings) {
    out.push_back({"ballbox " + s.Label(), [s] { return std::make_unique<peers::BallboxEngine>(s); }});
  }
  return out;
}

// A figure run per engine (it also warms up), then the timed repeats with the engines interleaved,
// so a drifting machine load hits them all alike. Step 1 is left out of the timing.
std::vector<Row> RunScene(const peers::Scene& scene, const Options& options) {
  const int steps = options.quick ? std::min(scene.spec.steps, kQuickSteps) : scene.spec.steps;
  const int repeats = options.quick ? 1 : options.repeats;
  const std::vector<peers::EngineEntry> engines = EnginesFor(scene);
  std::vector<Row> rows;
  for (const peers::EngineEntry& entry : engines) {
    bench::Progress(scene.spec.name + ": " + entry.name + ", figures");
    std::unique_ptr<peers::PhysicsEngine> engine = entry.make();
    engine->Build(scene.spec);
    Row row;
    row.scene = scene.spec.name;
    row.engine = engine->Name();
    row.settings = engine->Settings(scene.spec);
    row.steps = steps;
    row.figures = scene.measure(*engine, scene.spec, steps);
    std::vector<peers::State> states;
    engine->Read(states);
    row.hash = peers::Hash(states);
    row.is_ballbox = entry.name.rfind("ballbox", 0) == 0;
    row.is_sweep = row.is_ballbox && entry.name != "ballbox" && entry.name != "ballbox 2 threads";
    rows.push_back(std::move(row));
  }
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < engines.size(); ++k) {
      bench::Progress(scene.spec.name + ": " + engines[k].name + ", run " + std::to_string(r + 1) + "/" +
                      std::to_string(repeats));
      std::unique_ptr<peers::PhysicsEngine> engine = engines[k].make();
      const auto [ms, hash] = peers::TimeSteps(*engine, scene.spec, 1, steps - 1);
      rows[k].ms_per_step.push_back(ms);
      rows[k].same_state = rows[k].same_state && hash == rows[k].hash;
    }
  }
  bench::Progress("");
  return rows;
}

std::string FigureText(const peers::Figure& f) {
  return bench::Number(f.value) + (f.unit.empty() ? "" : " " + f.unit);
}

std::string Ratio(double value, double reference) {
  if (std::isnan(value) || std::isnan(reference)) return "n/a";
  if (reference == 0) return value == 0 ? "1" : "inf";
  return bench::Number(value / reference, "%.3g");
}

const Row* BallboxRow(const std::vector<Row>& rows, const std::string& scene) {
  for (const Row& r : rows) {
    if (r.scene == scene && r.engine == "ballbox") return &r;
  }
  return nullptr;
}

void PrintTable(const std::vector<Row>& rows, bool sweep_rows, std::FILE* out) {
  std::fprintf(out, "| scene | engine | settings | ms/step | time ÷ ballbox's | headline figure | value "
                    "| ÷ ballbox's | other figures | same end state on rerun |\n");
  std::fprintf(out, "|---|---|---|---:|---:|---|---:|---:|---|---|\n");
  for (const Row& r : rows) {
    if (r.is_sweep != sweep_rows) continue;
    const Row* base = BallboxRow(rows, r.scene);
    const double ms = bench::Median(r.ms_per_step);
    const peers::Figure& head = r.figures.front();
    std::string others;
    for (std::size_t i = 1; i < r.figures.size(); ++i) {
      others += (others.empty() ? "" : "; ") + r.figures[i].name + " " + FigureText(r.figures[i]);
    }
    std::fprintf(out, "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", r.scene.c_str(), r.engine.c_str(),
                 r.settings.c_str(), bench::Number(ms).c_str(),
                 base ? Ratio(ms, bench::Median(base->ms_per_step)).c_str() : "n/a", head.name.c_str(),
                 FigureText(head).c_str(), base ? Ratio(head.value, base->figures.front().value).c_str() : "n/a",
                 others.c_str(), r.same_state ? "yes" : "no");
  }
}

bool WriteFigures(const std::vector<Row>& rows, const std::string& dir) {
  const bench::File csv_file = bench::OpenInFolder(dir, "peers_bench.csv");
  if (!csv_file) return false;
  std::FILE* csv = csv_file.get();
  // Long form, one row per figure, like bench_solver's CSV, so one plot script reads both.
  std::fprintf(csv, "scene,engine,settings,steps,repeats,ms_per_step_median,ms_per_step_min,figure,value,unit,"
                    "headline,same_state\n");
  for (const Row& r : rows) {
    for (std::size_t i = 0; i < r.figures.size(); ++i) {
      const peers::Figure& f = r.figures[i];
      std::fprintf(csv, "%s,%s,%s,%d,%zu,%.6g,%.6g,%s,%.9g,%s,%d,%d\n", bench::Quoted(r.scene).c_str(),
                   bench::Quoted(r.engine).c_str(), bench::Quoted(r.settings).c_str(), r.steps, r.ms_per_step.size(),
                   bench::Median(r.ms_per_step), bench::Min(r.ms_per_step), bench::Quoted(f.name).c_str(), f.value,
                   f.unit.c_str(), i == 0 ? 1 : 0, r.same_state ? 1 : 0);
    }
  }
  return true;
}

// Wide form for the ratio plot: one row per scene, one column per peer (time, then figure).
bool WriteRatios(const std::vector<Row>& rows, const std::string& dir) {
  const bench::File wide_file = bench::OpenInFolder(dir, "peers_ratios.csv");
  if (!wide_file) return false;
  std::FILE* wide = wide_file.get();
  std::vector<std::string> peer_names;
  for (const Row& r : rows) {
    if (!r.is_ballbox && std::find(peer_names.begin(), peer_names.end(), r.engine) == peer_names.end()) {
      peer_names.push_back(r.engine);
    }
  }
  std::fprintf(wide, "scene");
  for (const std::string& p : peer_names) std::fprintf(wide, ",%s", bench::Quoted(p + " time").c_str());
  for (const std::string& p : peer_names) std::fprintf(wide, ",%s", bench::Quoted(p + " figure").c_str());
  std::fprintf(wide, ",headline\n");
  std::vector<std::string> scenes;
  for (const Row& r : rows) {
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  }
  for (const std::string& scene : scenes) {
    const Row* base = BallboxRow(rows, scene);
    if (base == nullptr) continue;
    std::vector<std::string> time, figure;
    for (const std::string& p : peer_names) {
      std::string t = "nan", f = "nan";
      for (const Row& r : rows) {
        if (r.scene != scene || r.engine != p) continue;
        t = bench::Number(bench::Median(r.ms_per_step) / bench::Median(base->ms_per_step), "%.6g");
        const double reference = base->figures.front().value, value = r.figures.front().value;
        f = reference == 0 ? (value == 0 ? "1" : "inf") : bench::Number(value / reference, "%.6g");
      }
      time.push_back(t), figure.push_back(f);
    }
    std::fprintf(wide, "%s", bench::Quoted(scene).c_str());
    for (const std::string& t : time) std::fprintf(wide, ",%s", t.c_str());
    for (const std::string& f : figure) std::fprintf(wide, ",%s", f.c_str());
    std::fprintf(wide, ",%s\n", bench::Quoted(base->figures.front().name).c_str());
  }
  return true;
}

bool WriteCsv(const std::vector<Row>& rows, const std::string& dir) {
  return WriteFigures(rows, dir) && WriteRatios(rows, dir);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exit_code = Arguments(options).Parse(argc, argv)) return *exit_code;
  const std::string load_before = bench::LoadAverage();

  std::vector<Row> rows;
  for (const peers::Scene& scene : peers::Scenes()) {
    if (scene.spec.name.find(options.scene_filter) == std::string::npos) continue;
    for (Row& r : RunScene(scene, options)) rows.push_back(std::move(r));
  }

  const int repeats = options.quick ? 1 : options.repeats;
  std::printf("bench_peers%s: the same scenes in ballbox and its peers, 60 Hz, one thread, sleeping off\n",
              options.quick ? " --quick (smoke run: figures are not the scenes')" : "");
  std::printf("timing: ms/step over steps 2..N (step 1 builds structures); a warm-up run per engine measures the "
              "figures from body states alone, then the median of %d timed runs, engines interleaved\n", repeats);
  bench::PrintMachine(load_before);
  const std::string missing = peers::MissingPeers();
  if (!missing.empty()) {
    std::printf("not in this build: %s (configure with -DBALLBOX_BENCH_PEERS=ON and the Debian packages "
                "libbox2d-dev libchipmunk-dev)\n", missing.c_str());
  }
  std::printf("\n");
  PrintTable(rows, false, stdout);
  bool any_sweep = false;
  for (const Row& r : rows) any_sweep = any_sweep || r.is_sweep;
  if (any_sweep) {
    std::printf("\nballbox's solver settings on the scene bench_solver does not have:\n\n");
    PrintTable(rows, true, stdout);
  }

  int status = 0;
  for (const Row& r : rows) {
    // ballbox is deterministic, so a timed run that ended elsewhere did other work; a peer that
    // does not rerun to the same state is reported in the table, not treated as a failure.
    if (!r.is_ballbox || r.same_state) continue;
    std::fprintf(stderr, "error: %s, %s: a timed run ended in a different state\n", r.scene.c_str(), r.engine.c_str());
    status = 1;
  }
  return bench::ReportCsv(WriteCsv(rows, options.out_dir), options.out_dir,
                          {"peers_bench.csv (one row per figure)", "peers_ratios.csv (each peer ÷ ballbox)"}, status);
}
