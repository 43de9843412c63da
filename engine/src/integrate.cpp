// Semi-implicit and explicit Euler for bodies under gravity.
#include "integrate.h"

namespace engine::detail {

namespace {

// The kicked velocity, written once so both phases compute it to the same bits.
Vec2 Kick(Vec2 velocity, Vec2 gravity, double dt) { return velocity + gravity * dt; }

}  // namespace

void IntegrateVelocities(std::span<BodyState> states, std::span<const std::uint8_t> moving,
                         Vec2 gravity, double dt, std::span<Vec2> start_velocities) {
  for (std::size_t i = 0; i < states.size(); ++i) {
    start_velocities[i] = states[i].velocity;
    if (!moving[i]) continue;
    states[i].velocity = Kick(states[i].velocity, gravity, dt);
  }
}

void IntegratePositions(Integrator integrator, std::span<BodyState> states,
                        std::span<const std::uint8_t> moving, std::span<const Vec2> start_velocities,
                        Vec2 gravity, double dt) {
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (!moving[i]) continue;
    BodyState& s = states[i];
    switch (integrator) {
      case Integrator::kSemiImplicitEuler:
        s.position += s.velocity * dt;
        break;
      case Integrator::kExplicitEuler: {
        const Vec2 contact_change = s.velocity - Kick(start_velocities[i], gravity, dt);
        s.position += (start_velocities[i] + contact_change) * dt;
        break;
      }
    }
  }
}

}  // namespace engine::detail
