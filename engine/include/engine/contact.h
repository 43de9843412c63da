// Contacts between bodies: what the narrow phase found, and the impulses the solver left on them.
#pragma once

#include <cstdint>

#include "engine/ids.h"
#include "engine/math.h"

namespace engine {

struct ContactPoint {
  Vec2 point;    ///< world point midway between the two surfaces
  double depth;  ///< penetration along the normal, m: 0 when touching, negative for a gap
  /// Which features meet here (a box face's end, say), so the same point can be recognised
  /// next step and warm-started with its impulse.
  std::uint8_t id = 0;
};

/// Up to two contact points sharing one normal. `normal` is a unit vector pointing from shape A
/// to shape B: moving B along it (or A against it) separates them.
struct Manifold {
  Vec2 normal;
  ContactPoint points[2];
  int point_count = 0;
};

struct Contact {
  BodyIndex a;  ///< the lower slot (World::IdAt gives the id)
  BodyIndex b;
  /// Which convex piece of each body (World::Pieces; 0 for a circle or box): bodies made of
  /// parts can touch at several pieces, one contact each, in (a, b, piece_a, piece_b) order.
  std::uint16_t piece_a = 0;
  std::uint16_t piece_b = 0;
  /// One of the bodies is made of parts: a bounce strikes the points that touch first (the
  /// others, a speculative margin behind, would turn a pointed body hit tip-first), where two
  /// lone circles or boxes are struck at the middle of the manifold, as they always were.
  bool strike_first_touch = false;
  Manifold manifold;   ///< normal points from a to b
  double restitution;  ///< the larger of the pair's
  double friction;     ///< the geometric mean of the pair's
  /// Impulses accumulated on each point last step (N·s), carried over to warm-start the next.
  double normal_impulse[2] = {0.0, 0.0};
  double tangent_impulse[2] = {0.0, 0.0};
};

}  // namespace engine
