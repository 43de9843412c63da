// Gaffer's "fix your timestep" accumulator, without interpolation: a frame shows the last
// whole step, so what is drawn is always a state that sim and render reach too.
#include "game/frame_clock.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace game {

FrameClock::FrameClock(double dt, double max_frame_seconds)
    : dt_(dt), max_frame_seconds_(max_frame_seconds) {
  assert(dt > 0.0 && max_frame_seconds > 0.0);
}

int FrameClock::Advance(double frame_seconds) {
  // A clock that jumps back, or garbage, owes nothing; a long stall owes at most the clamp.
  if (!(frame_seconds > 0.0)) frame_seconds = 0.0;
  owed_ += std::min(frame_seconds, max_frame_seconds_);
  int steps = 0;
  while (owed_ >= dt_) {
    owed_ -= dt_;
    ++steps;
  }
  return steps;
}

double FrameClock::SecondsToNextStep() const { return std::max(0.0, dt_ - owed_); }

int FrameClock::MaxStepsPerFrame() const {
  return static_cast<int>(std::floor(max_frame_seconds_ / dt_)) + 1;
}

}  // namespace game
