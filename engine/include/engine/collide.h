// Narrow phase: exact contact manifolds between circles and axis-aligned boxes.
#pragma once

#include "engine/math.h"

namespace engine {

struct ContactPoint {
  Vec2 point;    ///< world point midway between the two surfaces
  double depth;  ///< penetration along the normal, m; 0 when exactly touching, never negative
};

/// Up to two contact points sharing one normal. `normal` is a unit vector pointing from shape A
/// to shape B: moving B along it (or A against it) separates them.
struct Manifold {
  Vec2 normal;
  ContactPoint points[2];
  int point_count = 0;
};

/// Each function returns false (and leaves `out` alone) when the shapes are apart; touching
/// shapes collide with depth 0. Boxes are given by centre and half extents.
bool CollideCircles(Vec2 center_a, double radius_a, Vec2 center_b, double radius_b, Manifold* out);
bool CollideCircleBox(Vec2 center_a, double radius_a, Vec2 center_b, Vec2 half_b, Manifold* out);
bool CollideBoxes(Vec2 center_a, Vec2 half_a, Vec2 center_b, Vec2 half_b, Manifold* out);

}  // namespace engine
