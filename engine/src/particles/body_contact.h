// Where a particle (a small disc) meets a rigid body: the contact planes soft bodies, fluid and
// effect particles collide with. Internal.
#pragma once

#include <vector>

#include "bodies.h"
#include "engine/math.h"

namespace engine::detail {

/// A face of a body a particle touches or nearly touches: the particle's centre x stays where
/// Dot(normal, x − surface) ≥ its radius.
struct BodyPlane {
  Vec2 normal;   ///< unit, from the body to the particle
  Vec2 surface;  ///< a point of the body's surface, world
  double friction = 0.0;
};

/// Appends the planes of body `body` (one per convex piece, or one for a lone circle or box)
/// that a disc of `radius` at `center` is within `margin` of. Returns how many it appended.
int AppendBodyPlanes(const Bodies& bodies, BodyIndex body, Vec2 center, double radius, double margin,
                     std::vector<BodyPlane>* out);

}  // namespace engine::detail
