// The click rule (docs/click-rule.md): a click pushes a ball away from the click point.
#pragma once

#include <cstddef>
#include <optional>

#include "engine/math.h"
#include "engine/world.h"

namespace game {

/// J = max_impulse · (d / r) · (c − p) / d for a click at p on a ball of centre c and radius r,
/// d = |p − c| ≤ r. Zero at the exact centre.
engine::Vec2 ClickImpulse(engine::Vec2 center, double radius, engine::Vec2 p, double max_impulse);

struct ClickHit {
  engine::BodyId body;
  engine::Vec2 impulse;
};

/// The dynamic circle whose disc contains p (the last in scene order when several do), and the
/// impulse it receives; nothing when p hits no dynamic ball.
std::optional<ClickHit> ResolveClick(const engine::World& world, engine::Vec2 p,
                                     double max_impulse);

/// A dynamic ball near a point, for telling a user what a missed click missed.
struct NearBall {
  engine::BodyId body;
  double gap;  ///< metres from the point to the ball's rim (≤ 0 inside it)
};

/// The dynamic circle whose rim is nearest to p (the first in scene order on a tie), or nothing
/// when the world has none.
std::optional<NearBall> NearestBall(const engine::World& world, engine::Vec2 p);

/// Resolves the click and applies its impulse; returns what it hit.
std::optional<ClickHit> ApplyClick(engine::World& world, engine::Vec2 p, double max_impulse);

/// The velocity change a click at p gives a soft-body or fluid particle at x (docs/click-rule.md):
/// away from p, of size speed · 2u for u = |x − p| / radius up to ½, then speed · 2(1 − u) down
/// to 0 at the radius; nothing at p itself or from the radius on.
engine::Vec2 ParticleClickVelocity(engine::Vec2 x, engine::Vec2 p, double radius, double speed);

/// Changes the velocity of every soft-body and fluid particle by ParticleClickVelocity (an
/// impulse of its mass times that); returns how many it changed. Effect particles are not pushed.
std::size_t PushParticles(engine::World& world, engine::Vec2 p, double radius, double speed);

}  // namespace game
