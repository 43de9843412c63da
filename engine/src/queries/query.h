// What the world's queries share: which bodies they see, and their preconditions. Internal to
// the engine.
#pragma once

#include <cmath>
#include <optional>

#include "bodies.h"
#include "engine/filter.h"
#include "engine/shape.h"
#include "require.h"

namespace engine::detail {

/// Whether a query sees the body in `slot`: it is live and enabled (a free slot is never
/// enabled) and, with a filter, a body of that filter would collide with it.
inline bool IsQueried(const Bodies& bodies, BodyIndex slot, const std::optional<Filter>& filter) {
  return bodies.enabled[slot] != 0 && (!filter || ShouldCollide(*filter, bodies.filters[slot]));
}

/// The rotation of `angle`, without the sine and cosine when nothing is turned.
inline Rot RotationOf(double angle) { return angle == 0.0 ? Rot{} : MakeRot(angle); }

/// A query's shape has a positive finite size and a finite placement; `what` names the call.
inline void RequireQueryShape(const Shape& shape, Vec2 position, double angle, const char* what) {
  const bool sized = shape.type == ShapeType::kCircle
                         ? IsPositiveFinite(shape.radius)
                         : IsPositiveFinite(shape.half_extents.x) && IsPositiveFinite(shape.half_extents.y);
  Require(sized && IsFinite(position) && std::isfinite(angle), what);
}

}  // namespace engine::detail
