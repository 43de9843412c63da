// Narrow phase against hand-computed manifolds, including the exact edge cases.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

#include "narrow_phase/collide.h"
#include "engine/world.h"
#include "world_builders.h"

using engine::Manifold;
using engine::Vec2;

namespace {

void CheckPoint(const engine::ContactPoint& p, Vec2 point, double depth) {
  CHECK(p.point.x == Approx(point.x).margin(1e-12));
  CHECK(p.point.y == Approx(point.y).margin(1e-12));
  CHECK(p.depth == Approx(depth).margin(1e-12));
}

void CheckNormal(const Manifold& m, Vec2 normal) {
  CHECK(m.normal.x == Approx(normal.x).margin(1e-12));
  CHECK(m.normal.y == Approx(normal.y).margin(1e-12));
}

}  // namespace

TEST_CASE("circles: overlapping along x", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircles({0, 0}, 1.0, {1.5, 0}, 1.0, &m));
  REQUIRE(m.point_count == 1);
  CheckNormal(m, {1, 0});
  // Surfaces at x = 1 (A) and x = 0.5 (B): the point lies midway.
  CheckPoint(m.points[0], {0.75, 0}, 0.5);
}

TEST_CASE("circles: a 3-4-5 offset", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircles({0, 0}, 3.0, {3, 4}, 3.0, &m));
  CheckNormal(m, {0.6, 0.8});
  // Surface of A at 3·(0.6, 0.8) = (1.8, 2.4); of B at (3, 4) − 3·(0.6, 0.8) = (1.2, 1.6).
  CheckPoint(m.points[0], {1.5, 2.0}, 1.0);
}

TEST_CASE("circles: exactly touching is a contact of depth 0, apart is none", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircles({0, 0}, 1.0, {0, 2}, 1.0, &m));
  CheckNormal(m, {0, 1});
  CheckPoint(m.points[0], {0, 1}, 0.0);
  Manifold untouched;
  untouched.point_count = 7;
  CHECK_FALSE(engine::CollideCircles({0, 0}, 1.0, {0, 2.000001}, 1.0, &untouched));
  CHECK(untouched.point_count == 7);
}

TEST_CASE("circles: concentric circles push B up by the sum of the radii", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircles({2, 3}, 1.0, {2, 3}, 0.5, &m));
  CheckNormal(m, {0, 1});
  CHECK(m.points[0].depth == 1.5);
  CHECK(std::isfinite(m.points[0].point.x));
  CHECK(std::isfinite(m.points[0].point.y));
}

TEST_CASE("circle-box: circle above the top face", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircleBox({0, 1.4}, 0.5, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {0, -1});  // from the circle (A) to the box (B)
  // Circle surface at y = 0.9, box face at y = 1.
  CheckPoint(m.points[0], {0, 0.95}, 0.1);
}

TEST_CASE("circle-box: circle at a corner", "[collide]") {
  Manifold m;
  // The closest box point is the corner (1, 1), at (−0.3, −0.4) from the centre: distance 0.5.
  REQUIRE(engine::CollideCircleBox({1.3, 1.4}, 0.6, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {-0.6, -0.8});
  CheckPoint(m.points[0], {0.5 * (1.3 - 0.36 + 1.0), 0.5 * (1.4 - 0.48 + 1.0)}, 0.1);
  CHECK_FALSE(engine::CollideCircleBox({1.3, 1.4}, 0.49, {0, 0}, {1, 1}, &m));
}

TEST_CASE("circle-box: exactly touching a face", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideCircleBox({-1.5, 0.25}, 0.5, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {1, 0});
  CheckPoint(m.points[0], {-1, 0.25}, 0.0);
}

TEST_CASE("circle-box: centre inside the box leaves through the nearest face", "[collide]") {
  Manifold m;
  // Distances to the faces: top 0.2, bottom 1.8, right 0.5, left 1.5.
  REQUIRE(engine::CollideCircleBox({0.5, 0.8}, 0.3, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {0, -1});  // the circle must move up, i.e. the box down relative to it
  CHECK(m.points[0].depth == Approx(0.5).margin(1e-12));

  // The centre of a square is equally near all faces: the tie goes to the top face.
  REQUIRE(engine::CollideCircleBox({0, 0}, 0.25, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {0, -1});
  CHECK(m.points[0].depth == Approx(1.25).margin(1e-12));

  // Nearest the left face.
  REQUIRE(engine::CollideCircleBox({-0.9, 0.1}, 0.2, {0, 0}, {1, 1}, &m));
  CheckNormal(m, {1, 0});
  CHECK(m.points[0].depth == Approx(0.3).margin(1e-12));
}

TEST_CASE("boxes: overlap along y gives two points on the overlap's ends", "[collide]") {
  Manifold m;
  // Overlap x = 2 − 1.5 = 0.5, overlap y = 2 − 1.8 = 0.2: separate along y.
  REQUIRE(engine::CollideBoxes({0, 0}, {1, 1}, {1.5, 1.8}, {1, 1}, &m));
  REQUIRE(m.point_count == 2);
  CheckNormal(m, {0, 1});
  CheckPoint(m.points[0], {0.5, 0.9}, 0.2);
  CheckPoint(m.points[1], {1.0, 0.9}, 0.2);
}

TEST_CASE("boxes: overlap along x, B on the left", "[collide]") {
  Manifold m;
  // B spans x ∈ [−1.7, −0.7], y ∈ [−0.5, 1.5]: overlap x = 0.3, y = 1.5.
  REQUIRE(engine::CollideBoxes({0, 0}, {1, 1}, {-1.2, 0.5}, {0.5, 1}, &m));
  REQUIRE(m.point_count == 2);
  CheckNormal(m, {-1, 0});
  CheckPoint(m.points[0], {-0.85, -0.5}, 0.3);
  CheckPoint(m.points[1], {-0.85, 1.0}, 0.3);
}

TEST_CASE("boxes: exactly touching faces collide with depth 0", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideBoxes({0, 0}, {1, 1}, {0, 2}, {1, 1}, &m));
  CheckNormal(m, {0, 1});
  REQUIRE(m.point_count == 2);
  CheckPoint(m.points[0], {-1, 1}, 0.0);
  CheckPoint(m.points[1], {1, 1}, 0.0);
  CHECK_FALSE(engine::CollideBoxes({0, 0}, {1, 1}, {0, 2.0000001}, {1, 1}, &m));
}

TEST_CASE("boxes: corner to corner is one point, not two", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideBoxes({0, 0}, {1, 1}, {2, 2}, {1, 1}, &m));
  CHECK(m.point_count == 1);
  CheckNormal(m, {0, 1});  // equal overlap on both axes: stood up along y
  CheckPoint(m.points[0], {1, 1}, 0.0);
}

TEST_CASE("boxes: coincident boxes separate upward by their full height", "[collide]") {
  Manifold m;
  REQUIRE(engine::CollideBoxes({1, 1}, {2, 0.5}, {1, 1}, {2, 0.5}, &m));
  CheckNormal(m, {0, 1});
  CHECK(m.points[0].depth == 1.0);
}

TEST_CASE("world: a box below a ball gives a normal from the box (a) to the ball (b)", "[collide]") {
  engine::WorldDef def;
  def.gravity = {0, 0};
  engine::World world(def);
  engine::BodyDef floor;
  floor.shape = {engine::ShapeType::kBox, 0, {1, 0.5}};
  floor.position = {0, -0.5};
  floor.is_static = true;
  world.CreateBody(floor);
  engine::BodyDef ball;
  ball.shape = {engine::ShapeType::kCircle, 0.5, {}};
  ball.position = {0.25, 0.4};
  world.CreateBody(ball);
  world.Step();
  REQUIRE(world.Contacts().size() == 1);
  const engine::Contact& c = world.Contacts()[0];
  CHECK(c.a == 0);
  CHECK(c.b == 1);
  CheckNormal(c.manifold, {0, 1});
  CHECK(c.manifold.points[0].depth == Approx(0.1).margin(1e-12));
}

TEST_CASE("world: a box turned back to angle 0 collides as an unturned box", "[collide]") {
  // A wide box A and a square B turned by 0.3 rad whose lowest corner dips 0.05 m into A's top.
  // A is turned first, then set back to angle 0: its contact with B must be the one a box that
  // never turned makes (the narrow phase takes each box's rotation from the broad phase, which
  // must make A's again once it is unturned, not keep the one from its turned step).
  const double dip = 0.05, turn = 0.3, half = 0.5;
  const engine::Vec2 b_position{0.2, 0.5 + half * (std::cos(turn) + std::sin(turn)) - dip};
  const auto make = [&](double a_angle) {
    engine::WorldDef def;
    def.gravity = {0, 0};
    def.rotation = true;
    auto world = std::make_unique<engine::World>(def);
    engine::BodyDef a = testing::Box({0, 0}, {2, 1});
    a.angle = a_angle;
    world->CreateBody(a);
    engine::BodyDef b = testing::Box(b_position, {2 * half, 2 * half});
    b.angle = turn;
    world->CreateBody(b);
    return world;
  };
  // Puts both bodies back where make() placed them, at rest, A unturned.
  const auto reset = [&](engine::World& world) {
    const engine::BodyId a = world.IdAt(0), b = world.IdAt(1);
    world.SetPosition(a, {0, 0});
    world.SetAngle(a, 0.0);
    world.SetPosition(b, b_position);
    world.SetAngle(b, turn);
    for (const engine::BodyId id : {a, b}) {
      world.SetLinearVelocity(id, {0, 0});
      world.SetAngularVelocity(id, 0.0);
    }
  };
  const auto turned_first = make(0.4);
  turned_first->Step();
  reset(*turned_first);
  turned_first->Step();
  const auto never_turned = make(0.0);
  never_turned->Step();
  REQUIRE(turned_first->Contacts().size() == 1);
  REQUIRE(never_turned->Contacts().size() == 1);
  const Manifold& m = turned_first->Contacts()[0].manifold;
  const Manifold& expected = never_turned->Contacts()[0].manifold;
  // B's corner on A's top face: the normal is A's up, the depth the dip.
  CheckNormal(m, {0, 1});
  REQUIRE(m.point_count >= 1);
  CHECK(m.points[0].depth == Approx(dip).margin(1e-12));
  REQUIRE(m.point_count == expected.point_count);
  CHECK(m.normal.x == expected.normal.x);
  CHECK(m.normal.y == expected.normal.y);
  for (int i = 0; i < m.point_count; ++i) {
    CHECK(m.points[i].point.x == expected.points[i].point.x);
    CHECK(m.points[i].point.y == expected.points[i].point.y);
    CHECK(m.points[i].depth == expected.points[i].depth);
  }
}
