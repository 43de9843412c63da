// A running scene: events are applied at the start of their step, then the world steps.
#include "game/session.h"

#include <cstdlib>

#include "game/click.h"
#include "game/grab.h"
#include "game/saved_state.h"

namespace game {

namespace {

// Fitted at 800x600 like a scene camera is framed, so the fit too shows the same region at
// every size once framed.
render::Camera ChooseView(const Scene& scene, const engine::World& world) {
  render::Camera camera = render::FitCamera(world, render::kFramingWidth, render::kFramingHeight);
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
      view_(ChooseView(scene, world_)),
      camera_(render::FrameCamera(view_, image_width, image_height)),
      image_width_(image_width),
      image_height_(image_height) {}

void Session::Step() {
  while (next_event_ < events_.size() && events_[next_event_].step <= StepIndex()) {
    ApplyEvent(events_[next_event_++]);
  }
  world_.Step();
}

Status Session::LoadState(const std::string& path) {
  if (Status failed = game::LoadState(path, scene_, &world_)) return failed;
  while (next_event_ < events_.size() && events_[next_event_].step < StepIndex()) ++next_event_;
  return std::nullopt;
}

void Session::Rewind(std::span<const std::uint8_t> snapshot) {
  const engine::RestoreResult restored = world_.RestoreSnapshot(snapshot);
  if (!restored) std::abort();  // its own snapshot: refusing it would be a bug, not bad input
  next_event_ = 0;
  while (next_event_ < events_.size() && events_[next_event_].step < StepIndex()) ++next_event_;
}

Status Session::SaveState(const std::string& path) const { return game::SaveState(path, scene_, world_); }

Status Session::Fault() const {
  const std::optional<engine::NumericFault>& fault = world_.Fault();
  if (!fault) return std::nullopt;
  // A particle's fault names no body (its `what` says which particles).
  const std::string who = fault->body < scene_.bodies.size()
                              ? "body \"" + scene_.bodies[fault->body].id + "\" (bodies[" + std::to_string(fault->body) + "])"
                              : std::string("a particle");
  return RuntimeFailure("the simulation broke down: " + who + " got a non-finite " + fault->what + " in step " +
                        std::to_string(fault->step) + "; the numbers outgrew double precision");
}

engine::Vec2 Session::EventPoint(const InputEvent& event) const {
  if (!IsPixelEvent(event.kind)) return event.at;
  if (event.image_width == 0) {
    return render::PixelToWorld(camera_, image_width_, image_height_, event.at.x, event.at.y);
  }
  const render::Camera camera = render::FrameCamera(view_, event.image_width, event.image_height);
  return render::PixelToWorld(camera, event.image_width, event.image_height, event.at.x,
                              event.at.y);
}

engine::Vec2 Session::ApplyEvent(const InputEvent& event) {
  const engine::Vec2 p = EventPoint(event);
  if (IsClick(event.kind)) {
    const bool hit = ApplyClick(world_, p, scene_.click_max_impulse).has_value();
    // A ball takes the click whole, as before; a click on no ball pushes the particles around it.
    const bool pushed =
        !hit && PushParticles(world_, p, scene_.particle_click.radius, scene_.particle_click.speed) > 0;
    log_.Record(event, p, hit, pushed, world_);
  } else if (IsGrab(event.kind)) {
    log_.RecordGrab(Grab(world_, p).has_value());
  } else if (IsDrag(event.kind)) {
    Drag(world_, p);
    log_.RecordDrag();
  } else {
    Release(world_);
    log_.RecordRelease();
  }
  return p;
}

EventsAfterEnd Session::EventsLeft() const {
  EventsAfterEnd late;
  late.count = events_.size() - next_event_;
  late.first_step = late.count > 0 ? events_[next_event_].step : 0;
  late.end_step = StepIndex();
  return late;
}

}  // namespace game
