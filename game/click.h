// The click rule (docs/click-rule.md): a click pushes a ball away from the click point.
#pragma once

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

}  // namespace game
