// A one-line progress bar on stderr for long runs; silent when stderr is not a terminal, so
// logs and pipes get no control characters.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace game {

/// Whether stderr is a terminal (where a progress bar belongs).
bool StderrIsTerminal();

class ProgressBar {
 public:
  /// `label` leads the line, `unit` follows the counts ("frames"). Draws nothing unless enabled.
  ProgressBar(std::string label, std::int64_t total, std::string unit, bool enabled);
  /// Shows `done` of total and, once there is a rate to go by, the time left ("ETA 0:42");
  /// redraws at most a few dozen times a second.
  void Update(std::int64_t done);
  /// Clears the line, so what is printed next starts clean.
  void Finish();

 private:
  void Draw(std::int64_t done);

  std::string label_;
  std::int64_t total_;
  std::string unit_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_draw_{};
};

/// The time left at the average rate so far, as "M:SS" (or "H:MM:SS" past an hour); empty
/// until half a second has passed or while nothing is done.
std::string EtaText(double elapsed_seconds, std::int64_t done, std::int64_t total);

}  // namespace game
