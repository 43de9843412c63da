// The fixed-step accumulator of the real-time loop: real time owed turns into whole steps of
// dt (dt never changes), and a frame-time clamp keeps a slow frame from snowballing.
#pragma once

namespace game {

/// A long frame (a debugger stop, a dragged window) would otherwise owe so many steps that
/// simulating them makes the next frame longer still: the spiral of death.
inline constexpr double kMaxFrameSeconds = 0.25;

class FrameClock {
 public:
  /// `dt` > 0: the fixed step, s. `max_frame_seconds` > 0: the most real time one frame counts.
  explicit FrameClock(double dt, double max_frame_seconds = kMaxFrameSeconds);

  /// Adds one frame's real time (clamped to [0, max_frame_seconds]; NaN counts as 0) and
  /// returns how many steps are due now; the remainder stays owed to the next frame.
  int Advance(double frame_seconds);

  /// Real time until the next step falls due, ≥ 0.
  double SecondsToNextStep() const;

  /// Forgets the time owed: after a pause, a restart, or steps taken by hand.
  void Reset() { owed_ = 0.0; }

  /// The most steps one Advance returns: floor(max_frame_seconds / dt) + 1 (the +1 is the
  /// remainder owed from earlier frames).
  int MaxStepsPerFrame() const;

  double Dt() const { return dt_; }

 private:
  double dt_;
  double max_frame_seconds_;
  double owed_ = 0.0;  ///< real time not yet turned into steps, in [0, dt)
};

}  // namespace game
