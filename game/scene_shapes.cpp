// Scene shapes: the keys of each shape, read and checked at the edge; the geometry a part must
// have (simple outlines, no zero-length segments, ...) is engine::CheckShapePart's, named here by
// the key path of the part it is in.
#include "game/scene_shapes.h"

#include <cmath>
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/shape.h"
#include "game/limits.h"

namespace game::scene_values {

namespace {

using engine::ShapeType;

constexpr int kMinPolygonPoints = 3;
constexpr int kMaxPolygonPoints = 64;
constexpr int kMinSegmentPoints = 2;

// The keys that describe a shape, in the order a shape's stray keys are reported.
constexpr const char* kShapeKeys[] = {"radius", "size", "vertices", "length", "points", "loop"};

// Keys only the entries of `shapes` take; on a body they are misplaced.
constexpr const char* kPartOnlyKeys[] = {"offset"};

// Body keys that have no meaning for one part of a body.
constexpr const char* kBodyOnlyKeys[] = {
    "id", "position", "velocity", "angular_velocity", "mass", "static", "kinematic", "fixed_rotation",
    "bullet", "color", "linear_damping", "angular_damping", "drag_coefficient", "shapes"};

ShapeType ReadShapeType(const Json& value, const std::string& path) {
  return ReadChoice<ShapeType>(value, path,
                               {{"circle", ShapeType::kCircle},
                                {"box", ShapeType::kBox},
                                {"polygon", ShapeType::kPolygon},
                                {"capsule", ShapeType::kCapsule},
                                {"segment", ShapeType::kSegments}});
}

bool Takes(ShapeType type, std::string_view key) {
  switch (type) {
    case ShapeType::kCircle: return key == "radius";
    case ShapeType::kBox: return key == "size";
    case ShapeType::kPolygon: return key == "vertices" || key == "radius";
    case ShapeType::kCapsule: return key == "length" || key == "radius";
    case ShapeType::kSegments: return key == "points" || key == "loop";
    case ShapeType::kCompound: return false;
  }
  return false;
}

// Which shapes take a key, for the message when another shape has it.
const char* Owners(std::string_view key) {
  if (key == "radius") return "circles, capsules and polygons";
  if (key == "size") return "boxes";
  if (key == "vertices") return "polygons";
  if (key == "length") return "capsules";
  return "segments";  // points, loop
}

const char* WhatItHas(ShapeType type) {
  switch (type) {
    case ShapeType::kCircle: return "a circle has a \"radius\"";
    case ShapeType::kBox: return "a box has a \"size\"";
    case ShapeType::kPolygon: return "a polygon has \"vertices\" and an optional \"radius\"";
    case ShapeType::kCapsule: return "a capsule has a \"length\" and a \"radius\"";
    case ShapeType::kSegments: return "a segment has \"points\" and an optional \"loop\"";
    case ShapeType::kCompound: break;
  }
  return "";
}

double ReadSize(const Json& value, const std::string& path) {
  const double v = ReadPositive(value, path);
  if (!(v >= kMinBodySize)) throw SceneError{path, TooSmall()};
  return v;
}

// [[x, y], ...] with `least` to `most` points, each apart from the one before it (and, closed,
// the last from the first) by at least kMinBodySize: nearer, the edge between them is rounding
// noise (docs/limits.md).
std::vector<engine::Vec2> ReadPoints(const Json& value, const std::string& path, std::size_t least,
                                     std::size_t most, bool closed, const char* shape_name) {
  if (!value.is_array()) throw SceneError{path, "must be an array of points [x, y]"};
  const std::size_t n = value.size();
  if (n < least || n > most) {
    const std::string range = most == SIZE_MAX ? "at least " + std::to_string(least)
                                               : std::to_string(least) + " to " + std::to_string(most);
    throw SceneError{path, "has " + std::to_string(n) + (n == 1 ? " point" : " points") + "; a " +
                               shape_name + " needs " + range};
  }
  std::vector<engine::Vec2> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string at = path + "[" + std::to_string(i) + "]";
    points.push_back(ReadVec2(value[i], at));
    if (i > 0 && !(engine::Length(points[i] - points[i - 1]) >= kMinBodySize)) {
      throw SceneError{at, "is the point before it, or within 1e-09 m of it (docs/limits.md)"};
    }
  }
  if (closed && !(engine::Length(points.front() - points.back()) >= kMinBodySize)) {
    throw SceneError{path + "[" + std::to_string(n - 1) + "]",
                     std::string("is the first point, or within 1e-09 m of it: a ") + shape_name +
                         " closes by itself (docs/limits.md)"};
  }
  return points;
}

// The keys of a shape of the given type, in `object` (a body or an entry of `shapes`).
engine::ShapePart ReadShapeKeys(const Json& object, const std::string& path, ShapeType type) {
  auto key = [&](const char* k) { return Join(path, k); };
  for (const char* k : kShapeKeys) {
    if (Find(object, k) && !Takes(type, k)) {
      throw SceneError{key(k), std::string("applies to ") + Owners(k) + " only; " + WhatItHas(type)};
    }
  }
  engine::ShapePart part;
  part.type = type;
  switch (type) {
    case ShapeType::kCircle: {
      const Json* radius = Find(object, "radius");
      if (!radius) throw SceneError{path, "a circle needs a \"radius\""};
      part.radius = ReadSize(*radius, key("radius"));
      break;
    }
    case ShapeType::kBox: {
      const Json* size = Find(object, "size");
      if (!size) throw SceneError{path, "a box needs a \"size\" [width, height]"};
      const engine::Vec2 s = ReadVec2(*size, key("size"));
      if (!(s.x > 0.0)) throw SceneError{key("size") + "[0]", "must be > 0"};
      if (!(s.y > 0.0)) throw SceneError{key("size") + "[1]", "must be > 0"};
      if (!(s.x >= kMinBodySize)) throw SceneError{key("size") + "[0]", TooSmall()};
      if (!(s.y >= kMinBodySize)) throw SceneError{key("size") + "[1]", TooSmall()};
      part.half_extents = 0.5 * s;
      break;
    }
    case ShapeType::kPolygon: {
      const Json* vertices = Find(object, "vertices");
      if (!vertices) throw SceneError{path, "a polygon needs \"vertices\" [[x, y], ...]"};
      part.points = ReadPoints(*vertices, key("vertices"), kMinPolygonPoints, kMaxPolygonPoints, true, "polygon");
      if (const Json* radius = Find(object, "radius")) part.radius = ReadNonNegative(*radius, key("radius"));
      break;
    }
    case ShapeType::kCapsule: {
      const Json* length = Find(object, "length");
      if (!length) throw SceneError{path, "a capsule needs a \"length\" (between its cap centres)"};
      const Json* radius = Find(object, "radius");
      if (!radius) throw SceneError{path, "a capsule needs a \"radius\""};
      part.length = ReadSize(*length, key("length"));
      part.radius = ReadSize(*radius, key("radius"));
      break;
    }
    case ShapeType::kSegments: {
      if (const Json* loop = Find(object, "loop")) part.loop = ReadBool(*loop, key("loop"));
      const Json* points = Find(object, "points");
      if (!points) throw SceneError{path, "a segment needs \"points\" [[x, y], ...]"};
      part.points = ReadPoints(*points, key("points"), kMinSegmentPoints, SIZE_MAX, part.loop, "segment");
      break;
    }
    case ShapeType::kCompound: break;
  }
  return part;
}

// Segments are static only; then the engine's own check of the part's geometry.
void CheckPart(const engine::ShapePart& part, const std::string& path, const engine::BodyDef& def) {
  if (part.type == ShapeType::kSegments && !def.is_static) {
    throw SceneError{Join(path, "shape"), "a segment belongs to static bodies only (\"static\": true)"};
  }
  if (const std::optional<engine::PartProblem> problem = engine::CheckShapePart(part, def.is_static)) {
    throw SceneError{Join(path, problem->key), problem->message};
  }
}

// One entry of `shapes`: a shape with its keys, placed in the body's frame, with its own material.
engine::ShapePart ReadPart(const Json& entry, const std::string& path, const engine::BodyDef& def) {
  if (!entry.is_object()) throw SceneError{path, "must be an object"};
  auto key = [&](const char* k) { return Join(path, k); };
  for (const char* k : kBodyOnlyKeys) {
    if (!Find(entry, k)) continue;
    const std::string_view name = k;
    if (name == "position") throw SceneError{key(k), "a part is placed by \"offset\" (and \"angle\") in the body's frame"};
    if (name == "shapes") throw SceneError{key(k), "parts do not nest: list every part in the body's \"shapes\""};
    throw SceneError{key(k), "belongs to the body, not to one of its parts"};
  }
  RejectUnknownKeys(entry, path,
                    {"shape", "radius", "size", "vertices", "length", "points", "loop", "offset", "angle",
                     "density", "friction", "restitution"});
  const Json* shape = Find(entry, "shape");
  if (!shape) {
    throw SceneError{path, "needs a \"shape\" (\"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\")"};
  }
  engine::ShapePart part = ReadShapeKeys(entry, path, ReadShapeType(*shape, key("shape")));
  if (const Json* v = Find(entry, "offset")) part.offset = ReadVec2(*v, key("offset"));
  if (const Json* v = Find(entry, "angle")) part.angle = ReadNumber(*v, key("angle"));
  if (const Json* v = Find(entry, "density")) {
    if (def.is_static) throw SceneError{key("density"), "a static body takes no mass, density or velocity"};
    if (def.is_kinematic) {
      throw SceneError{key("density"), "a kinematic body takes no mass or density (nothing pushes it)"};
    }
    part.density = ReadPositive(*v, key("density"));
  }
  if (const Json* v = Find(entry, "friction")) part.friction = ReadNonNegative(*v, key("friction"));
  if (const Json* v = Find(entry, "restitution")) part.restitution = ReadNonNegative(*v, key("restitution"));
  CheckPart(part, path, def);
  return part;
}

// m²: what the engine's mass adds up, near enough for a lower bound (a concave rounded polygon's
// reflex corners are counted as if convex).
double PartArea(const engine::ShapePart& part) {
  constexpr double kPi = 3.14159265358979323846;
  const double r = part.radius;
  switch (part.type) {
    case ShapeType::kCircle: return kPi * r * r;
    case ShapeType::kBox: return 4.0 * part.half_extents.x * part.half_extents.y;
    case ShapeType::kCapsule: return 2.0 * r * part.length + kPi * r * r;
    case ShapeType::kPolygon: {
      double twice_area = 0.0, perimeter = 0.0;
      for (std::size_t i = 0; i < part.points.size(); ++i) {
        const engine::Vec2 a = part.points[i], b = part.points[(i + 1) % part.points.size()];
        twice_area += engine::Cross(a, b);
        perimeter += engine::Length(b - a);
      }
      return 0.5 * std::abs(twice_area) + perimeter * r + kPi * r * r;
    }
    case ShapeType::kSegments:
    case ShapeType::kCompound: return 0.0;
  }
  return 0.0;
}

}  // namespace

void ReadBodyShape(const Json& body, const std::string& path, engine::BodyDef* def) {
  auto key = [&](const char* k) { return Join(path, k); };
  for (const char* k : kPartOnlyKeys) {
    if (Find(body, k)) {
      throw SceneError{key(k), "applies to the entries of \"shapes\" only; a body is placed by \"position\""};
    }
  }
  const Json* shape = Find(body, "shape");
  const Json* shapes = Find(body, "shapes");
  if (shape && shapes) throw SceneError{path, "give \"shape\" or \"shapes\", not both"};
  if (shapes) {
    for (const char* k : kShapeKeys) {
      if (Find(body, k)) throw SceneError{key(k), "belongs in an entry of \"shapes\", not on the body"};
    }
    if (!shapes->is_array()) throw SceneError{key("shapes"), "must be an array of shapes"};
    if (shapes->empty()) throw SceneError{key("shapes"), "must hold at least one shape"};
    def->parts.reserve(shapes->size());
    for (std::size_t i = 0; i < shapes->size(); ++i) {
      def->parts.push_back(ReadPart((*shapes)[i], key("shapes") + "[" + std::to_string(i) + "]", *def));
    }
    return;
  }
  if (!shape) {
    throw SceneError{path, "needs a \"shape\" (\"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\") "
                           "or \"shapes\" (a list of them)"};
  }
  const ShapeType type = ReadShapeType(*shape, key("shape"));
  engine::ShapePart part = ReadShapeKeys(body, path, type);
  if (engine::IsSimpleShape(type)) {
    // A lone circle or box is the body itself, centred on its position, as it always was.
    def->shape.type = type;
    if (type == ShapeType::kCircle) def->shape.radius = part.radius;
    if (type == ShapeType::kBox) def->shape.half_extents = part.half_extents;
    return;
  }
  CheckPart(part, path, *def);
  def->parts.push_back(std::move(part));
}

double MassFromDensity(const engine::BodyDef& def) {
  if (def.parts.empty()) return def.density * engine::ShapeArea(def.shape);
  double mass = 0.0;
  for (const engine::ShapePart& part : def.parts) mass += part.density.value_or(def.density) * PartArea(part);
  return mass;
}

}  // namespace game::scene_values
