// Broad-phase milliseconds per step for each choice as the body count grows (1k to 64k), on an
// even rain and a clumped pile, with the fitted log-log slope; then whole-world steps per choice.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/stress_scenes.h"
#include "broad_phase/broad_phase.h"
#include "engine/world.h"

namespace {

using bench::Clock;
using bench::Median;
using bench::Progress;
using engine::AABB;
using engine::BodyPair;
using engine::Vec2;

struct Options {
  bool quick = false;
  int repeats = 5;
  int steps = 20;                // timed steps per repeat
  int warmup = 10;               // steps before timing: structures built, caches warm
  std::size_t all_pairs_max = 16000;  // all pairs is quadratic: beyond this it would take minutes
  std::vector<std::size_t> sizes = {1000, 4000, 16000, 64000};
  bool world = true;             // also time whole world steps per choice
  std::string out_dir = "bench-out";
};

constexpr double kDt = 1.0 / 60.0;

// --- Scenes: bodies moved by a fixed rule, their boxes grown by the reach of one step as the
// world grows them, statics (floor and walls) first as in the example scenes.

struct MovingBody {
  Vec2 position;
  Vec2 velocity;
  Vec2 half;   // half extents (a circle's radius on both axes)
  Vec2 home;   // the pile: where the body rests
  double phase = 0.0;
};

class Scene {
 public:
  virtual ~Scene() = default;
  virtual void Step() = 0;
  std::span<const AABB> Boxes() const { return boxes_; }

 protected:
  void AddStatic(Vec2 lower, Vec2 upper) { statics_.push_back({lower, upper}); }
  void UpdateBoxes(double speculative) {
    boxes_.resize(statics_.size() + bodies_.size());
    std::copy(statics_.begin(), statics_.end(), boxes_.begin());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const MovingBody& b = bodies_[i];
      const double reach = engine::Length(b.velocity) * kDt + speculative;
      const Vec2 grow = b.half + Vec2{reach, reach};
      boxes_[statics_.size() + i] = {b.position - grow, b.position + grow};
    }
  }
  std::vector<AABB> statics_;
  std::vector<MovingBody> bodies_;
  std::vector<AABB> boxes_;
};

// Half extents of a body: circles of radius 0.2-0.5 m and boxes of the same range of sides.
Vec2 RandomHalf(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(0.2, 0.5);
  if (rng() % 2 == 0) {
    const double r = size(rng);
    return {r, r};
  }
  return {size(rng), size(rng)};
}

// An even rain: bodies spread over a wide area (8 m² each, twice as wide as high) falling at 4-12
// m/s; one that reaches the floor starts again at the top. Ids are in random spatial order.
class Rain : public Scene {
 public:
  explicit Rain(std::size_t n) {
    std::mt19937_64 rng(n);
    width_ = std::sqrt(2.0 * 8.0 * static_cast<double>(n));
    height_ = 0.5 * width_;
    AddStatic({-1, -1}, {width_ + 1, 0});
    AddStatic({-1, 0}, {0, height_ + 2});
    AddStatic({width_, 0}, {width_ + 1, height_ + 2});
    std::uniform_real_distribution<double> x(0.5, width_ - 0.5), y(1.0, height_ + 1.0);
    std::uniform_real_distribution<double> drift(-1.0, 1.0), fall(4.0, 12.0);
    bodies_.resize(n);
    for (MovingBody& b : bodies_) {
      b.half = RandomHalf(rng);
      b.position = {x(rng), y(rng)};
      b.velocity = {drift(rng), -fall(rng)};
    }
    UpdateBoxes(0.01);
  }
  void Step() override {
    for (MovingBody& b : bodies_) {
      b.position += kDt * b.velocity;
      if (b.position.y < b.half.y) b.position.y += height_;
      if (b.position.x < b.half.x || b.position.x > width_ - b.half.x) b.velocity.x = -b.velocity.x;
    }
    UpdateBoxes(0.01);
  }

 private:
  double width_ = 0.0;
  double height_ = 0.0;
};

// A clumped pile: bodies packed in staggered rows (about six neighbours each) in a block twice as
// wide as high on the floor between walls, each jiggling a couple of centimetres about its rest
// place as resting contacts do. Ids go row by row, as a scene file lists them.
class Pile : public Scene {
 public:
  explicit Pile(std::size_t n) {
    std::mt19937_64 rng(n + 1);
    const double pitch = 0.9;
    const auto per_row = static_cast<std::size_t>(std::ceil(std::sqrt(2.0 * static_cast<double>(n))));
    const double width = pitch * (static_cast<double>(per_row) + 1.0);
    const double height = 0.866 * pitch * (static_cast<double>(n / per_row) + 2.0);
    AddStatic({-1, -1}, {width + 1, 0});
    AddStatic({-1, 0}, {0, height + 2});
    AddStatic({width, 0}, {width + 1, height + 2});
    std::uniform_real_distribution<double> half(0.45, 0.5), phase(0.0, 6.283185307179586);
    bodies_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      MovingBody& b = bodies_[i];
      const std::size_t row = i / per_row, column = i % per_row;
      const double r = half(rng);
      b.half = rng() % 2 == 0 ? Vec2{r, r} : Vec2{r, half(rng)};
      b.home = {pitch * (static_cast<double>(column) + 0.5 + 0.5 * static_cast<double>(row % 2)),
                0.5 + 0.866 * pitch * static_cast<double>(row)};
      b.phase = phase(rng);
      b.position = b.home;
    }
    UpdateBoxes(0.01);
  }
  void Step() override {
    time_ += kDt;
    for (MovingBody& b : bodies_) {
      const Vec2 before = b.position;
      b.position = b.home + 0.02 * Vec2{std::sin(7.0 * time_ + b.phase), std::sin(5.0 * time_ + 2.0 * b.phase)};
      b.velocity = (b.position - before) / kDt;
    }
    UpdateBoxes(0.01);
  }

 private:
  double time_ = 0.0;
};

std::unique_ptr<Scene> MakeScene(const std::string& name, std::size_t n) {
  if (name == "rain") return std::make_unique<Rain>(n);
  return std::make_unique<Pile>(n);
}

// --- Broad phases behind one signature, each with its own persistent state.

using FindPairs = std::function<void(std::span<const AABB>, std::vector<BodyPair>*)>;

struct Choice {
  const char* name;
  engine::BroadPhaseType type;
};

const Choice kChoices[] = {
    {"auto", engine::BroadPhaseType::kAuto},
    {"all_pairs", engine::BroadPhaseType::kAllPairs},
    {"sweep_and_prune", engine::BroadPhaseType::kSweepAndPrune},
    {"uniform_grid", engine::BroadPhaseType::kUniformGrid},
    {"quadtree", engine::BroadPhaseType::kQuadtree},
    {"aabb_tree", engine::BroadPhaseType::kAabbTree},
};

template <class T>
FindPairs Bind() {
  auto structure = std::make_shared<T>();
  return [structure](std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
    structure->FindPairs(boxes, pairs);
  };
}

FindPairs MakeBroadPhase(engine::BroadPhaseType type) {
  switch (type) {
    case engine::BroadPhaseType::kAuto: {
      auto chooser = std::make_shared<engine::BroadPhase>();
      return [chooser](std::span<const AABB> boxes, std::vector<BodyPair>* pairs) {
        chooser->FindPairs(engine::BroadPhaseType::kAuto, boxes, pairs);
      };
    }
    case engine::BroadPhaseType::kSweepAndPrune: return Bind<engine::SweepAndPrune>();
    case engine::BroadPhaseType::kUniformGrid: return Bind<engine::UniformGrid>();
    case engine::BroadPhaseType::kQuadtree: return Bind<engine::Quadtree>();
    case engine::BroadPhaseType::kAabbTree: return Bind<engine::AabbTree>();
    default: return engine::FindPairsAllPairs;
  }
}

// --- Measurement.

struct Result {
  std::string scene;
  std::string choice;
  std::size_t n = 0;
  std::vector<double> ms_per_step;  // one per timed repeat
  std::vector<double> cpu_ms_per_step;  // the thread's CPU time: what other processes' load leaves
  double pairs_per_step = 0.0;
  std::uint64_t checksum = 14695981039346656037ull;  // FNV-1a over every step's pairs
};

void Mix(std::uint64_t* hash, std::uint64_t value) {
  for (int k = 0; k < 8; ++k) {
    *hash ^= (value >> (8 * k)) & 0xff;
    *hash *= 1099511628211ull;
  }
}

// One scene at one size: every choice steps its own copy of the same deterministic scene, timed
// repeats interleaved across choices so drifting machine load hits all alike. Only the FindPairs
// call is timed; the checksum proves every choice found the same pairs at every step.
std::vector<Result> Measure(const std::string& scene_name, std::size_t n, const Options& options) {
  struct Run {
    Result result;
    std::unique_ptr<Scene> scene;
    FindPairs find;
    std::vector<BodyPair> pairs;
    std::size_t pair_total = 0;
    int steps_counted = 0;
  };
  std::vector<Run> runs;
  for (const Choice& choice : kChoices) {
    if (choice.type == engine::BroadPhaseType::kAllPairs && n > options.all_pairs_max) continue;
    Run run;
    run.result = {scene_name, choice.name, n, {}, {}, 0.0};
    run.scene = MakeScene(scene_name, n);
    run.find = MakeBroadPhase(choice.type);
    runs.push_back(std::move(run));
  }
  auto step = [](Run& run, double* cpu_seconds) {
    run.scene->Step();
    const double cpu_start = bench::ThreadSeconds();
    const Clock::time_point start = Clock::now();
    run.find(run.scene->Boxes(), &run.pairs);
    const double seconds = bench::SecondsSince(start);
    *cpu_seconds += bench::ThreadSeconds() - cpu_start;
    Mix(&run.result.checksum, run.pairs.size());
    for (const BodyPair& p : run.pairs) Mix(&run.result.checksum, (std::uint64_t{p.a} << 32) | p.b);
    run.pair_total += run.pairs.size();
    ++run.steps_counted;
    return seconds;
  };
  for (Run& run : runs) {
    Progress(scene_name + " " + std::to_string(n) + ": " + run.result.choice + ", warm-up");
    double unused = 0.0;
    for (int s = 0; s < options.warmup; ++s) step(run, &unused);
  }
  for (int r = 0; r < options.repeats; ++r) {
    for (Run& run : runs) {
      Progress(scene_name + " " + std::to_string(n) + ": " + run.result.choice + ", run " + std::to_string(r + 1) +
               "/" + std::to_string(options.repeats));
      double seconds = 0.0, cpu_seconds = 0.0;
      for (int s = 0; s < options.steps; ++s) seconds += step(run, &cpu_seconds);
      run.result.ms_per_step.push_back(1000.0 * seconds / options.steps);
      run.result.cpu_ms_per_step.push_back(1000.0 * cpu_seconds / options.steps);
    }
  }
  std::vector<Result> results;
  for (Run& run : runs) {
    run.result.pairs_per_step = static_cast<double>(run.pair_total) / run.steps_counted;
    results.push_back(run.result);
  }
  return results;
}

// The exponent k in time ∝ n^k.
double FittedSlope(const std::vector<std::pair<double, double>>& points) { return bench::LogLogSlope(points); }

std::vector<std::pair<double, double>> Points(const std::vector<Result>& results, const std::string& scene,
                                              const std::string& choice) {
  std::vector<std::pair<double, double>> points;
  for (const Result& r : results) {
    if (r.scene == scene && r.choice == choice) points.push_back({static_cast<double>(r.n), Median(r.ms_per_step)});
  }
  return points;
}

// Whole numbers from 100 up, so the wide tables keep narrow columns.
std::string Number(double value) { return bench::Number(value, value >= 100 ? "%.0f" : "%.3g"); }

void PrintTable(const std::vector<Result>& results, const Options& options) {
  std::printf("| scene | broad phase |");
  for (std::size_t n : options.sizes) std::printf(" n = %zu |", n);
  std::printf(" fitted slope |\n|---|---|");
  for (std::size_t k = 0; k < options.sizes.size(); ++k) std::printf("---:|");
  std::printf("---:|\n");
  for (const char* scene : {"rain", "pile"}) {
    for (const Choice& choice : kChoices) {
      std::printf("| %s | %s |", scene, choice.name);
      for (std::size_t n : options.sizes) {
        std::string cell = "-";
        for (const Result& r : results) {
          if (r.scene == scene && r.choice == choice.name && r.n == n) cell = Number(Median(r.ms_per_step));
        }
        std::printf(" %s |", cell.c_str());
      }
      std::printf(" %s |\n", Number(FittedSlope(Points(results, scene, choice.name))).c_str());
    }
    std::printf("| %s | pairs per step |", scene);
    for (std::size_t n : options.sizes) {
      std::string cell = "-";
      for (const Result& r : results) {
        if (r.scene == scene && r.n == n) cell = Number(r.pairs_per_step);
      }
      std::printf(" %s |", cell.c_str());
    }
    std::printf(" |\n");
  }
}

bool WriteCsv(const std::vector<Result>& results, const std::string& dir) {
  const bench::File csv_file = bench::OpenInFolder(dir, "broadphase_bench.csv");
  const bench::File runs_file = bench::OpenInFolder(dir, "broadphase_bench_runs.csv");
  const bench::File slopes_file = bench::OpenInFolder(dir, "broadphase_slopes.csv");
  if (!csv_file || !runs_file || !slopes_file) return false;
  std::FILE* csv = csv_file.get();
  std::FILE* runs = runs_file.get();
  std::FILE* slopes = slopes_file.get();
  std::fprintf(csv, "scene,broad_phase,n,ms_per_step_median,ms_per_step_min,ms_per_step_max,cpu_ms_per_step_median,"
                    "pairs_per_step,repeats\n");
  std::fprintf(runs, "scene,broad_phase,n,repeat,ms_per_step,cpu_ms_per_step\n");
  std::fprintf(slopes, "scene,broad_phase,fitted_slope\n");
  for (const Result& r : results) {
    const auto [min, max] = std::minmax_element(r.ms_per_step.begin(), r.ms_per_step.end());
    std::fprintf(csv, "%s,%s,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%zu\n", r.scene.c_str(), r.choice.c_str(), r.n,
                 Median(r.ms_per_step), *min, *max, Median(r.cpu_ms_per_step), r.pairs_per_step,
                 r.ms_per_step.size());
    for (std::size_t k = 0; k < r.ms_per_step.size(); ++k) {
      std::fprintf(runs, "%s,%s,%zu,%zu,%.6g,%.6g\n", r.scene.c_str(), r.choice.c_str(), r.n, k, r.ms_per_step[k],
                   r.cpu_ms_per_step[k]);
    }
  }
  for (const char* scene : {"rain", "pile"}) {
    for (const Choice& choice : kChoices) {
      const double slope = FittedSlope(Points(results, scene, choice.name));
      if (!std::isnan(slope)) std::fprintf(slopes, "%s,%s,%.4f\n", scene, choice.name, slope);
    }
  }
  return true;
}

// --- Whole world steps: the broad phase in its place among the other phases, on the stress pour
// while it pours (bodies falling and colliding) and once it has settled (most bodies asleep).

struct WorldResult {
  int bodies = 0;
  std::string choice;
  double pouring_ms = 0.0;
  double settled_ms = 0.0;
  std::uint64_t hash = 0;
};

constexpr int kPouringStart = 30;    // steps before the "pouring" window
constexpr int kSettledStart = 600;   // steps before the "settled" window (10 s)

std::vector<WorldResult> MeasureWorld(const Options& options) {
  std::vector<WorldResult> results;
  const int window = options.quick ? 5 : 60;
  const int settled_start = options.quick ? 40 : kSettledStart;
  const int repeats = options.quick ? 1 : 3;
  for (int count : {1000, 4000}) {
    const double width = std::sqrt(static_cast<double>(count)) * 0.6;
    for (const Choice& choice : kChoices) {
      if (choice.type == engine::BroadPhaseType::kAllPairs) continue;
      std::vector<double> pouring, settled;
      std::uint64_t hash = 0;
      for (int r = 0; r < repeats; ++r) {
        Progress("world pour " + std::to_string(count) + ": " + choice.name);
        engine::WorldDef def;
        def.broad_phase = choice.type;
        engine::World world(def);
        stress::AddContainer(world, width, 4.0 * width);
        stress::AddCirclePour(world, count, 0.1, width);
        auto timed = [&world](int steps) {
          const Clock::time_point start = Clock::now();
          for (int s = 0; s < steps; ++s) world.Step();
          return 1000.0 * bench::SecondsSince(start) / steps;
        };
        for (int s = 0; s < kPouringStart; ++s) world.Step();
        pouring.push_back(timed(window));
        for (int s = kPouringStart + window; s < settled_start; ++s) world.Step();
        settled.push_back(timed(window));
        hash = world.StateHash();
      }
      results.push_back({count, choice.name, Median(pouring), Median(settled), hash});
    }
  }
  Progress("");
  return results;
}

// "1000,4000": body counts of at least 2; an error, or "" when every item is one.
std::string ParseSizes(const std::string& text, std::vector<std::size_t>* sizes) {
  std::vector<std::size_t> parsed;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    std::size_t value = 0;
    if (!bench::ParseValue(item, &value).empty() || value < 2) {
      return "\"" + item + "\" is not a body count of 2 or more";
    }
    parsed.push_back(value);
  }
  if (parsed.empty()) return "no sizes in \"" + text + "\"";
  *sizes = parsed;
  return "";
}

bench::Args Arguments(Options& options) {
  bench::Args args("bench_broadphase", "FindPairs time per step for each broad phase as the body count grows (rain, "
                                       "pile), then whole-world steps per choice; a table on stdout and CSV files.");
  // --quick sets its values where it stands on the line, so an option after it still changes them.
  args.Flag("--quick", [&options] {
        options.quick = true, options.repeats = 1, options.steps = 2, options.warmup = 1;
        options.sizes = {1000, 4000};
      }, "smoke run: sizes 1000 and 4000, 1 warm-up and 2 timed steps, one repeat")
      .Value("--repeats R", &options.repeats, "timed repeats per size and choice (default 5)", 1)
      .Value("--steps S", &options.steps, "timed steps per repeat (default 20)", 1)
      .Value("--warmup W", &options.warmup, "steps before timing (default 10)", 0)
      .Value("--out DIR", &options.out_dir, "folder for the CSV files (default bench-out)")
      .Custom("--sizes N,N,...", [&options](const std::string& text) { return ParseSizes(text, &options.sizes); },
              "body counts (default 1000,4000,16000,64000)")
      .Value("--all-pairs-max N", &options.all_pairs_max, "time all_pairs only up to N bodies (default 16000)")
      .Flag("--no-world", [&options] { options.world = false; }, "leave out the whole-world steps");
  return args;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exit_code = Arguments(options).Parse(argc, argv)) return *exit_code;
  const std::string load_before = bench::LoadAverage();

  std::vector<Result> results;
  for (const char* scene : {"rain", "pile"}) {
    for (std::size_t n : options.sizes) {
      for (Result& r : Measure(scene, n, options)) results.push_back(std::move(r));
    }
  }
  std::vector<WorldResult> world_results;
  if (options.world) world_results = MeasureWorld(options);
  Progress("");

  std::printf("bench_broadphase%s: FindPairs time per step for each broad phase; rain = bodies spread thin "
              "and falling, pile = bodies packed with about six neighbours, jiggling; 3 static bodies "
              "(floor, walls) in each\n", options.quick ? " --quick (smoke run)" : "");
  std::printf("timing: one thread; %d warm-up steps, then the median over %d repeats of the mean over %d "
              "steps (only the FindPairs call is timed); all_pairs only up to n = %zu\n",
              options.warmup, options.repeats, options.steps, options.all_pairs_max);
  bench::PrintMachine(load_before);
  std::printf("\n");
  std::printf("ms per step (median):\n\n");
  PrintTable(results, options);

  int status = 0;
  for (const Result& r : results) {
    for (const Result& other : results) {
      if (other.scene != r.scene || other.n != r.n || other.checksum == r.checksum) continue;
      std::fprintf(stderr, "error: %s n = %zu: %s and %s found different pairs\n", r.scene.c_str(), r.n,
                   r.choice.c_str(), other.choice.c_str());
      status = 1;
    }
  }

  if (!world_results.empty()) {
    std::printf("\nwhole world step, ms (median of %d): circles of radius 0.1 m poured in a closed box, default "
                "world (substep solver, sleeping on); pouring = steps %d-%d, settled = steps %d-%d\n\n",
                options.quick ? 1 : 3, kPouringStart + 1, kPouringStart + (options.quick ? 5 : 60),
                options.quick ? 41 : kSettledStart + 1, (options.quick ? 40 : kSettledStart) + (options.quick ? 5 : 60));
    std::printf("| bodies | window |");
    for (const Choice& c : kChoices) {
      if (c.type != engine::BroadPhaseType::kAllPairs) std::printf(" %s |", c.name);
    }
    std::printf(" same state hash |\n|---:|---|");
    for (std::size_t k = 1; k < std::size(kChoices); ++k) std::printf("---:|");
    std::printf("---|\n");
    for (int count : {1000, 4000}) {
      std::uint64_t first = 0;
      bool same = true;
      for (const WorldResult& w : world_results) {
        if (w.bodies != count) continue;
        if (first == 0) first = w.hash;
        same = same && w.hash == first;
      }
      for (int window = 0; window < 2; ++window) {
        std::printf("| %d | %s |", count, window == 0 ? "pouring" : "settled");
        for (const WorldResult& w : world_results) {
          if (w.bodies == count) std::printf(" %s |", Number(window == 0 ? w.pouring_ms : w.settled_ms).c_str());
        }
        std::printf(" %s |\n", same ? "yes" : "NO");
      }
      if (!same) status = 1;
    }
  }

  return bench::ReportCsv(WriteCsv(results, options.out_dir), options.out_dir,
                          {"broadphase_bench.csv (medians)",
                           "broadphase_bench_runs.csv (every timed run)",
                           "broadphase_slopes.csv"},
                          status);
}
