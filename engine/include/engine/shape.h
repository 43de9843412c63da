// Shapes and the mass properties that follow from them.
#pragma once

#include <cstdint>

#include "engine/math.h"

namespace engine {

enum class ShapeType : std::uint8_t { kCircle, kBox };

struct Shape {
  ShapeType type = ShapeType::kCircle;
  double radius = 0.5;             ///< m, circles only
  Vec2 half_extents{0.5, 0.5};     ///< m, boxes only (half the width and height)
};

/// m²: π·r² for a circle, width × height for a box.
constexpr double ShapeArea(const Shape& shape) {
  constexpr double kPi = 3.14159265358979323846;
  return shape.type == ShapeType::kCircle ? kPi * shape.radius * shape.radius
                                          : 4.0 * shape.half_extents.x * shape.half_extents.y;
}

/// kg·m², the moment of inertia about the centre of a body of `mass` kg: a disc ½·m·r², a box
/// m·(w² + h²)/12.
constexpr double ShapeInertia(const Shape& shape, double mass) {
  if (shape.type == ShapeType::kCircle) return 0.5 * mass * shape.radius * shape.radius;
  const double w = 2.0 * shape.half_extents.x, h = 2.0 * shape.half_extents.y;
  return mass * (w * w + h * h) / 12.0;
}

}  // namespace engine
