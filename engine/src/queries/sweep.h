// Sweeps: when a point, circle or box moving along a straight line touches a still shape. Ray
// casts and shape casts are built on these. Internal to the engine.
#pragma once

#include <limits>
#include <optional>

#include "engine/math.h"
#include "narrow_phase/collide.h"

namespace engine::detail {

/// The span of the motion p + t·d (t in units of d) during which a mover touches or overlaps a
/// still convex shape: [enter, leave], empty when it never does. `normal` is the still shape's
/// outward normal where it is entered; `starts_inside` says the mover overlaps it, more than
/// touching, at t = 0.
struct Crossing {
  double enter = std::numeric_limits<double>::infinity();
  double leave = -std::numeric_limits<double>::infinity();
  Vec2 normal;
  bool starts_inside = false;

  bool Meets() const { return enter <= leave; }
  /// Inside for every t: the span before any slab narrows it.
  static Crossing Always() {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), {}, true};
  }
};

/// A point moving p + t·d against a circle.
Crossing CircleCrossing(Vec2 p, Vec2 d, Vec2 center, double radius);
/// A point against the axis-aligned box of half extents `half` centred at the origin.
Crossing BoxCrossing(Vec2 p, Vec2 d, Vec2 half);
/// A point against that box grown by `radius` all round (its corners rounded): where a circle of
/// that radius centred on the point touches the box. Radius 0 is the box itself.
Crossing RoundedBoxCrossing(Vec2 p, Vec2 d, Vec2 half, double radius);
/// The box `moving` translated by t·d against the box `still`.
Crossing BoxesCrossing(const OrientedBox& moving, Vec2 d, const OrientedBox& still);

/// The fraction in [0, 1] at which the mover first touches the shape going into it; 0 when it
/// starts inside and `starts_inside_counts`; nothing otherwise (a mover that only touches at
/// t = 0 and leaves, or slides along, never goes in).
std::optional<double> FirstTouch(const Crossing& crossing, bool starts_inside_counts);

}  // namespace engine::detail
