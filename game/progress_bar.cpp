// The progress bar: carriage return and redraw, throttled so drawing never costs a frame.
#include "game/progress_bar.h"

#include <unistd.h>

#include <cinttypes>
#include <cstdio>
#include <utility>

namespace game {

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(std::string label, std::int64_t total, std::string unit, bool enabled)
    : label_(std::move(label)), total_(total), unit_(std::move(unit)), enabled_(enabled) {
  if (enabled_) Draw(0);
}

void ProgressBar::Update(std::int64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - last_draw_ < std::chrono::milliseconds(50)) return;
  last_draw_ = now;
  Draw(done);
}

void ProgressBar::Finish() {
  if (!enabled_) return;
  std::fputs("\r\033[K", stderr);  // erase the bar's line
  std::fflush(stderr);
  enabled_ = false;
}

std::string EtaText(double elapsed_seconds, std::int64_t done, std::int64_t total) {
  if (done <= 0 || elapsed_seconds < 0.5 || done > total) return "";
  const auto left = static_cast<std::int64_t>(
      elapsed_seconds * static_cast<double>(total - done) / static_cast<double>(done) + 0.5);
  char text[32];
  if (left >= 3600) {
    std::snprintf(text, sizeof text, "%" PRId64 ":%02d:%02d", left / 3600,
                  static_cast<int>(left / 60 % 60), static_cast<int>(left % 60));
  } else {
    std::snprintf(text, sizeof text, "%d:%02d", static_cast<int>(left / 60), static_cast<int>(left % 60));
  }
  return text;
}

void ProgressBar::Draw(std::int64_t done) {
  constexpr int kWidth = 30;
  const int filled = total_ > 0 ? static_cast<int>(kWidth * done / total_) : kWidth;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '-';
  bar[kWidth] = '\0';
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string eta = EtaText(elapsed, done, total_);
  // \033[K clears what a longer line before left behind.
  std::fprintf(stderr, "\r%s [%s] %" PRId64 "/%" PRId64 " %s%s%s\033[K", label_.c_str(), bar, done,
               total_, unit_.c_str(), eta.empty() ? "" : "  ETA ", eta.c_str());
  std::fflush(stderr);
}

}  // namespace game
