// Work-precision: run time per simulated second against error for every integrator on the
// analytic scenarios S1-S7 of accuracy.md, h = 1/30 .. 1/3840 s, with fitted orders of accuracy.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "bench/bench_common.h"
#include "bench/work_precision_scenarios.h"
#include "engine/world.h"

namespace {

namespace wp = work_precision;

struct Options : bench::RunOptions {
  Options() : RunOptions(7) {}
  double min_sample_seconds = 0.02;  // a timed sample repeats the run until it lasts this long
  std::string scenario_filter;
};

bench::Args Arguments(Options& options) {
  bench::Args args("bench_work_precision", "Run time per simulated second against error for every integrator on the "
                                           "analytic scenarios S1-S7, tables on stdout and CSV files.");
  options.AddTo(args, "a few steps of every run, one sample", "timed samples per run");
  args.Value("--scenario ID", &options.scenario_filter, "only this scenario, S1 to S7");
  return args;
}

struct Row {
  const wp::Scenario* scenario = nullptr;
  const wp::Method* method = nullptr;
  int rate = 0;
  wp::Figures figures;
  std::vector<double> seconds_per_run;  // one per timed sample
  bool same_state = true;
};

// Quick mode: a few steps of every run, one sample, so the program is checked end to end fast.
constexpr int kQuickSteps = 20;

double MicrosecondsPerSimulatedSecond(const Row& row, double seconds_per_run) {
  return 1e6 * seconds_per_run / (row.figures.steps / static_cast<double>(row.rate));
}

// Time only the stepping: worlds are built before the clock starts and the error is measured in
// the separate figure run. A sample steps k fresh worlds, k chosen so it lasts long enough for the
// clock; the first sample calibrates k and warms the caches and is not kept.
void Time(Row& row, const Options& options) {
  const int repeats = options.quick ? 1 : options.repeats;
  int runs = 1;
  for (int sample = -1; sample < repeats; ++sample) {
    std::vector<engine::World> worlds;
    worlds.reserve(runs);
    for (int k = 0; k < runs; ++k) worlds.push_back(row.scenario->build(row.method->integrator, 1.0 / row.rate));
    const bench::Clock::time_point start = bench::Clock::now();
    for (engine::World& world : worlds) {
      for (int step = 0; step < row.figures.steps; ++step) world.Step();
    }
    const double seconds = bench::SecondsSince(start) / runs;
    for (const engine::World& world : worlds) row.same_state = row.same_state && world.StateHash() == row.figures.hash;
    if (sample < 0) {
      runs = std::clamp(static_cast<int>(std::ceil(options.min_sample_seconds / std::max(seconds, 1e-9))), 1, 100000);
      if (options.quick) runs = 1;
      continue;
    }
    row.seconds_per_run.push_back(seconds);
  }
}

std::string Rate(int rate) { return "1/" + std::to_string(rate); }

/// The fitted order: the slope of log(error) against log(h) over the runs that did not blow up
/// whose error is above roundoff (1e-12 of the scene's size) and below a tenth of it (the
/// asymptotic range). A slowly growing energy is kept: its error still converges.
struct Fit {
  double order = std::nan("");
  std::string note;  ///< "exact" when every error is at roundoff
};

Fit FitOrder(const std::vector<const Row*>& rows, bool energy) {
  std::vector<std::pair<double, double>> points;
  int at_roundoff = 0, stable = 0;
  for (const Row* r : rows) {
    if (r->figures.blew_up) continue;
    ++stable;
    const double error = energy ? r->figures.energy_error : r->figures.position_error;
    const double size = energy ? 1.0 : r->scenario->scale;
    if (error <= 1e-12 * size) {
      ++at_roundoff;
    } else if (error < 0.1 * size) {
      points.push_back({1.0 / r->rate, error});
    }
  }
  Fit fit;
  if (stable > 0 && at_roundoff == stable) {
    fit.note = "exact";
  } else if (points.size() >= 3) {
    fit.order = bench::LogLogSlope(points);
  } else {
    fit.note = "n/a";
  }
  return fit;
}

std::string FitText(const Fit& fit) { return fit.note.empty() ? bench::Number(fit.order, "%.2f") : fit.note; }

std::vector<const Row*> RowsOf(const std::vector<Row>& rows, const wp::Scenario& s, const wp::Method& m) {
  std::vector<const Row*> out;
  for (const Row& r : rows) {
    if (r.scenario == &s && r.method == &m) out.push_back(&r);
  }
  return out;
}

std::string ErrorCell(const Row& r, bool energy) {
  const double error = energy ? r.figures.energy_error : r.figures.position_error;
  std::string text = std::isinf(error) ? "inf" : bench::Number(error, "%.2e");
  return r.figures.unstable.empty() ? text : text + " †";
}

void PrintTables(const std::vector<Row>& rows, const std::vector<wp::Scenario>& scenarios, std::FILE* out) {
  const auto& methods = wp::Methods();
  std::fprintf(out, "**Fitted order of accuracy** (slope of log error against log h over the runs that did "
                    "not blow up, error between 1e-12 and 0.1 of the scene's size; theory in brackets):\n\n| scenario | error |");
  for (const wp::Method& m : methods) std::fprintf(out, " %s (%d) |", m.name, m.order);
  std::fprintf(out, "\n|---|---|");
  for (std::size_t i = 0; i < methods.size(); ++i) std::fprintf(out, "---:|");
  std::fprintf(out, "\n");
  for (const wp::Scenario& s : scenarios) {
    for (bool energy : {false, true}) {
      if (energy && !s.conservative) continue;
      std::fprintf(out, "| %s %s | %s |", s.id.c_str(), s.title.c_str(), energy ? "max rel. energy" : "max position");
      for (const wp::Method& m : methods) std::fprintf(out, " %s |", FitText(FitOrder(RowsOf(rows, s, m), energy)).c_str());
      std::fprintf(out, "\n");
    }
  }

  for (const wp::Scenario& s : scenarios) {
    for (bool energy : {false, true}) {
      if (energy && !s.conservative) continue;
      std::fprintf(out, "\n**%s %s, %.4g s: %s** († unstable)\n\n| integrator |", s.id.c_str(), s.title.c_str(),
                   s.duration, energy ? "max relative energy error" : "max position error, m");
      for (int rate : wp::StepRates()) std::fprintf(out, " h = %s |", Rate(rate).c_str());
      std::fprintf(out, "\n|---|");
      for (std::size_t i = 0; i < wp::StepRates().size(); ++i) std::fprintf(out, "---:|");
      std::fprintf(out, "\n");
      for (const wp::Method& m : methods) {
        std::fprintf(out, "| %s |", m.name);
        for (const Row* r : RowsOf(rows, s, m)) std::fprintf(out, " %s |", ErrorCell(*r, energy).c_str());
        std::fprintf(out, "\n");
      }
    }
  }

  std::fprintf(out, "\n**Run time per simulated second at h = 1/240 s** (µs, median of the timed samples):\n\n"
                    "| scenario |");
  for (const wp::Method& m : methods) std::fprintf(out, " %s |", m.name);
  std::fprintf(out, "\n|---|");
  for (std::size_t i = 0; i < methods.size(); ++i) std::fprintf(out, "---:|");
  std::fprintf(out, "\n");
  for (const wp::Scenario& s : scenarios) {
    std::fprintf(out, "| %s %s |", s.id.c_str(), s.title.c_str());
    for (const wp::Method& m : methods) {
      for (const Row* r : RowsOf(rows, s, m)) {
        if (r->rate == 240) std::fprintf(out, " %s |", bench::Number(MicrosecondsPerSimulatedSecond(*r, bench::Median(r->seconds_per_run))).c_str());
      }
    }
    std::fprintf(out, "\n");
  }

  // The question a user asks: what is the cheapest way to reach a given accuracy?
  std::fprintf(out, "\n**Cheapest stable run reaching a max position error of 1 mm, and of 1 µm** "
                    "(method, h, µs per simulated second):\n\n| scenario | error ≤ 1e-3 m | error ≤ 1e-6 m |\n|---|---|---|\n");
  for (const wp::Scenario& s : scenarios) {
    std::fprintf(out, "| %s %s |", s.id.c_str(), s.title.c_str());
    for (double target : {1e-3, 1e-6}) {
      const Row* best = nullptr;
      double best_cost = 0;
      for (const Row& r : rows) {
        if (r.scenario != &s || !r.figures.unstable.empty() || !(r.figures.position_error <= target)) continue;
        const double cost = MicrosecondsPerSimulatedSecond(r, bench::Median(r.seconds_per_run));
        if (best == nullptr || cost < best_cost) best = &r, best_cost = cost;
      }
      if (best == nullptr) {
        std::fprintf(out, " none within 1/3840 s |");
      } else {
        std::fprintf(out, " %s, %s, %s |", best->method->name, Rate(best->rate).c_str(), bench::Number(best_cost).c_str());
      }
    }
    std::fprintf(out, "\n");
  }
}

bool WriteCsv(const std::vector<Row>& rows, const std::vector<wp::Scenario>& scenarios, const std::string& dir) {
  const bench::File csv_file = bench::OpenInFolder(dir, "work_precision.csv");
  const bench::File orders_file = bench::OpenInFolder(dir, "work_precision_orders.csv");
  if (!csv_file || !orders_file) return false;
  std::FILE* csv = csv_file.get();
  std::FILE* orders = orders_file.get();
  // accuracy.md §0 item 8's columns, as far as they apply (l∞ is the position error here).
  std::fprintf(csv, "scenario,integrator,h,rate,steps,evals_per_step,repeats,us_per_sim_s_median,us_per_sim_s_min,"
                    "err_linf_position,max_rel_dE,dE_slope,unstable,reason,blew_up,first_unstable\n");
  for (const Row& r : rows) {
    // The plot labels only the first unstable run of each method, so the labels stay readable.
    bool first_unstable = !r.figures.unstable.empty();
    for (const Row& other : rows) {
      if (&other == &r) break;
      if (other.scenario == r.scenario && other.method == r.method && !other.figures.unstable.empty()) first_unstable = false;
    }
    std::fprintf(csv, "%s,%s,%.9g,%d,%d,%d,%zu,%.6g,%.6g,%.9g,%.9g,%.9g,%d,%s,%d,%d\n", r.scenario->id.c_str(),
                 bench::Quoted(r.method->name).c_str(), 1.0 / r.rate, r.rate, r.figures.steps, r.method->evaluations,
                 r.seconds_per_run.size(), MicrosecondsPerSimulatedSecond(r, bench::Median(r.seconds_per_run)),
                 MicrosecondsPerSimulatedSecond(r, bench::Min(r.seconds_per_run)), r.figures.position_error,
                 r.figures.energy_error, r.figures.energy_slope, r.figures.unstable.empty() ? 0 : 1,
                 bench::Quoted(r.figures.unstable).c_str(), r.figures.blew_up ? 1 : 0, first_unstable ? 1 : 0);
  }
  std::fprintf(orders, "scenario,title,integrator,theory,order_position,note_position,order_energy,note_energy\n");
  for (const wp::Scenario& s : scenarios) {
    for (const wp::Method& m : wp::Methods()) {
      const std::vector<const Row*> of = RowsOf(rows, s, m);
      if (of.empty()) continue;
      const Fit position = FitOrder(of, false);
      const Fit energy = s.conservative ? FitOrder(of, true) : Fit{std::nan(""), "-"};
      std::fprintf(orders, "%s,%s,%s,%d,%.4g,%s,%.4g,%s\n", s.id.c_str(), bench::Quoted(s.title).c_str(),
                   bench::Quoted(m.name).c_str(), m.order, position.order, position.note.c_str(), energy.order,
                   energy.note.c_str());
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (const std::optional<int> exit_code = Arguments(options).Parse(argc, argv)) return *exit_code;
  const std::string load_before = bench::LoadAverage();
  std::vector<wp::Scenario> scenarios;
  for (wp::Scenario& s : wp::Scenarios()) {
    if (options.scenario_filter.empty() || s.id == options.scenario_filter) scenarios.push_back(std::move(s));
  }

  std::vector<Row> rows;
  for (const wp::Scenario& s : scenarios) {
    for (const wp::Method& m : wp::Methods()) {
      for (int rate : wp::StepRates()) {
        bench::Progress(s.id + " " + m.name + " h = " + Rate(rate));
        Row row{&s, &m, rate, wp::Measure(s, m.integrator, rate, options.quick ? kQuickSteps : 0), {}, true};
        Time(row, options);
        rows.push_back(std::move(row));
      }
    }
  }
  bench::Progress("");

  std::printf("bench_work_precision%s: run time per simulated second against error, integrators of "
              "accuracy.md S1-S7\n", options.quick ? " --quick (smoke run: a few steps, figures are not the scenarios')" : "");
  std::printf("setup: one world step of h (the default substep solver with 1 substep, sleeping off), "
              "h = 1/30 .. 1/3840 s; error measured every step in a separate run; g = %.2f m/s²\n", wp::kG);
  std::printf("timing: one thread, only the stepping loop; a calibration sample, then the median (and min) of "
              "%d samples of >= %.0f ms each; † marks an unstable run (kept, not dropped)\n",
              options.quick ? 1 : options.repeats, 1000 * options.min_sample_seconds);
  bench::PrintMachine(load_before);
  std::printf("\n");
  PrintTables(rows, scenarios, stdout);

  int status = 0;
  for (const Row& r : rows) {
    if (r.same_state) continue;
    std::fprintf(stderr, "error: %s %s h = %s: a timed run ended in a different state\n", r.scenario->id.c_str(),
                 r.method->name, Rate(r.rate).c_str());
    status = 1;
  }
  return bench::ReportCsv(WriteCsv(rows, scenarios, options.out_dir), options.out_dir,
                          {"work_precision.csv (every run)", "work_precision_orders.csv (fitted orders)"}, status);
}
