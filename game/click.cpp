// The click rule, written in the contract's own order of operations so results match it bit for bit.
#include "game/click.h"

namespace game {

namespace {

// A ball: a dynamic lone circle. A body made of parts is no ball, even of one circle part (its
// `shapes` entry may sit off the body's origin, and the rule names a ball's centre and radius).
bool IsBall(const engine::World& world, engine::BodyId id) {
  const engine::BodyInfo& info = world.Info(id);
  return !engine::HasInfiniteMass(info) && info.shape.type == engine::ShapeType::kCircle &&
         world.Parts(id).empty();
}

}  // namespace

engine::Vec2 ClickImpulse(engine::Vec2 center, double radius, engine::Vec2 p, double max_impulse) {
  const engine::Vec2 away = center - p;
  const double d = engine::Length(away);
  if (d == 0.0) return {};  // the exact centre has no direction to push in
  const double strength = max_impulse * (d / radius);
  return {strength * away.x / d, strength * away.y / d};
}

std::optional<ClickHit> ResolveClick(const engine::World& world, engine::Vec2 p,
                                     double max_impulse) {
  // Scan from the back: the last ball in scene order is drawn on top, so it takes the click.
  const std::span<const engine::BodyId> ids = world.BodyIds();
  for (auto it = ids.rbegin(); it != ids.rend(); ++it) {
    const engine::BodyId id = *it;
    if (!IsBall(world, id)) continue;
    const engine::BodyInfo& info = world.Info(id);
    const engine::Vec2 center = world.State(id).position;
    const double r = info.shape.radius;
    if (engine::LengthSquared(p - center) > r * r) continue;
    return ClickHit{id, ClickImpulse(center, r, p, max_impulse)};
  }
  return std::nullopt;
}

std::optional<NearBall> NearestBall(const engine::World& world, engine::Vec2 p) {
  std::optional<NearBall> nearest;
  for (const engine::BodyId id : world.BodyIds()) {
    if (!IsBall(world, id)) continue;
    const engine::BodyInfo& info = world.Info(id);
    const double gap = engine::Length(p - world.State(id).position) - info.shape.radius;
    if (!nearest || gap < nearest->gap) nearest = NearBall{id, gap};
  }
  return nearest;
}

std::optional<ClickHit> ApplyClick(engine::World& world, engine::Vec2 p, double max_impulse) {
  const std::optional<ClickHit> hit = ResolveClick(world, p, max_impulse);
  if (hit) world.ApplyLinearImpulseToCenter(hit->body, hit->impulse);
  return hit;
}

engine::Vec2 ParticleClickVelocity(engine::Vec2 x, engine::Vec2 p, double radius, double speed) {
  const engine::Vec2 away = x - p;
  const double d = engine::Length(away);
  if (d == 0.0 || !(d < radius)) return {};
  const double u = d / radius;
  // Rises like the ball rule from the centre, falls to nothing at the edge: no seam in the fluid.
  const double strength = speed * (u <= 0.5 ? 2.0 * u : 2.0 * (1.0 - u));
  return {strength * away.x / d, strength * away.y / d};
}

std::size_t PushParticles(engine::World& world, engine::Vec2 p, double radius, double speed) {
  std::size_t pushed = 0;
  const auto push = [&](engine::Vec2 x, double mass, auto apply) {
    const engine::Vec2 dv = ParticleClickVelocity(x, p, radius, speed);
    if (dv.x == 0.0 && dv.y == 0.0) return;
    apply(mass * dv);
    ++pushed;
  };
  for (const engine::SoftBodyId id : world.SoftBodyIds()) {
    const std::span<const engine::Vec2> positions = world.SoftBodyPositions(id);
    const double mass = world.SoftBodyParticleMass(id);
    for (std::uint32_t i = 0; i < positions.size(); ++i) {
      push(positions[i], mass, [&](engine::Vec2 impulse) { world.ApplySoftBodyImpulse(id, i, impulse); });
    }
  }
  const std::span<const engine::Vec2> fluid = world.FluidPositions();
  const std::span<const double> masses = world.FluidMasses();
  for (std::uint32_t i = 0; i < fluid.size(); ++i) {
    push(fluid[i], masses[i], [&](engine::Vec2 impulse) { world.ApplyFluidImpulse(i, impulse); });
  }
  return pushed;
}

}  // namespace game
