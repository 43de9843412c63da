// The embedding API with bodies made of parts: snapshots, queries, debug draw, the origin.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/world.h"
#include "shape_builders.h"
#include "world_builders.h"

using namespace testing;

namespace {

// A pile of every kind of part on segment terrain: a polygon, a concave L, a capsule, a compound
// of a circle and a box with its own material, and lone circles and boxes among them.
engine::World MixedPile() {
  engine::World world{TurningWorld()};
  engine::BodyDef terrain = PartsBody({SegmentsPart({{-6, 3}, {-3, 0}, {3, 0}, {6, 3}})}, {0, 0});
  terrain.is_static = true;
  world.CreateBody(terrain);
  for (int i = 0; i < 6; ++i) {
    const double x = -2.0 + 0.8 * i;
    world.CreateBody(PartsBody({PolygonPart(RegularPolygon(5, 0.3))}, {x, 1.0}, 0.3 * i));
    world.CreateBody(PartsBody({PolygonPart({{0, 0}, {0.6, 0}, {0.6, 0.2}, {0.2, 0.2}, {0.2, 0.6}, {0, 0.6}})},
                               {x, 2.0}, 0.2 * i));
    world.CreateBody(PartsBody({CapsulePart(0.5, 0.15)}, {x, 3.0}, 0.1 * i));
    engine::ShapePart ball;
    ball.type = engine::ShapeType::kCircle;
    ball.radius = 0.2;
    ball.offset = {0.3, 0};
    ball.density = 3.0;
    ball.restitution = 0.6;
    world.CreateBody(PartsBody({ball, BoxPart({0.4, 0.2}, {-0.1, 0})}, {x, 4.0}));
    world.CreateBody(Circle({x + 0.3, 5.0}, 0.15));
    world.CreateBody(Box({x, 6.0}, {0.3, 0.3}));
  }
  return world;
}

}  // namespace

TEST_CASE("a world with parts restored from a snapshot steps on to the same bits", "[shapes][snapshot]") {
  engine::World original = MixedPile();
  for (int i = 0; i < 60; ++i) original.Step();
  const std::vector<std::uint8_t> snapshot = original.TakeSnapshot();
  engine::World copy{TurningWorld()};
  REQUIRE(copy.RestoreSnapshot(snapshot));
  CHECK(copy.StateHash() == original.StateHash());
  for (int i = 0; i < 300; ++i) {
    original.Step();
    copy.Step();
    REQUIRE(copy.StateHash() == original.StateHash());
  }
  // The restored bodies keep their parts as given.
  const engine::BodyId compound = copy.BodyIds()[4];
  REQUIRE(copy.Parts(compound).size() == 2);
  CHECK(copy.Parts(compound)[0].density == 3.0);
  CHECK_FALSE(copy.Parts(compound)[1].density);
  // Half a snapshot is refused.
  engine::World other{TurningWorld()};
  CHECK_FALSE(other.RestoreSnapshot(std::span(snapshot).first(snapshot.size() / 2)));
}

TEST_CASE("the state hash reports the origin of a body made of parts", "[shapes]") {
  // A triangle whose centre of mass is 1 m right of its origin, at rest on nothing (no gravity).
  engine::World a{NoGravity()};
  a.CreateBody(PartsBody({PolygonPart({{0, 0}, {3, 0}, {0, 3}})}, {5, 7}));
  // The hash of a circle at the same origin, with the same (zero) motion, is the same.
  engine::World b{NoGravity()};
  b.CreateBody(Circle({5, 7}, 1));
  CHECK(a.StateHash() == b.StateHash());
  CHECK(a.Origin(a.BodyIds()[0]).x == 5.0);
}

TEST_CASE("ray casts and overlaps see the pieces of polygons, capsules and segments", "[shapes][queries]") {
  engine::World world{NoGravity()};
  // A triangle with its right angle at (2, 0); a capsule along x centred at (10, 0); a segment
  // from (20, −1) to (20, 1).
  const engine::BodyId triangle = world.CreateBody(PartsBody({PolygonPart({{0, -1}, {0, 1}, {-1, 0}})}, {3, 0}));
  const engine::BodyId capsule = world.CreateBody(PartsBody({CapsulePart(2.0, 0.5)}, {10, 0}));
  engine::BodyDef wall = PartsBody({SegmentsPart({{0, -1}, {0, 1}})}, {20, 0});
  wall.is_static = true;
  const engine::BodyId segment = world.CreateBody(wall);

  // Along y = 0 from the left: the triangle's tip at x = 2, the capsule's cap at 8.5, the
  // segment at 20.
  const std::vector<engine::RayHit> hits = world.RayCastAll({0, 0}, {30, 0});
  REQUIRE(hits.size() == 3);
  CHECK(hits[0].body == triangle);
  CHECK(hits[0].point.x == Approx(2.0).epsilon(1e-12));
  CHECK(hits[1].body == capsule);
  CHECK(hits[1].point.x == Approx(8.5).epsilon(1e-12));
  CHECK(hits[1].normal.x == Approx(-1.0).epsilon(1e-12));
  CHECK(hits[2].body == segment);
  CHECK(hits[2].fraction == Approx(20.0 / 30.0).epsilon(1e-12));

  // Across the capsule's flat side at x = 10.7 from above: enters at y = 0.5.
  const auto down = world.RayCast({10.7, 5}, {10.7, -5});
  REQUIRE(down);
  CHECK(down->point.y == Approx(0.5).epsilon(1e-12));

  // A circle of radius 0.5 cast from the left meets the triangle's tip when its centre is at
  // x = 1.5.
  engine::Shape ball;
  ball.radius = 0.5;
  const auto cast = world.ShapeCast(ball, {0, 0}, 0.0, {30, 0});
  REQUIRE(cast);
  CHECK(cast->body == triangle);
  CHECK(cast->fraction * 30.0 == Approx(1.5).epsilon(1e-12));

  // A unit box cast down onto the capsule from above touches its top (y = 0.5) when its centre
  // is at y = 1.0, to the box cast's tolerance.
  engine::Shape box;
  box.type = engine::ShapeType::kBox;
  box.half_extents = {0.5, 0.5};
  const auto box_cast = world.ShapeCast(box, {10, 5}, 0.0, {0, -10});
  REQUIRE(box_cast);
  CHECK(box_cast->body == capsule);
  CHECK(5.0 - 10.0 * box_cast->fraction == Approx(1.0).margin(1e-8));
  CHECK(box_cast->normal.y == Approx(1.0).margin(1e-6));

  // Overlap: a small circle just inside the capsule's cap, and one just outside.
  engine::Shape probe;
  probe.radius = 0.1;
  CHECK(world.OverlapShape(probe, {8.45, 0}, 0.0) == std::vector<engine::BodyId>{capsule});
  CHECK(world.OverlapShape(probe, {8.35, 0}, 0.0).empty());
}

namespace {

struct PieceRecorder : engine::DebugDraw {
  int polygons = 0, capsules = 0, segments = 0, circles = 0;
  std::vector<engine::Vec2> polygon_points;
  void DrawPolygon(engine::BodyId, std::span<const engine::Vec2> vertices, double, engine::BodyKind) override {
    ++polygons;
    polygon_points.assign(vertices.begin(), vertices.end());
  }
  void DrawCapsule(engine::BodyId, engine::Vec2, engine::Vec2, double, engine::BodyKind) override { ++capsules; }
  void DrawSegment(engine::BodyId, engine::Vec2, engine::Vec2, engine::BodyKind) override { ++segments; }
  void DrawCircle(engine::BodyId, engine::Vec2, double, double, engine::BodyKind) override { ++circles; }
};

}  // namespace

TEST_CASE("debug draw describes each piece in the world", "[shapes][debug_draw]") {
  engine::World world{TurningWorld()};
  // A unit square polygon turned 90° about its frame's origin at (10, 0), its corner there.
  world.CreateBody(PartsBody({PolygonPart({{0, 0}, {1, 0}, {1, 1}, {0, 1}})}, {10, 0}, 3.14159265358979323846 / 2));
  world.CreateBody(PartsBody({CapsulePart(1, 0.2)}, {0, 5}));
  engine::BodyDef ground = PartsBody({SegmentsPart({{-5, 0}, {0, 0}, {5, 1}})}, {0, -3});
  ground.is_static = true;
  world.CreateBody(ground);
  PieceRecorder recorder;
  world.Draw(recorder);
  CHECK(recorder.polygons == 1);
  CHECK(recorder.capsules == 1);
  CHECK(recorder.segments == 2);
  CHECK(recorder.circles == 0);
  // Turned a quarter turn counter-clockwise about (10, 0): the corners land at (10, 0),
  // (10, 1), (9, 1) and (9, 0), in some order around the outline.
  REQUIRE(recorder.polygon_points.size() == 4);
  for (const engine::Vec2 corner : {engine::Vec2{10, 0}, engine::Vec2{10, 1}, engine::Vec2{9, 1}, engine::Vec2{9, 0}}) {
    bool found = false;
    for (const engine::Vec2 p : recorder.polygon_points) found = found || engine::Length(p - corner) < 1e-12;
    CHECK(found);
  }
}

TEST_CASE("a spring attaches to a body made of parts at a point of the body's frame", "[shapes]") {
  // A triangle whose centre of mass is 1 m from its frame's origin, held at that origin by a
  // stiff spring of rest length 0 to the same world point: nothing pulls, nothing moves.
  engine::World world{NoGravity()};
  const engine::BodyId triangle = world.CreateBody(PartsBody({PolygonPart({{0, 0}, {3, 0}, {0, 3}})}, {2, 5}));
  engine::SpringDef spring;
  spring.body_a = triangle;
  spring.local_a = {0, 0};
  spring.local_b = {2, 5};
  spring.stiffness = 100.0;
  world.AddSpring(spring);
  StepTimes(world, 60);
  CHECK(world.Origin(triangle).x == 2.0);
  CHECK(world.Origin(triangle).y == 5.0);
  // Pulled from its corner (3, 0) in its frame, the body moves that corner towards the anchor.
  engine::World pulled{NoGravity()};
  const engine::BodyId other = pulled.CreateBody(PartsBody({PolygonPart({{0, 0}, {3, 0}, {0, 3}})}, {0, 0}));
  spring.body_a = other;
  spring.local_a = {3, 0};
  spring.local_b = {3, -1};
  pulled.AddSpring(spring);
  pulled.Step();
  CHECK(pulled.State(other).velocity.y < 0.0);
  CHECK(pulled.State(other).velocity.x == Approx(0.0).margin(1e-12));
}
