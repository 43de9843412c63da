// Shapes and the mass properties that follow from them: circles and boxes (each a whole body, on
// the engine's fast paths), and bodies made of parts (polygons, capsules, segment polylines,
// circles and boxes placed in the body's frame), which the engine collides as convex pieces.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/math.h"

namespace engine {

enum class ShapeType : std::uint8_t {
  kCircle,
  kBox,
  kPolygon,   ///< convex or concave, optionally rounded
  kCapsule,
  kSegments,  ///< a polyline, open or closed; static bodies only
  kCompound,  ///< a body of several parts (BodyInfo::shape only; never a part's type)
};

/// What a body is, as BodyInfo reports it. Circles and boxes are described here in full; a body
/// made of parts (BodyDef::parts) has the type of its one part, or kCompound, and its geometry
/// is in World::Parts and World::Pieces.
struct Shape {
  ShapeType type = ShapeType::kCircle;
  double radius = 0.5;             ///< m, circles only
  Vec2 half_extents{0.5, 0.5};     ///< m, boxes only (half the width and height)
};

/// Whether the body is a lone circle or box (its centre is its origin), not made of parts.
constexpr bool IsSimpleShape(ShapeType type) { return type == ShapeType::kCircle || type == ShapeType::kBox; }

/// One part of a body made of parts, in the body's frame (whose origin is BodyDef::position).
struct ShapePart {
  ShapeType type = ShapeType::kPolygon;  ///< kCircle, kBox, kPolygon, kCapsule or kSegments
  /// kPolygon: the outline, 3 to 64 points in order around it, either direction, convex or
  /// concave (simple: no edge crosses another); kSegments: the polyline, 2 or more points.
  std::vector<Vec2> points;
  bool loop = false;            ///< kSegments: the last point joins the first
  /// kCircle and kCapsule: the radius (> 0); kPolygon: every corner rounded by it (≥ 0; the
  /// shape grows by it).
  double radius = 0.0;
  Vec2 half_extents;            ///< kBox, m
  double length = 0.0;          ///< kCapsule: between the cap centres, along the part's x axis
  Vec2 offset;                  ///< where the part's own frame stands in the body's frame
  double angle = 0.0;           ///< rad
  // A part's own material; unset means the body's (BodyDef::density, friction, restitution).
  std::optional<double> density;
  std::optional<double> friction;
  std::optional<double> restitution;
};

/// What is wrong with a part: the key at fault, named as the scene format names it ("vertices",
/// "points", "radius", "length", "size", "offset", "angle", "density", "friction",
/// "restitution", "shape") and what is wrong with it.
struct PartProblem {
  std::string key;
  std::string message;
};

/// Checks a part as CreateBody requires it (finite numbers, sizes > 0, 3 to 64 polygon points
/// forming a simple outline with area, a polyline without zero-length segments, segments only on
/// a static body), so a loader can name what is wrong instead of the engine stopping.
std::optional<PartProblem> CheckShapePart(const ShapePart& part, bool is_static);

/// A convex piece of a body as the engine collides it, in the body's frame: a concave polygon
/// gives several, a polyline one a segment.
struct ConvexPiece {
  /// kCircle (vertices[0] the centre), kPolygon (3 or more vertices, counter-clockwise, boxes
  /// too), kCapsule (the two cap centres) or kSegments (one segment: its two ends).
  ShapeType type = ShapeType::kPolygon;
  std::vector<Vec2> vertices;
  double radius = 0.0;  ///< the circle's, the capsule's, or the polygon's rounding
  int part = 0;         ///< which of the body's parts it comes from
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
