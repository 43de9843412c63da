// What every benchmark program of issue 8 shares: the machine and build it states, medians,
// fitted log-log slopes, timing by repeats, terminal-only progress and CSV files.
#pragma once

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#ifndef BALLBOX_BUILD_TYPE
#define BALLBOX_BUILD_TYPE "unknown"
#endif

namespace bench {

using Clock = std::chrono::steady_clock;

inline double Median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

inline double Min(const std::vector<double>& values) {
  return values.empty() ? std::nan("") : *std::min_element(values.begin(), values.end());
}

/// Half the distance between the quartiles, relative to the median: how far a repeat strays.
inline double RelativeSpread(std::vector<double> values) {
  if (values.size() < 2) return 0.0;
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) {
    const double position = q * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(position);
    const std::size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
  };
  const double median = at(0.5);
  return median > 0 ? 0.5 * (at(0.75) - at(0.25)) / median : 0.0;
}

/// Least-squares slope of log(y) against log(x); NaN with fewer than two usable points.
inline double LogLogSlope(const std::vector<std::pair<double, double>>& points) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& [x, y] : points) {
    if (!(x > 0) || !(y > 0) || !std::isfinite(x) || !std::isfinite(y)) continue;
    const double lx = std::log(x), ly = std::log(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    ++n;
  }
  const double denominator = n * sxx - sx * sx;
  if (n < 2 || denominator == 0) return std::nan("");
  return (n * sxy - sx * sy) / denominator;
}

inline std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

inline std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

inline std::string Compiler() {
#if defined(__clang__)
  return std::string("clang ") + __VERSION__;
#elif defined(__GNUC__)
  return std::string("g++ ") + __VERSION__;
#else
  return __VERSION__;
#endif
}

/// The lines every program prints first, so a table never travels without its machine.
inline void PrintMachine(const std::string& load_at_start) {
  std::printf("machine: %s, %u cores; compiler: %s; build: %s, -O flags of CMake's %s, -ffp-contract=off\n",
              CpuModel().c_str(), std::thread::hardware_concurrency(), Compiler().c_str(),
              BALLBOX_BUILD_TYPE, BALLBOX_BUILD_TYPE);
  std::printf("load average (1, 5, 15 min) at start: %s, at end: %s\n", load_at_start.c_str(),
              LoadAverage().c_str());
}

/// "%.3g", or "n/a" for NaN, so tables never print "nan".
inline std::string Number(double value, const char* format = "%.3g") {
  if (std::isnan(value)) return "n/a";
  char text[48];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

inline std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Progress goes to a terminal only, so redirected output holds the results alone.
inline void Progress(const std::string& text) {
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  if (terminal) std::fprintf(stderr, "\r\033[K%s", text.c_str());
}

inline double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the calling thread: on a shared machine it leaves out the time other processes
// held the core, which wall time cannot.
inline double ThreadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// A program's last line, where its CSV files went (each "name.csv (what it holds)"); when they
/// could not be written, the error instead and exit code 1 in place of `status`.
inline int ReportCsv(bool written, const std::string& dir, const std::vector<std::string>& files, int status) {
  if (!written) {
    std::fprintf(stderr, "error: cannot write CSV to %s\n", dir.c_str());
    return 1;
  }
  std::string list;
  for (const std::string& file : files) list += (list.empty() ? "" : ", ") + dir + "/" + file;
  std::printf("\nCSV: %s\n", list.c_str());
  return status;
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

/// `dir`/`name` open for writing, the folder made first; null when it cannot be opened.
inline File OpenInFolder(const std::string& dir, const std::string& name) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  return File(std::fopen((dir + "/" + name).c_str(), "w"));
}

}  // namespace bench
