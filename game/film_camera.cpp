// The follow camera: exponential smoothing in simulated time, so the picture at a step is the
// same whatever --every or --from, and the same run after run.
#include "game/film_camera.h"

#include <cmath>

namespace game {

FilmCamera::FilmCamera(render::Camera view, std::optional<engine::BodyId> follow,
                       const engine::World& world)
    : view_(view), follow_(follow) {
  if (follow_) view_.center = world.State(*follow_).position;
}

void FilmCamera::Advance(const engine::World& world, std::int64_t steps) {
  if (!follow_ || steps <= 0) return;
  // The share of the remaining distance closed in `steps` steps of dt.
  const double seconds = static_cast<double>(steps) * world.Def().dt;
  const double share = 1.0 - std::exp(-seconds / kFollowSeconds);
  // Aimed where the body will be one time constant ahead: a lag of τ behind that point puts the
  // centre on a steady mover (a plain lag trails it by v·τ, 7 m for a clicked ball at 30 m/s,
  // off the picture); a bounce turns the aim round, and the lag smooths the turn.
  const engine::BodyState& body = world.State(*follow_);
  const engine::Vec2 target = body.position + kFollowSeconds * body.velocity;
  view_.center = view_.center + share * (target - view_.center);
}

render::Camera FilmCamera::For(int image_width, int image_height) const {
  return render::FrameCamera(view_, image_width, image_height);
}

}  // namespace game
