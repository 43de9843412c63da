// A running scene: the world, its input events, the camera that maps pixel clicks, and the log
// of what the clicks did.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/world.h"
#include "game/event_log.h"
#include "game/scene.h"
#include "game/script.h"
#include "render/camera.h"

namespace game {

class Session {
 public:
  /// The camera is the scene's, or a fit of the initial state to an 800x600 image, framed for
  /// an image of this size (render::FrameCamera).
  Session(const Scene& scene, std::vector<InputEvent> events, int image_width, int image_height);

  /// Applies the events due at the current step, then simulates it.
  void Step();

  /// Applies one event now, at the current step (live input): a click by the click rule, a
  /// grab, drag or release by the drag rule (game/grab.h); logs what it did. Returns the world
  /// point it acted on ({0, 0} for a release).
  engine::Vec2 ApplyEvent(const InputEvent& event);

  /// The world point an event acts on: a pixel goes through the view framed at the size
  /// the script names (its `size` line), else at this session's image size.
  engine::Vec2 EventPoint(const InputEvent& event) const;

  /// Starts from the state saved in `path` instead of the scene's initial one (bad input if it
  /// was saved from another scene); the events before its step are skipped.
  Status LoadState(const std::string& path);
  /// Goes back to a snapshot this session's world took (TakeSnapshot): its events from that
  /// step on will be applied again.
  void Rewind(std::span<const std::uint8_t> snapshot);
  /// Writes the current state to `path` (--save-state).
  Status SaveState(const std::string& path) const;

  /// A failure naming the body and step where the simulation produced a non-finite number (exit
  /// code 1), or nothing. Once set, the world no longer steps.
  Status Fault() const;

  const engine::World& World() const { return world_; }
  /// The camera of this session's image: the view framed at ImageWidth × ImageHeight.
  const render::Camera& Camera() const { return camera_; }
  /// The scene's view as an 800x600 image shows it (what pixel clicks map through).
  const render::Camera& View() const { return view_; }
  const Scene& SceneDef() const { return scene_; }
  std::int64_t StepIndex() const { return world_.StepCount(); }
  int ImageWidth() const { return image_width_; }
  int ImageHeight() const { return image_height_; }
  const EventLog& Events() const { return log_; }
  /// The given events not applied yet (all of them late once the run has ended).
  EventsAfterEnd EventsLeft() const;

 private:
  Scene scene_;
  engine::World world_;
  std::vector<InputEvent> events_;
  std::size_t next_event_ = 0;
  render::Camera view_;
  render::Camera camera_;
  int image_width_;
  int image_height_;
  EventLog log_;
};

}  // namespace game
