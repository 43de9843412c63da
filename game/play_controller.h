// What `ballbox play` does with time and input, apart from any window: the session, the fixed
// step clock, pause and single steps, restart, script replay and the recording. Testable
// without a display; the window loop only feeds it frame times and clicks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "engine/math.h"
#include "game/film_camera.h"
#include "game/frame_clock.h"
#include "game/scene.h"
#include "game/script.h"
#include "game/session.h"

namespace game {

/// Stops for tests and demos (docs/play.md: BALLBOX_PLAY_STOP_AT, BALLBOX_PLAY_PAUSE_AT).
struct PlayLimits {
  std::optional<std::int64_t> stop_at;   ///< the run ends once this step index is reached
  std::optional<std::int64_t> pause_at;  ///< pause (once per run) when this step is reached
};

class PlayController {
 public:
  /// `script`: events to replay (pixel clicks map through the camera of an image_width ×
  /// image_height picture, as in sim and render).
  /// `view`: what the window shows instead of the scene's view (--camera, --follow); live
  /// clicks map through what it shows (Camera()), script pixel clicks through the scene's view.
  PlayController(Scene scene, std::vector<InputEvent> script, int image_width, int image_height,
                 PlayLimits limits = {}, double max_frame_seconds = kMaxFrameSeconds,
                 FilmView view = {});

  /// One frame's real time: takes the steps the clock says are due, unless paused or
  /// finished. Returns the number of steps taken.
  int Advance(double frame_seconds);

  /// A live click at world point `p`, for the current step: applied just before that step is
  /// simulated (the script rule), after the script's events of the same step, and recorded
  /// then. A run that ends first never applies it, so the live state and a replay of the
  /// recording agree at every step. Ignored once finished.
  void Click(engine::Vec2 p);
  /// Live drag input (the right button, game/grab.h), queued and applied as clicks are: the
  /// button went down at `p`, the cursor moved to `p` while it is held, the button went up.
  /// Moves queued for one step come down to the last, which is all that step would see of them.
  void Grab(engine::Vec2 p);
  void Drag(engine::Vec2 p);
  void Release();

  void TogglePause();
  /// While paused and not finished: one step. Returns whether it stepped.
  bool StepOnce();
  /// Starts over: the scene's initial state at step 0, the script from its first event, and an
  /// empty recording (the recording always describes the run since the last start). Paused or
  /// running stays as it was.
  void Restart();
  /// Starts from the state saved in `path` (--load-state); the script's events before its step
  /// are skipped.
  Status LoadState(const std::string& path);
  /// Back in time (Backspace, held): to the last rewind point before the current step. Points
  /// are kept every kRewindEvery steps, the oldest dropped beyond kRewindBytes. The recording
  /// forgets the events from that step on, so it still replays to the live state. Returns
  /// whether it went back (not at the oldest point).
  bool Rewind();
  static constexpr std::int64_t kRewindEvery = 10;
  static constexpr std::size_t kRewindBytes = std::size_t{256} << 20;
  /// The steps the kept rewind points are at, oldest first.
  std::vector<std::int64_t> RewindSteps() const;

  bool Paused() const { return paused_; }
  /// The stop_at step is reached: the run is over.
  bool Finished() const;
  const Session& GetSession() const { return *session_; }
  /// The camera of the picture the window shows (framed at the session's image size).
  render::Camera Camera() const;
  /// Live clicks not applied yet (they wait for the current step to be simulated).
  std::size_t PendingClicks() const;
  /// Live events of any kind not applied yet.
  std::size_t PendingEvents() const { return pending_.size(); }
  /// Every event applied since the last start, in the order applied, as world-point events
  /// (click-world, grab-world, drag-world, release): FormatScript of this replays to the same
  /// state in sim and render, at any --size.
  const std::vector<InputEvent>& Recorded() const { return recorded_; }
  /// Script events and live clicks not applied yet: late, once the run has ended.
  EventsAfterEnd EventsLeft() const;
  /// Real time until the next step is due (for waiting on input in between).
  double SecondsToNextStep() const { return clock_.SecondsToNextStep(); }
  int MaxStepsPerFrame() const { return clock_.MaxStepsPerFrame(); }

 private:
  /// Applies the script events due now, then the live input, then simulates one step.
  void StepOne();
  /// Queues a live event for the current step (nothing once finished).
  void Queue(EventKind kind, engine::Vec2 p);
  /// Applies `event` at the current step as a world-point event and records it.
  void Apply(const InputEvent& event);
  bool PauseDue() const;
  /// Keeps a rewind point at the current step (called at start and every kRewindEvery steps).
  void KeepRewindPoint();

  struct RewindPoint {
    std::int64_t step;
    std::vector<std::uint8_t> snapshot;
  };

  Scene scene_;
  std::vector<InputEvent> script_;
  std::size_t next_script_event_ = 0;
  int image_width_;
  int image_height_;
  PlayLimits limits_;
  bool pause_at_done_ = false;
  FilmView view_;
  std::unique_ptr<Session> session_;
  FilmCamera camera_;
  FrameClock clock_;
  bool paused_ = false;
  std::vector<InputEvent> pending_;  ///< live world-point events waiting for the next step
  std::vector<InputEvent> recorded_;
  std::deque<RewindPoint> rewind_points_;  ///< oldest first
  std::size_t rewind_bytes_ = 0;
};

}  // namespace game
