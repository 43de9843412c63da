// A running scene: the world, its input events and the camera that maps pixel clicks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/world.h"
#include "game/scene.h"
#include "game/script.h"
#include "render/camera.h"

namespace game {

class Session {
 public:
  /// The camera is the scene's, or a fit of the initial state to an image of this size.
  Session(const Scene& scene, std::vector<InputEvent> events, int image_width, int image_height);

  /// Applies the events due at the current step, then simulates it.
  void Step();

  /// Applies one event now, at the current step (live input).
  void ApplyEvent(const InputEvent& event);

  /// A failure naming the body and step where the simulation produced a non-finite number (exit
  /// code 1), or nothing. Once set, the world no longer steps.
  Status Fault() const;

  const engine::World& World() const { return world_; }
  const render::Camera& Camera() const { return camera_; }
  const Scene& SceneDef() const { return scene_; }
  std::int64_t StepIndex() const { return world_.StepCount(); }
  int ImageWidth() const { return image_width_; }
  int ImageHeight() const { return image_height_; }

 private:
  Scene scene_;
  engine::World world_;
  std::vector<InputEvent> events_;
  std::size_t next_event_ = 0;
  render::Camera camera_;
  int image_width_;
  int image_height_;
};

}  // namespace game
