// A running scene: events are applied at the start of their step, then the world steps.
#include "game/session.h"

#include "game/click.h"

namespace game {

namespace {

render::Camera ChooseCamera(const Scene& scene, const engine::World& world, int width, int height) {
  render::Camera camera = render::FitCamera(world, width, height);
  if (scene.camera.center) camera.center = *scene.camera.center;
  if (scene.camera.width) camera.width = *scene.camera.width;
  return camera;
}

}  // namespace

Session::Session(const Scene& scene, std::vector<InputEvent> events, int image_width,
                 int image_height)
    : scene_(scene),
      world_(BuildWorld(scene)),
      events_(std::move(events)),
      camera_(ChooseCamera(scene, world_, image_width, image_height)),
      image_width_(image_width),
      image_height_(image_height) {}

void Session::Step() {
  while (next_event_ < events_.size() && events_[next_event_].step <= StepIndex()) {
    ApplyEvent(events_[next_event_++]);
  }
  world_.Step();
}

Status Session::Fault() const {
  const std::optional<engine::NumericFault>& fault = world_.Fault();
  if (!fault) return std::nullopt;
  return RuntimeFailure("the simulation broke down: body \"" + scene_.bodies[fault->body].id + "\" (bodies[" +
                        std::to_string(fault->body) + "]) got a non-finite " + fault->what + " in step " +
                        std::to_string(fault->step) + "; the numbers outgrew double precision");
}

void Session::ApplyEvent(const InputEvent& event) {
  const engine::Vec2 p = event.kind == EventKind::kClickPixel
                             ? render::PixelToWorld(camera_, image_width_, image_height_,
                                                    event.at.x, event.at.y)
                             : event.at;
  ApplyClick(world_, p, scene_.click_max_impulse);
}

}  // namespace game
