// Skip ablation: each skippable feature present but with nothing to do against absent. The state
// hashes must be identical and the cost difference within the timing noise (design.md, "Skip what
// a scene doesn't need"; accuracy.md §0 item 9).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/skip_ablation_scenes.h"
#include "engine/world.h"

namespace {

struct Options : bench::RunOptions {
  Options() : RunOptions(9) {}
};

bench::Args Arguments(Options& options) {
  bench::Args args("bench_skip", "Every skippable feature present but with nothing to do, against absent: state "
                                 "hashes and cost, a table on stdout and a CSV file.");
  options.AddTo(args, "5 steps, one run per side, no timing verdict", "timed runs per side");
  return args;
}

struct Row {
  const skip_ablation::Ablation* ablation = nullptr;
  int steps = 0;
  std::uint64_t absent_hash = 0, present_hash = 0;
  bool reruns_same = true;  // every timed run ended in its side's figure-run state
  std::vector<double> absent_ms, present_ms;
};

// A difference counts as noise when it is below twice the larger side's relative half-IQR, or
// below 1% (what a quiet machine cannot resolve either).
constexpr double kNoiseFloor = 0.01;

double Difference(const Row& r) { return bench::Median(r.present_ms) / bench::Median(r.absent_ms) - 1; }
double Noise(const Row& r) {
  return std::max(kNoiseFloor, 2 * std::max(bench::RelativeSpread(r.absent_ms), bench::RelativeSpread(r.present_ms)));
}

std::pair<double, std::uint64_t> TimeRun(const std::function<engine::World()>& make, int steps) {
  engine::World world = make();
  world.Step();  // the first step builds the broad phase from scratch
  const bench::Clock::time_point start = bench::Clock::now();
  for (int i = 1; i < steps; ++i) world.Step();
  const double seconds = bench::SecondsSince(start);
  return {1000 * seconds / std::max(1, steps - 1), world.StateHash()};
}

Row Run(const skip_ablation::Ablation& ablation, const Options& options) {
  Row row;
  row.ablation = &ablation;
  row.steps = options.quick ? 5 : ablation.steps;
  // The figure runs double as the warm-up; then absent and present alternate, so a drifting
  // machine load hits both sides alike.
  row.absent_hash = TimeRun(ablation.absent, row.steps).second;
  row.present_hash = TimeRun(ablation.present, row.steps).second;
  for (int r = 0; r < (options.quick ? 1 : options.repeats); ++r) {
    bench::Progress(ablation.feature + ": run " + std::to_string(r + 1));
    const bool absent_first = r % 2 == 0;
    for (int side = 0; side < 2; ++side) {
      const bool absent = (side == 0) == absent_first;
      const auto [ms, hash] = TimeRun(absent ? ablation.absent : ablation.present, row.steps);
      (absent ? row.absent_ms : row.present_ms).push_back(ms);
      row.reruns_same = row.reruns_same && hash == (absent ? row.absent_hash : row.present_hash);
    }
  }
  bench::Progress("");
  return row;
}

std::string Hex(std::uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

void PrintTable(const std::vector<Row>& rows, bool quick) {
  std::printf("| feature, present but unused | how | state hash absent | present | identical | "
              "ms/step absent | present | difference | noise band | verdict |\n");
  std::printf("|---|---|---|---|---|---:|---:|---:|---:|---|\n");
  for (const Row& r : rows) {
    const bool same = r.absent_hash == r.present_hash;
    const double difference = Difference(r), noise = Noise(r);
    std::string verdict = !same ? "FAIL: hash differs" : (std::abs(difference) <= noise ? "pass" : "cost beyond noise");
    if (quick) verdict = same ? "hash identical (quick: no timing verdict)" : verdict;
    std::printf("| %s | %s | %s | %s | %s | %s | %s | %+.1f%% | ±%.1f%% | %s |\n", r.ablation->feature.c_str(),
                r.ablation->note.c_str(), Hex(r.absent_hash).c_str(), Hex(r.present_hash).c_str(), same ? "yes" : "NO",
                bench::Number(bench::Median(r.absent_ms)).c_str(), bench::Number(bench::Median(r.present_ms)).c_str(),
                100 * difference, 100 * noise, verdict.c_str());
  }
}

bool WriteCsv(const std::vector<Row>& rows, const std::string& dir) {
  const bench::File csv_file = bench::OpenInFolder(dir, "skip_ablation.csv");
  if (!csv_file) return false;
  std::FILE* csv = csv_file.get();
  std::fprintf(csv, "feature,steps,repeats,hash_absent,hash_present,identical,ms_absent_median,ms_present_median,"
                    "difference,noise_band\n");
  for (const Row& r : rows) {
    std::fprintf(csv, "%s,%d,%zu,%s,%s,%d,%.6g,%.6g,%.4g,%.4g\n", bench::Quoted(r.ablation->feature).c_str(), r.steps,
                 r.absent_ms.size(), Hex(r.absent_hash).c_str(), Hex(r.present_hash).c_str(),
                 r.absent_hash == r.present_hash ? 1 : 0, bench::Median(r.absent_ms), bench::Median(r.present_ms),
                 Difference(r), Noise(r));
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exit_code = Arguments(options).Parse(argc, argv)) return *exit_code;
  const std::string load_before = bench::LoadAverage();
  const std::vector<skip_ablation::Ablation> ablations = skip_ablation::Ablations();
  std::vector<Row> rows;
  for (const skip_ablation::Ablation& a : ablations) rows.push_back(Run(a, options));

  std::printf("bench_skip%s: every skippable feature present but with nothing to do, against absent\n",
              options.quick ? " --quick (smoke run)" : "");
  std::printf("scene: %d bodies (two circles of r 0.25 m to every 0.5 m box) falling into a pile in a closed "
              "30 m box, sleeping off unless the row is about sleep; %d steps at 60 Hz, hash after the last\n",
              skip_ablation::kMixedCount, options.quick ? 5 : ablations.front().steps);
  std::printf("timing: ms/step over steps 2..N, median of %d runs per side, sides alternating; noise band: "
              "twice the larger side's relative half-IQR, at least %.0f%%\n",
              options.quick ? 1 : options.repeats, 100 * kNoiseFloor);
  bench::PrintMachine(load_before);
  std::printf("\n");
  PrintTable(rows, options.quick);

  int status = 0;
  for (const Row& r : rows) {
    if (r.reruns_same) continue;
    std::fprintf(stderr, "error: %s: a timed run ended in a different state\n", r.ablation->feature.c_str());
    status = 1;
  }
  return bench::ReportCsv(WriteCsv(rows, options.out_dir), options.out_dir,
                          {"skip_ablation.csv"}, status);
}
