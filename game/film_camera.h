// The camera a film or the window is drawn through: the scene's view or `--camera`, framed for
// the image, its centre tracking a body with `--follow`. It only changes the picture: pixel
// clicks in scripts keep mapping through the scene's view (Session::EventPoint).
#pragma once

#include <cstdint>
#include <optional>

#include "engine/world.h"
#include "render/camera.h"

namespace game {

/// What the picture shows instead of the scene's view: `--camera` and `--follow`.
struct FilmView {
  std::optional<render::Camera> camera;  ///< centre and width as at 800x600
  std::optional<engine::BodyId> follow;
};

class FilmCamera {
 public:
  /// `view`: centre and width as an 800x600 image shows them. With `follow`, the centre
  /// starts on that body.
  FilmCamera(render::Camera view, std::optional<engine::BodyId> follow, const engine::World& world);

  /// After `steps` simulation steps: the centre moves toward the followed body (aimed at where
  /// its velocity takes it in kFollowSeconds) as a first-order lag of kFollowSeconds, so it
  /// keeps up with a steady mover and a bounce or a click does not jolt the picture.
  void Advance(const engine::World& world, std::int64_t steps = 1);

  /// The camera of a width × height image (render::FrameCamera of the current view).
  render::Camera For(int image_width, int image_height) const;
  const render::Camera& View() const { return view_; }

  /// The lag's time constant: the centre covers 63% of the way to the body in this time.
  static constexpr double kFollowSeconds = 0.25;

 private:
  render::Camera view_;
  std::optional<engine::BodyId> follow_;
};

}  // namespace game
