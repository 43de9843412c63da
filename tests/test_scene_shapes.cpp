// game::ParseScene for polygons, capsules, segments and `shapes` lists (contract: "More shapes,
// compound bodies and joints"): each key read into the engine::ShapePart expected by hand, each
// bad input named by its key path, and the dump reporting a body's origin.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "game/click.h"
#include "game/scene.h"
#include "run_program.h"

namespace {

using engine::ShapeType;
using engine::Vec2;

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

// A scene of the given bodies (JSON array text), with `rotation` as given.
std::string SceneWith(const std::string& bodies, bool rotation = false) {
  return std::string("{\"rotation\": ") + (rotation ? "true" : "false") + ", \"bodies\": " + bodies + "}";
}

game::Scene RequireParsed(const std::string& json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "shapes.json", "shapes");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

// Bad input whose message is "shapes.json: " then exactly `rest`.
void RequireError(const std::string& json, const std::string& rest) {
  const game::Expected<game::Scene> scene = game::ParseScene(json, "shapes.json", "shapes");
  INFO(json);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == "shapes.json: " + rest);
}

// Bad input named at `key_path`, whatever the reason (the engine's CheckShapePart words it).
void RequireErrorAt(const std::string& json, const std::string& key_path) {
  const game::Expected<game::Scene> scene = game::ParseScene(json, "shapes.json", "shapes");
  INFO(json);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  const std::string& message = scene.Error().message;
  INFO(message);
  CHECK(message.rfind("shapes.json: " + key_path + ": ", 0) == 0);
  CHECK(message.size() > ("shapes.json: " + key_path + ": ").size());
  CHECK(message.find('\n') == std::string::npos);
}

bool Same(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }

bool SamePoints(const std::vector<Vec2>& points, const std::vector<Vec2>& expected) {
  if (points.size() != expected.size()) return false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!Same(points[i], expected[i])) return false;
  }
  return true;
}

// A part with nothing but what its shape needs: no placement, no material of its own.
void CheckPlainPlacement(const engine::ShapePart& part) {
  CHECK(Same(part.offset, {0, 0}));
  CHECK(part.angle == 0.0);
  CHECK_FALSE(part.density.has_value());
  CHECK_FALSE(part.friction.has_value());
  CHECK_FALSE(part.restitution.has_value());
}

constexpr double kPi = 3.14159265358979323846;

const char* kTriangle = "[[0, 0], [2, 0], [0, 1]]";

}  // namespace

// --- Each new key loads to the part written out by hand.

TEST_CASE("scene shapes: a polygon body is one kPolygon part at its position", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"([{"shape": "polygon", "vertices": [[0, 0], [2, 0], [2, 1], [1, 2.5], [0, 1]], "position": [3, 4]}])"));
  REQUIRE(scene.bodies.size() == 1);
  const engine::BodyDef& def = scene.bodies[0].def;
  CHECK(Same(def.position, {3, 4}));
  REQUIRE(def.parts.size() == 1);
  const engine::ShapePart& part = def.parts[0];
  CHECK(part.type == ShapeType::kPolygon);
  CHECK(SamePoints(part.points, {{0, 0}, {2, 0}, {2, 1}, {1, 2.5}, {0, 1}}));
  CHECK(part.radius == 0.0);
  CHECK_FALSE(part.loop);
  CheckPlainPlacement(part);
}

TEST_CASE("scene shapes: a polygon's radius rounds it, and either direction loads as given",
          "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"([{"shape": "polygon", "vertices": [[0, 0], [0, 1], [2, 0]], "radius": 0.125, "position": [0, 0]}])"));
  const engine::ShapePart& part = scene.bodies[0].def.parts.at(0);
  CHECK(part.type == ShapeType::kPolygon);
  CHECK(SamePoints(part.points, {{0, 0}, {0, 1}, {2, 0}}));  // clockwise, kept in its order
  CHECK(part.radius == 0.125);
}

TEST_CASE("scene shapes: a concave polygon loads as written (the engine splits it)", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"([{"shape": "polygon", "vertices": [[0, 0], [4, 0], [4, 3], [2, 1], [0, 3]], "position": [0, 1]}])"));
  const engine::ShapePart& part = scene.bodies[0].def.parts.at(0);
  CHECK(SamePoints(part.points, {{0, 0}, {4, 0}, {4, 3}, {2, 1}, {0, 3}}));
}

TEST_CASE("scene shapes: 64 polygon vertices load", "[scene][shapes]") {
  std::ostringstream vertices;
  vertices.precision(17);
  vertices << "[";
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * kPi * i / 64.0;
    vertices << (i ? ", " : "") << "[" << std::cos(a) << ", " << std::sin(a) << "]";
  }
  vertices << "]";
  const game::Scene scene = RequireParsed(
      SceneWith(R"([{"shape": "polygon", "vertices": )" + vertices.str() + R"(, "position": [0, 0]}])"));
  CHECK(scene.bodies[0].def.parts.at(0).points.size() == 64);
}

TEST_CASE("scene shapes: a capsule body is one kCapsule part", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"([{"shape": "capsule", "length": 1.5, "radius": 0.25, "position": [-1, 2], "density": 3}])"));
  const engine::BodyDef& def = scene.bodies[0].def;
  CHECK(Same(def.position, {-1, 2}));
  CHECK(def.density == 3.0);
  REQUIRE(def.parts.size() == 1);
  const engine::ShapePart& part = def.parts[0];
  CHECK(part.type == ShapeType::kCapsule);
  CHECK(part.length == 1.5);
  CHECK(part.radius == 0.25);
  CHECK(part.points.empty());
  CheckPlainPlacement(part);
}

TEST_CASE("scene shapes: a static segment body is one kSegments part, open or a loop", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([
    {"shape": "segment", "points": [[-5, 0], [0, -1], [5, 0]], "position": [0, 0], "static": true},
    {"shape": "segment", "points": [[0, 0], [1, 0], [1, 1], [0, 1]], "loop": true, "position": [7, 8],
     "static": true},
    {"shape": "segment", "points": [[0, 0], [3, 0]], "loop": false, "position": [0, 0], "static": true}])"));
  REQUIRE(scene.bodies.size() == 3);
  const engine::ShapePart& open = scene.bodies[0].def.parts.at(0);
  CHECK(open.type == ShapeType::kSegments);
  CHECK(SamePoints(open.points, {{-5, 0}, {0, -1}, {5, 0}}));
  CHECK_FALSE(open.loop);
  CheckPlainPlacement(open);
  const engine::ShapePart& loop = scene.bodies[1].def.parts.at(0);
  CHECK(loop.loop);
  CHECK(SamePoints(loop.points, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}));
  CHECK(Same(scene.bodies[1].def.position, {7, 8}));
  CHECK(scene.bodies[1].def.is_static);
  const engine::ShapePart& two = scene.bodies[2].def.parts.at(0);
  CHECK(SamePoints(two.points, {{0, 0}, {3, 0}}));
  CHECK_FALSE(two.loop);
}

TEST_CASE("scene shapes: \"shapes\" gives one part per entry, in order, with placement and material",
          "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([
    {"id": "robot", "position": [1, 2], "angle": 0.5, "friction": 0.7, "shapes": [
      {"shape": "circle", "radius": 0.5},
      {"shape": "box", "size": [2, 0.5], "offset": [0, -1], "angle": 0.25, "density": 2},
      {"shape": "polygon", "vertices": [[0, 0], [1, 0], [0, 1]], "radius": 0.05, "offset": [1.5, 0],
       "friction": 0.1, "restitution": 0.9},
      {"shape": "capsule", "length": 2, "radius": 0.2, "offset": [-2, 0.5], "angle": -1.5}]}])",
                                                    true));
  REQUIRE(scene.bodies.size() == 1);
  const engine::BodyDef& def = scene.bodies[0].def;
  CHECK(scene.bodies[0].id == "robot");
  CHECK(Same(def.position, {1, 2}));
  CHECK(def.angle == 0.5);
  CHECK(def.friction == 0.7);
  REQUIRE(def.parts.size() == 4);

  const engine::ShapePart& circle = def.parts[0];
  CHECK(circle.type == ShapeType::kCircle);
  CHECK(circle.radius == 0.5);
  CHECK(circle.points.empty());
  CheckPlainPlacement(circle);

  const engine::ShapePart& box = def.parts[1];
  CHECK(box.type == ShapeType::kBox);
  CHECK(Same(box.half_extents, {1, 0.25}));  // half the size, as a body's box
  CHECK(Same(box.offset, {0, -1}));
  CHECK(box.angle == 0.25);
  CHECK(box.density == 2.0);
  CHECK_FALSE(box.friction.has_value());
  CHECK_FALSE(box.restitution.has_value());

  const engine::ShapePart& polygon = def.parts[2];
  CHECK(polygon.type == ShapeType::kPolygon);
  CHECK(SamePoints(polygon.points, {{0, 0}, {1, 0}, {0, 1}}));
  CHECK(polygon.radius == 0.05);
  CHECK(Same(polygon.offset, {1.5, 0}));
  CHECK(polygon.angle == 0.0);
  CHECK_FALSE(polygon.density.has_value());
  CHECK(polygon.friction == 0.1);
  CHECK(polygon.restitution == 0.9);

  const engine::ShapePart& capsule = def.parts[3];
  CHECK(capsule.type == ShapeType::kCapsule);
  CHECK(capsule.length == 2.0);
  CHECK(capsule.radius == 0.2);
  CHECK(Same(capsule.offset, {-2, 0.5}));
  CHECK(capsule.angle == -1.5);
}

TEST_CASE("scene shapes: a part's angle is its placement, allowed without rotation", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(
      R"([{"position": [0, 0], "shapes": [{"shape": "box", "size": [1, 1], "angle": 0.75}]}])"));
  CHECK(scene.bodies[0].def.parts.at(0).angle == 0.75);
  CHECK(scene.bodies[0].def.angle == 0.0);
}

TEST_CASE("scene shapes: a static body of segments and other parts", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([
    {"static": true, "position": [0, 0], "shapes": [
      {"shape": "segment", "points": [[-10, 0], [10, 0]]},
      {"shape": "segment", "points": [[-10, 0], [-10, 5], [-9, 5]], "loop": true, "restitution": 0.5},
      {"shape": "box", "size": [1, 1], "offset": [0, 3]}]}])"));
  const engine::BodyDef& def = scene.bodies[0].def;
  REQUIRE(def.parts.size() == 3);
  CHECK(def.parts[0].type == ShapeType::kSegments);
  CHECK_FALSE(def.parts[0].loop);
  CHECK(def.parts[1].loop);
  CHECK(def.parts[1].restitution == 0.5);
  CHECK(def.parts[2].type == ShapeType::kBox);
}

TEST_CASE("scene shapes: circles and boxes stay whole-body shapes with no parts, as before",
          "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([
    {"shape": "circle", "radius": 0.75, "position": [1, 2]},
    {"shape": "box", "size": [3, 1], "position": [-1, 0], "static": true}])"));
  const engine::BodyDef& circle = scene.bodies[0].def;
  CHECK(circle.parts.empty());
  CHECK(circle.shape.type == ShapeType::kCircle);
  CHECK(circle.shape.radius == 0.75);
  CHECK(Same(circle.shape.half_extents, {0.5, 0.5}));  // the BodyDef default, untouched
  const engine::BodyDef& box = scene.bodies[1].def;
  CHECK(box.parts.empty());
  CHECK(box.shape.type == ShapeType::kBox);
  CHECK(Same(box.shape.half_extents, {1.5, 0.5}));
  CHECK(box.shape.radius == 0.5);  // the BodyDef default, untouched
  // Every other field as a default BodyDef has it.
  const engine::BodyDef plain;
  for (const engine::BodyDef* def : {&circle, &box}) {
    CHECK(def->density == plain.density);
    CHECK(def->mass == plain.mass);
    CHECK(def->restitution == plain.restitution);
    CHECK(def->friction == plain.friction);
    CHECK(def->drag_coefficient == plain.drag_coefficient);
  }
}

TEST_CASE("scene shapes: the scene of every new key in tests/data loads", "[scene][shapes]") {
  const game::Expected<game::Scene> scene = game::LoadScene(DataPath("scene_shapes.json"));
  if (!scene.HasValue()) FAIL(scene.Error().message);
  const std::vector<game::SceneBody>& bodies = scene.Value().bodies;
  REQUIRE(bodies.size() == 6);
  CHECK(bodies[0].def.parts.at(0).type == ShapeType::kSegments);
  CHECK(bodies[1].def.parts.at(0).type == ShapeType::kPolygon);
  CHECK(bodies[2].def.parts.at(0).type == ShapeType::kPolygon);  // concave
  CHECK(bodies[3].def.parts.at(0).type == ShapeType::kCapsule);
  CHECK(bodies[4].def.parts.size() == 3);
  CHECK(bodies[5].def.parts.empty());  // a ball
}

// --- Bad input, named by key path.

TEST_CASE("scene shapes error: shape and shapes together", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "circle", "radius": 1, "position": [0, 0],
                             "shapes": [{"shape": "circle", "radius": 1}]}])"),
               "bodies[0]: give \"shape\" or \"shapes\", not both");
}

TEST_CASE("scene shapes error: a shape key on a shape that does not take it", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "circle", "radius": 1, "vertices": [[0, 0], [1, 0], [0, 1]],
                             "position": [0, 0]}])"),
               "bodies[0].vertices: applies to polygons only; a circle has a \"radius\"");
  RequireError(SceneWith(std::string(R"([{"shape": "polygon", "vertices": )") + kTriangle +
                         R"(, "length": 2, "position": [0, 0]}])"),
               "bodies[0].length: applies to capsules only; a polygon has \"vertices\" and an optional "
               "\"radius\"");
  RequireError(SceneWith(R"([{"shape": "capsule", "length": 1, "radius": 1, "size": [1, 1], "position": [0, 0]}])"),
               "bodies[0].size: applies to boxes only; a capsule has a \"length\" and a \"radius\"");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0]], "radius": 0.1,
                             "position": [0, 0], "static": true}])"),
               "bodies[0].radius: applies to circles, capsules and polygons only; a segment has "
               "\"points\" and an optional \"loop\"");
  RequireError(SceneWith(R"([{"shape": "box", "size": [1, 1], "loop": true, "position": [0, 0]}])"),
               "bodies[0].loop: applies to segments only; a box has a \"size\"");
  RequireError(SceneWith(R"([{"shape": "circle", "radius": 1, "points": [[0, 0], [1, 0]], "position": [0, 0]}])"),
               "bodies[0].points: applies to segments only; a circle has a \"radius\"");
}

TEST_CASE("scene shapes error: offset on a body", "[scene][shapes]") {
  RequireError(SceneWith(std::string(R"([{"shape": "polygon", "vertices": )") + kTriangle +
                         R"(, "offset": [1, 0], "position": [0, 0]}])"),
               "bodies[0].offset: applies to the entries of \"shapes\" only; a body is placed by \"position\"");
}

TEST_CASE("scene shapes error: a shape's keys beside \"shapes\" on the body", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"radius": 1, "position": [0, 0], "shapes": [{"shape": "circle", "radius": 1}]}])"),
               "bodies[0].radius: belongs in an entry of \"shapes\", not on the body");
}

TEST_CASE("scene shapes error: a body with neither shape nor shapes", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"position": [0, 0]}])"),
               "bodies[0]: needs a \"shape\" (\"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\") or "
               "\"shapes\" (a list of them)");
}

TEST_CASE("scene shapes error: polygon vertices missing, too few, too many, not points", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "polygon", "position": [0, 0]}])"),
               "bodies[0]: a polygon needs \"vertices\" [[x, y], ...]");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1, 0]], "position": [0, 0]}])"),
               "bodies[0].vertices: has 2 points; a polygon needs 3 to 64");
  std::string many = "[";
  for (int i = 0; i < 65; ++i) many += (i ? ", [" : "[") + std::to_string(i) + ", " + std::to_string(i * i) + "]";
  many += "]";
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": )" + many + R"(, "position": [0, 0]}])"),
               "bodies[0].vertices: has 65 points; a polygon needs 3 to 64");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": 3, "position": [0, 0]}])"),
               "bodies[0].vertices: must be an array of points [x, y]");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1, 0], [0]], "position": [0, 0]}])"),
               "bodies[0].vertices[2]: must be an array of 2 numbers");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1, 0], [0, "1"]], "position": [0, 0]}])"),
               "bodies[0].vertices[2][1]: must be a number");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [2e9, 0], [0, 1]], "position": [0, 0]}])"),
               "bodies[0].vertices[1][0]: must be between -1e9 and 1e9 (docs/limits.md)");
}

TEST_CASE("scene shapes error: a polygon that crosses itself", "[scene][shapes]") {
  // A bow tie: the edge (2,0)-(0,2) crosses the closing edge (2,2)-(0,0) at (1,1).
  RequireErrorAt(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [2, 0], [0, 2], [2, 2]],
                               "position": [0, 0]}])"),
                 "bodies[0].vertices");
}

TEST_CASE("scene shapes error: a polygon of collinear points only", "[scene][shapes]") {
  RequireErrorAt(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1, 1], [2, 2], [3, 3]],
                               "position": [0, 0], "static": true}])"),
                 "bodies[0].vertices");
}

TEST_CASE("scene shapes error: duplicate points, and a first point repeated at the end", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[1, 1], [1, 1], [1, 1]], "position": [0, 0]}])"),
               "bodies[0].vertices[1]: is the point before it, or within 1e-09 m of it (docs/limits.md)");
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1, 0], [0, 1], [0, 0]], "position": [0, 0]}])"),
               "bodies[0].vertices[3]: is the first point, or within 1e-09 m of it: a polygon closes by "
               "itself (docs/limits.md)");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0], [1, 0]], "position": [0, 0],
                             "static": true}])"),
               "bodies[0].points[2]: is the point before it, or within 1e-09 m of it (docs/limits.md)");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0], [0, 1], [0, 0]], "loop": true,
                             "position": [0, 0], "static": true}])"),
               "bodies[0].points[3]: is the first point, or within 1e-09 m of it: a segment closes by "
               "itself (docs/limits.md)");
}

TEST_CASE("scene shapes: an open polyline may end where it began", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0], [0, 1], [0, 0]],
                                                         "position": [0, 0], "static": true}])"));
  CHECK(scene.bodies[0].def.parts.at(0).points.size() == 4);
}

TEST_CASE("scene shapes error: polygon radius below 0", "[scene][shapes]") {
  RequireError(SceneWith(std::string(R"([{"shape": "polygon", "vertices": )") + kTriangle +
                         R"(, "radius": -0.1, "position": [0, 0]}])"),
               "bodies[0].radius: must be >= 0");
}

TEST_CASE("scene shapes error: capsule length and radius", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "capsule", "radius": 1, "position": [0, 0]}])"),
               "bodies[0]: a capsule needs a \"length\" (between its cap centres)");
  RequireError(SceneWith(R"([{"shape": "capsule", "length": 1, "position": [0, 0]}])"),
               "bodies[0]: a capsule needs a \"radius\"");
  RequireError(SceneWith(R"([{"shape": "capsule", "length": 0, "radius": 1, "position": [0, 0]}])"),
               "bodies[0].length: must be > 0");
  RequireError(SceneWith(R"([{"shape": "capsule", "length": 1, "radius": -1, "position": [0, 0]}])"),
               "bodies[0].radius: must be > 0");
  RequireError(SceneWith(R"([{"shape": "capsule", "length": 1e-10, "radius": 1, "position": [0, 0]}])"),
               "bodies[0].length: must be at least 1e-09 m (docs/limits.md)");
}

TEST_CASE("scene shapes error: segment points missing or too few", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "segment", "position": [0, 0], "static": true}])"),
               "bodies[0]: a segment needs \"points\" [[x, y], ...]");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0]], "position": [0, 0], "static": true}])"),
               "bodies[0].points: has 1 point; a segment needs at least 2");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0]], "loop": 1, "position": [0, 0],
                             "static": true}])"),
               "bodies[0].loop: must be true or false");
}

TEST_CASE("scene shapes error: a segment on a body that is not static", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0]], "position": [0, 0]}])"),
               "bodies[0].shape: a segment belongs to static bodies only (\"static\": true)");
  RequireError(SceneWith(R"([{"shape": "segment", "points": [[0, 0], [1, 0]], "position": [0, 0],
                             "kinematic": true}])"),
               "bodies[0].shape: a segment belongs to static bodies only (\"static\": true)");
  RequireError(SceneWith(R"([{"shape": "circle", "radius": 1, "position": [0, 5]},
                             {"position": [0, 0], "shapes": [{"shape": "box", "size": [1, 1]},
                                                             {"shape": "segment", "points": [[0, 0], [1, 0]]}]}])"),
               "bodies[1].shapes[1].shape: a segment belongs to static bodies only (\"static\": true)");
}

TEST_CASE("scene shapes error: a bad polygon inside shapes is named by its full path", "[scene][shapes]") {
  RequireErrorAt(SceneWith(R"([
    {"shape": "circle", "radius": 1, "position": [0, 5]},
    {"shape": "box", "size": [1, 1], "position": [0, 0]},
    {"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1},
                                    {"shape": "polygon", "vertices": [[0, 0], [2, 0], [0, 2], [2, 2]]}]}])"),
                 "bodies[2].shapes[1].vertices");
  RequireError(SceneWith(R"([
    {"shape": "circle", "radius": 1, "position": [0, 5]},
    {"shape": "box", "size": [1, 1], "position": [0, 0]},
    {"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1},
                                    {"shape": "polygon", "vertices": [[0, 0], [2, 0]]}]}])"),
               "bodies[2].shapes[1].vertices: has 2 points; a polygon needs 3 to 64");
}

TEST_CASE("scene shapes error: shapes that is not a list of shapes", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": {"shape": "circle", "radius": 1}}])"),
               "bodies[0].shapes: must be an array of shapes");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": []}])"), "bodies[0].shapes: must hold at least one shape");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": ["circle"]}])"), "bodies[0].shapes[0]: must be an object");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"radius": 1}]}])"),
               "bodies[0].shapes[0]: needs a \"shape\" (\"circle\", \"box\", \"polygon\", \"capsule\" or \"segment\")");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "disc", "radius": 1}]}])"),
               "bodies[0].shapes[0].shape: unknown value \"disc\" (expected one of \"circle\", \"box\", "
               "\"polygon\", \"capsule\", \"segment\")");
}

TEST_CASE("scene shapes error: body keys inside a part, and unknown part keys", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "position": [1, 0]}]}])"),
               "bodies[0].shapes[0].position: a part is placed by \"offset\" (and \"angle\") in the body's frame");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "mass": 2}]}])"),
               "bodies[0].shapes[0].mass: belongs to the body, not to one of its parts");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "static": true}]}])"),
               "bodies[0].shapes[0].static: belongs to the body, not to one of its parts");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1,
                                                              "shapes": [{"shape": "circle", "radius": 1}]}]}])"),
               "bodies[0].shapes[0].shapes: parts do not nest: list every part in the body's \"shapes\"");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "ofset": [1, 0]}]}])"),
               "bodies[0].shapes[0]: unknown key \"ofset\" (did you mean \"offset\"?)");
}

TEST_CASE("scene shapes error: a part's own values", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "offset": [1]}]}])"),
               "bodies[0].shapes[0].offset: must be an array of 2 numbers");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "angle": "up"}]}])"),
               "bodies[0].shapes[0].angle: must be a number");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "density": 0}]}])"),
               "bodies[0].shapes[0].density: must be > 0");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1, "friction": -1}]}])"),
               "bodies[0].shapes[0].friction: must be >= 0");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "box", "size": [1, 1]},
                                                            {"shape": "circle", "radius": 1, "restitution": -1}]}])"),
               "bodies[0].shapes[1].restitution: must be >= 0");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "circle", "radius": 0}]}])"),
               "bodies[0].shapes[0].radius: must be > 0");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "box", "size": [1, 0]}]}])"),
               "bodies[0].shapes[0].size[1]: must be > 0");
  RequireError(SceneWith(R"([{"position": [0, 0], "shapes": [{"shape": "box"}]}])"),
               "bodies[0].shapes[0]: a box needs a \"size\" [width, height]");
}

TEST_CASE("scene shapes error: a part's density on a static or kinematic body", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"position": [0, 0], "static": true,
                             "shapes": [{"shape": "circle", "radius": 1, "density": 2}]}])"),
               "bodies[0].shapes[0].density: a static body takes no mass, density or velocity");
  RequireError(SceneWith(R"([{"position": [0, 0], "kinematic": true,
                             "shapes": [{"shape": "circle", "radius": 1, "density": 2}]}])"),
               "bodies[0].shapes[0].density: a kinematic body takes no mass or density (nothing pushes it)");
}

TEST_CASE("scene shapes error: a dynamic polygon lighter than the least mass", "[scene][shapes]") {
  RequireError(SceneWith(R"([{"shape": "polygon", "vertices": [[0, 0], [1e-7, 0], [0, 1e-7]], "position": [0, 0]}])"),
               "bodies[0]: its mass, density * area, must be at least 1e-12 kg (docs/limits.md)");
  RequireError(SceneWith(R"([{"position": [0, 0], "density": 1e-9,
                             "shapes": [{"shape": "circle", "radius": 1e-3}, {"shape": "box", "size": [1e-3, 1e-3]}]}])"),
               "bodies[0]: its mass, density * area, must be at least 1e-12 kg (docs/limits.md)");
}

TEST_CASE("scene shapes: a part's own density counts toward the least mass", "[scene][shapes]") {
  // The body's density alone gives 1e-9 * 1e-6 kg; the part's own density makes it 1e-6 kg.
  const game::Scene scene = RequireParsed(SceneWith(R"([{"position": [0, 0], "density": 1e-9,
                              "shapes": [{"shape": "box", "size": [1e-3, 1e-3], "density": 1}]}])"));
  CHECK(scene.bodies[0].def.parts.at(0).density == 1.0);
}

TEST_CASE("scene shapes error: body angle still needs rotation", "[scene][shapes]") {
  RequireError(SceneWith(std::string(R"([{"shape": "polygon", "vertices": )") + kTriangle +
                         R"(, "angle": 1, "position": [0, 0]}])"),
               "bodies[0].angle: needs \"rotation\": true in the scene");
}

// --- The built world and the dump.

TEST_CASE("scene shapes: a polygon body's mass is density × area in the built world", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(std::string(R"([
    {"shape": "polygon", "vertices": )") + kTriangle + R"(, "position": [0, 0], "density": 3},
    {"shape": "capsule", "length": 2, "radius": 0.5, "position": [5, 0]},
    {"position": [10, 0], "density": 2, "shapes": [{"shape": "box", "size": [1, 2]},
                                                   {"shape": "circle", "radius": 1, "offset": [3, 0], "density": 5}]}])"));
  const engine::World world = game::BuildWorld(scene);
  CHECK(world.Info({0}).mass == Approx(3.0 * 1.0).epsilon(1e-12));  // the triangle's area is 1
  CHECK(world.Info({1}).mass == Approx(2.0 * 0.5 * 2.0 + kPi * 0.25).epsilon(1e-12));
  CHECK(world.Info({2}).mass == Approx(2.0 * 2.0 + 5.0 * kPi).epsilon(1e-12));
  REQUIRE(world.Parts({2}).size() == 2);
  CHECK(world.Parts({0}).size() == 1);
}

TEST_CASE("scene shapes: the origin is the scene's position; the centre of mass follows the shapes",
          "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(std::string(R"([
    {"shape": "polygon", "vertices": )") + kTriangle + R"(, "position": [0.1, 0.3], "static": true},
    {"shape": "polygon", "vertices": )" + kTriangle + R"(, "position": [0.1, 0.3]}])"));
  const engine::World world = game::BuildWorld(scene);
  for (const engine::BodyId id : {engine::BodyId{0}, engine::BodyId{1}}) {
    INFO(id.index);
    CHECK(world.Origin(id).x == Approx(0.1).margin(1e-15));
    CHECK(world.Origin(id).y == Approx(0.3).margin(1e-15));
    // The triangle's centroid is (2/3, 1/3) in its frame.
    CHECK(world.LocalCenter(id).x == Approx(2.0 / 3.0).epsilon(1e-12));
    CHECK(world.LocalCenter(id).y == Approx(1.0 / 3.0).epsilon(1e-12));
    CHECK(world.State(id).position.x == Approx(0.1 + 2.0 / 3.0).epsilon(1e-12));
  }
}

namespace {

struct DumpRow {
  std::string step, id;
  double x = 0.0, y = 0.0;
};

// `ballbox sim` of a floor, a static triangle at (0.1, 0.3) and a falling one at (5.1, 0.2) for
// 30 steps, its dump read back.
std::vector<DumpRow> DumpTriangles(const std::string& test_name) {
  const auto dir = testing::FreshTestDir("scene_shapes", test_name);
  const auto scene = dir / "triangle.json";
  std::FILE* f = std::fopen(scene.c_str(), "w");
  REQUIRE(f);
  std::fputs(R"({"bodies": [
    {"id": "floor", "shape": "box", "size": [20, 1], "position": [0, -0.5], "static": true},
    {"id": "ramp", "shape": "polygon", "vertices": [[0, 0], [2, 0], [0, 1]], "position": [0.1, 0.3],
     "static": true},
    {"id": "wedge", "shape": "polygon", "vertices": [[0, 0], [2, 0], [0, 1]], "position": [5.1, 0.2]}]})",
             f);
  std::fclose(f);
  const testing::ProgramRun run = testing::Ballbox("sim '" + scene.string() + "' --steps 30 --dump d.csv", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  std::istringstream csv(testing::ReadFile(dir / "d.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "step,time,id,x,y,vx,vy,angle,omega");
  std::vector<DumpRow> rows;
  while (std::getline(csv, line)) {
    std::vector<std::string> fields;
    std::stringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    REQUIRE(fields.size() == 9);
    rows.push_back({fields[0], fields[2], std::stod(fields[3]), std::stod(fields[4])});
  }
  REQUIRE(rows.size() == 31 * 3);
  return rows;
}

}  // namespace

TEST_CASE("scene shapes: the dump reports a polygon body's origin, not its centre of mass",
          "[scene][shapes][cli]") {
  for (const DumpRow& row : DumpTriangles("dump_origin")) {
    INFO(row.step << " " << row.id);
    if (row.id == "ramp") {  // static: its origin, the same every step (the centroid is 0.67 m away)
      CHECK(row.x == Approx(0.1).margin(1e-15));
      CHECK(row.y == Approx(0.3).margin(1e-15));
    }
    if (row.id == "wedge" && row.step == "0") {
      CHECK(row.x == Approx(5.1).margin(1e-15));
      CHECK(row.y == Approx(0.2).margin(1e-15));
    }
  }
}

// The dump's x, y of a resting body made of parts is its scene position to the bit, as a
// circle's and a box's are: the engine reports the origin as placed while the body has not moved
// (computed back from the centre of mass it would round: 0.1 + 2/3 − 2/3 is 0.09999999999999998).
TEST_CASE("scene shapes: a resting polygon's dumped origin is its position to the bit",
          "[scene][shapes][cli]") {
  for (const DumpRow& row : DumpTriangles("dump_origin_exact")) {
    INFO(row.step << " " << row.id);
    if (row.id == "ramp") {
      CHECK(row.x == 0.1);
      CHECK(row.y == 0.3);
    }
  }
}

TEST_CASE("scene shapes: bad input exits 2 with one line naming the file and the key path",
          "[scene][shapes][cli]") {
  const auto dir = testing::FreshTestDir("scene_shapes", "exit_2");
  const auto scene = dir / "bad.json";
  {
    std::FILE* f = std::fopen(scene.c_str(), "w");
    REQUIRE(f);
    std::fputs(R"({"bodies": [
      {"shape": "circle", "radius": 1, "position": [0, 5]},
      {"shape": "box", "size": [1, 1], "position": [0, 0]},
      {"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1},
                                      {"shape": "polygon", "vertices": [[0, 0], [2, 0]]}]}]})",
               f);
    std::fclose(f);
  }
  const testing::ProgramRun run = testing::Ballbox("sim '" + scene.string() + "' --steps 1 --dump d.csv", dir);
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + scene.string() + ": bodies[2].shapes[1].vertices: has 2 points; a polygon needs 3 to 64\n");
  CHECK_FALSE(std::filesystem::exists(dir / "d.csv"));
}

TEST_CASE("scene shapes: the click acts on balls only, not on a body of one circle part", "[scene][shapes]") {
  const game::Scene scene = RequireParsed(SceneWith(R"([
    {"position": [0, 0], "shapes": [{"shape": "circle", "radius": 1}]},
    {"shape": "capsule", "length": 1, "radius": 1, "position": [5, 0]}])"));
  engine::World world = game::BuildWorld(scene);
  CHECK_FALSE(game::ResolveClick(world, {0.5, 0}, 10.0).has_value());
  CHECK_FALSE(game::ResolveClick(world, {5.0, 0.5}, 10.0).has_value());
}
