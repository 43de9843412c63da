// Bodies made of parts, in a line each, for the shape tests.
#pragma once

#include <vector>

#include "engine/world.h"

namespace testing {

inline engine::ShapePart PolygonPart(std::vector<engine::Vec2> points, double radius = 0.0) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kPolygon;
  part.points = std::move(points);
  part.radius = radius;
  return part;
}

inline engine::ShapePart BoxPart(engine::Vec2 size, engine::Vec2 offset = {}, double angle = 0.0) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kBox;
  part.half_extents = 0.5 * size;
  part.offset = offset;
  part.angle = angle;
  return part;
}

inline engine::ShapePart CapsulePart(double length, double radius) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kCapsule;
  part.length = length;
  part.radius = radius;
  return part;
}

inline engine::ShapePart SegmentsPart(std::vector<engine::Vec2> points, bool loop = false) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kSegments;
  part.points = std::move(points);
  part.loop = loop;
  return part;
}

/// A world with rotation on (bodies made of parts turn), sleeping as asked.
inline engine::WorldDef TurningWorld(bool sleeping = true) {
  engine::WorldDef def;
  def.rotation = true;
  def.sleeping = sleeping;
  return def;
}

/// A body of `parts` whose frame's origin stands at `position`, turned by `angle`.
inline engine::BodyDef PartsBody(std::vector<engine::ShapePart> parts, engine::Vec2 position, double angle = 0.0) {
  engine::BodyDef def;
  def.parts = std::move(parts);
  def.position = position;
  def.angle = angle;
  return def;
}

/// A regular polygon of `n` vertices on a circle of radius `r` about the origin, counter-clockwise.
inline std::vector<engine::Vec2> RegularPolygon(int n, double r, double phase = 0.0) {
  std::vector<engine::Vec2> points;
  for (int i = 0; i < n; ++i) {
    const double a = phase + 2.0 * 3.14159265358979323846 * i / n;
    points.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return points;
}

/// An axis-aligned square of side `side` centred on the origin, as polygon points.
inline std::vector<engine::Vec2> SquarePoints(double side) {
  const double h = 0.5 * side;
  return {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
}

}  // namespace testing
