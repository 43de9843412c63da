// Casts: a ray, circle or box moving along a straight line, against the world's bodies. The
// World's ray casts and shape casts are this over different movers. Internal to the engine.
#pragma once

#include <optional>
#include <vector>

#include "bodies.h"
#include "engine/filter.h"
#include "engine/queries.h"
#include "engine/shape.h"

namespace engine::detail {

/// What moves, and how the start is treated.
struct Cast {
  Shape shape;       ///< a ray is a circle of radius 0
  Vec2 position;     ///< its centre at the start
  double angle = 0;  ///< turned by this much (rad), all the way
  Vec2 translation;
  /// Shape casts: a body the mover starts inside is met at fraction 0. Rays: it is not met.
  bool starts_inside_counts = false;
};

/// A ray from `from` to `to`.
Cast Ray(Vec2 from, Vec2 to);

/// Where the mover first meets the body (its `body` field left for the caller), if it does.
std::optional<RayHit> CastAgainst(const Cast& cast, const Shape& shape, const BodyState& state);

/// The body the mover meets first, ties going to the lower slot.
std::optional<RayHit> FirstHit(const Bodies& bodies, const Cast& cast, const std::optional<Filter>& filter);
/// Every body the mover meets, by fraction, ties in slot order.
std::vector<RayHit> AllHits(const Bodies& bodies, const Cast& cast, const std::optional<Filter>& filter);

}  // namespace engine::detail
