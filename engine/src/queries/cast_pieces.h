// Casts against a body made of parts: the mover against each of its pieces, the first touch
// kept. Internal to the engine.
#pragma once

#include <optional>

#include "body_geometry.h"
#include "engine/queries.h"
#include "queries/cast.h"

namespace engine::detail {

/// Where the mover first meets one of the body's pieces (the `body` field left for the caller).
/// A ray or circle is cast exactly, as a ray against each piece grown by the circle's radius; a
/// box by conservative advancement on the GJK distance (geometry/time_of_impact.h), to within
/// kBoxCastTolerance.
std::optional<RayHit> CastAgainstPieces(const Cast& cast, const BodyGeometry& geometry, const BodyState& state);

inline constexpr double kBoxCastTolerance = 1e-9;

}  // namespace engine::detail
