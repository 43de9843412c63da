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

void ProgressBar::Draw(std::int64_t done) {
  constexpr int kWidth = 30;
  const int filled = total_ > 0 ? static_cast<int>(kWidth * done / total_) : kWidth;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '-';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r%s [%s] %" PRId64 "/%" PRId64 " %s", label_.c_str(), bar, done, total_,
               unit_.c_str());
  std::fflush(stderr);
}

}  // namespace game
