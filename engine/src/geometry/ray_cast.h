// Ray casts against polygons (rounded or not), capsules and segments, in world placement.
#pragma once

#include "engine/math.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// The ray origin + t·translation for 0 ≤ t ≤ max_fraction, in the world.
struct RayCastInput {
  Vec2 origin;
  Vec2 translation;
  double max_fraction = 1.0;
};

struct CastOutput {
  Vec2 point;            ///< where the ray enters the shape, world
  Vec2 normal;           ///< the outline's outward unit normal there
  double fraction = 0.0;
  bool hit = false;
};

/// A ray starting inside the shape does not hit it (the world's ray cast does the same).
/// A rounded polygon is entered through one of its edges pushed out by the radius or one of
/// the discs round its corners: the first of those the ray enters from outside.
CastOutput RayCastPolygon(const Polygon& polygon, const Transform& xf, const RayCastInput& ray);
CastOutput RayCastCapsule(const Capsule& capsule, const Transform& xf, const RayCastInput& ray);
/// Two-sided: the normal faces the ray's origin.
CastOutput RayCastSegment(Vec2 start, Vec2 end, const Transform& xf, const RayCastInput& ray);

}  // namespace engine::geometry
