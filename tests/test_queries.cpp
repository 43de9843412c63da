// The world's queries against answers worked out by hand: ray casts (closest and all), bounding
// box and shape overlaps, shape casts of circles and boxes; a turned box cast against a
// brute-force search; disabled and destroyed bodies never reported; filters.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "engine/world.h"
#include "world_builders.h"

using engine::BodyId;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Static;

namespace {

constexpr double kExact = 1e-12;

engine::Shape CircleShape(double radius) { return {engine::ShapeType::kCircle, radius, {}}; }
engine::Shape BoxShape(Vec2 half_extents) { return {engine::ShapeType::kBox, 0.0, half_extents}; }

std::vector<BodyId> IdsOf(const std::vector<engine::RayHit>& hits) {
  std::vector<BodyId> ids;
  for (const engine::RayHit& hit : hits) ids.push_back(hit.body);
  return ids;
}

void CheckHit(const engine::RayHit& hit, BodyId body, double fraction, Vec2 point, Vec2 normal) {
  CHECK(hit.body == body);
  CHECK(hit.fraction == Approx(fraction).margin(kExact));
  CHECK(hit.point.x == Approx(point.x).margin(kExact));
  CHECK(hit.point.y == Approx(point.y).margin(kExact));
  CHECK(hit.normal.x == Approx(normal.x).margin(kExact));
  CHECK(hit.normal.y == Approx(normal.y).margin(kExact));
}

// A static floor whose top is y = 0: 10 m wide, 1 m thick.
engine::BodyDef Floor() { return Static(Box({0, -0.5}, {10, 1})); }

}  // namespace

TEST_CASE("ray cast all: three circles in a row, by fraction, entry points and normals by hand",
          "[queries][ray]") {
  engine::World world(testing::NoGravity());
  // Made out of order, so that fraction order is not slot order. The ray runs along y = 0.3; a
  // circle of radius r whose centre is dy off it is entered dx = √(r² − dy²) before its centre:
  // 3-4-5 triangles, so every number below is exact in decimal.
  const BodyId far = world.CreateBody(Circle({9, 0.7}, 0.5));    // dy −0.4, dx 0.3: x = 8.7
  const BodyId near = world.CreateBody(Circle({2, 0}, 0.5));     // dy 0.3, dx 0.4: x = 1.6
  const BodyId middle = world.CreateBody(Circle({5, -0.3}, 1));  // dy 0.6, dx 0.8: x = 4.2
  world.CreateBody(Circle({5, 3}, 1));                           // well off the ray

  const std::vector<engine::RayHit> hits = world.RayCastAll({0, 0.3}, {10, 0.3});
  REQUIRE(hits.size() == 3);
  // The normal is (entry − centre) / r.
  CheckHit(hits[0], near, 0.16, {1.6, 0.3}, {-0.8, 0.6});
  CheckHit(hits[1], middle, 0.42, {4.2, 0.3}, {-0.8, 0.6});
  CheckHit(hits[2], far, 0.87, {8.7, 0.3}, {-0.6, -0.8});

  const std::optional<engine::RayHit> first = world.RayCast({0, 0.3}, {10, 0.3});
  REQUIRE(first);
  CheckHit(*first, near, 0.16, {1.6, 0.3}, {-0.8, 0.6});

  // Backwards, the far circle is entered first, at x = 9.3, 0.07 of the way.
  const std::vector<engine::RayHit> back = world.RayCastAll({10, 0.3}, {0, 0.3});
  CHECK(IdsOf(back) == std::vector<BodyId>{far, middle, near});
  REQUIRE(back.size() == 3);
  CheckHit(back[0], far, 0.07, {9.3, 0.3}, {0.6, -0.8});

  // A ray that stops inside the middle circle enters only the first two.
  CHECK(IdsOf(world.RayCastAll({0, 0.3}, {5, 0.3})) == std::vector<BodyId>{near, middle});
}

TEST_CASE("ray casts: a miss reports nothing, a body the ray starts inside is not entered",
          "[queries][ray]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(Circle({2, 0}, 0.5));
  world.CreateBody(Static(Box({6, 0}, {2, 2})));
  CHECK(world.RayCastAll({0, 2}, {10, 2}).empty());  // passes 1 m above the box's top at y = 1
  CHECK_FALSE(world.RayCast({0, 2}, {10, 2}));
  CHECK(world.RayCastAll({0, 0}, {1.4, 0}).empty());  // stops 0.1 m short of the circle
  // From inside the circle: only the box is entered, at its left face x = 5.
  const std::vector<engine::RayHit> hits = world.RayCastAll({2, 0}, {10, 0});
  REQUIRE(hits.size() == 1);
  CheckHit(hits[0], BodyId{1}, 3.0 / 8.0, {5, 0}, {-1, 0});
}

TEST_CASE("ray casts: equal fractions keep slot order", "[queries][ray]") {
  engine::World world(testing::NoGravity());
  for (int i = 0; i < 3; ++i) world.CreateBody(Circle({5, 0}, 1));  // slots 0-2 in one place
  const BodyId nearest = world.CreateBody(Circle({2, 0}, 0.5));
  CHECK(IdsOf(world.RayCastAll({0, 0}, {10, 0})) == std::vector<BodyId>{nearest, {0}, {1}, {2}});
  // Straight down through the three alone: a tie, which the lowest slot wins.
  CHECK(world.RayCast({5, 3}, {5, -3})->body == BodyId{0});
  world.DestroyBody(nearest);
  CHECK(world.RayCast({0, 0}, {10, 0})->body == BodyId{0});
}

TEST_CASE("overlap AABB: bounding boxes, touching counts, turned boxes by their bounds",
          "[queries][overlap]") {
  engine::World world(testing::NoGravity());
  const BodyId box = world.CreateBody(Box({0, 0}, {2, 2}));        // bounds [−1, 1]²
  const BodyId circle = world.CreateBody(Circle({5, 0}, 1));       // bounds [4, 6] × [−1, 1]
  engine::BodyDef diamond_def = Box({0, 10}, {2, 2});
  diamond_def.angle = 3.14159265358979323846 / 4;                   // bounds ±√2 about (0, 10)
  const BodyId diamond = world.CreateBody(diamond_def);

  using Ids = std::vector<BodyId>;
  CHECK(world.OverlapAABB({{1, 0}, {4, 0.5}}) == Ids{box, circle});  // touches both at x = 1, 4
  CHECK(world.OverlapAABB({{std::nextafter(1.0, 2.0), 0}, {std::nextafter(4.0, 0.0), 0.5}}).empty());
  CHECK(world.OverlapAABB({{-100, -100}, {100, 100}}) == Ids{box, circle, diamond});
  // Inside the diamond's bounds, off its shape (|x| + |y − 10| = 2.4 > √2): the box test sees it,
  // the shape test does not.
  CHECK(world.OverlapAABB({{1.2, 11.2}, {1.3, 11.3}}) == Ids{diamond});
  CHECK(world.OverlapShape(BoxShape({0.05, 0.05}), {1.25, 11.25}, 0).empty());
  // Past the bounds' corner (1.4142..., 11.4142...).
  CHECK(world.OverlapAABB({{1.42, 11.42}, {2, 12}}).empty());
}

TEST_CASE("overlap shape: circles and boxes, touching counts, a hair apart does not",
          "[queries][overlap]") {
  engine::World world(testing::NoGravity());
  const BodyId circle = world.CreateBody(Circle({0, 0}, 1.5));
  const BodyId box = world.CreateBody(Static(Box({10, 0}, {2, 2})));  // x ∈ [9, 11], y ∈ [−1, 1]
  using Ids = std::vector<BodyId>;
  // A circle of radius 0.5 two metres from the circle's centre touches it.
  CHECK(world.OverlapShape(CircleShape(0.5), {2, 0}, 0) == Ids{circle});
  CHECK(world.OverlapShape(CircleShape(0.5), {std::nextafter(2.0, 3.0), 0}, 0).empty());
  // A box whose left face lies on the box's right face at x = 11.
  CHECK(world.OverlapShape(BoxShape({0.5, 0.5}), {11.5, 0.7}, 0) == Ids{box});
  CHECK(world.OverlapShape(BoxShape({0.5, 0.5}), {11.5 + 1e-9, 0.7}, 0).empty());
  // A square of half size 0.5 turned 45° reaches √½ = 0.7071 m from its centre along x: into the
  // box from 11.70, clear of it from 11.71.
  const double quarter = 3.14159265358979323846 / 4;
  CHECK(world.OverlapShape(BoxShape({0.5, 0.5}), {11.70, 0}, quarter) == Ids{box});
  CHECK(world.OverlapShape(BoxShape({0.5, 0.5}), {11.71, 0}, quarter).empty());
  // A big box over both, in slot order; the circle between them touches neither.
  CHECK(world.OverlapShape(BoxShape({20, 20}), {5, 0}, 0) == Ids{circle, box});
  CHECK(world.OverlapShape(CircleShape(1), {5, 0}, 0).empty());
}

TEST_CASE("queries never report disabled or destroyed bodies; a reused slot reports its new id",
          "[queries][overlap][ray][cast]") {
  engine::World world(testing::NoGravity());
  const BodyId a = world.CreateBody(Circle({2, 0}, 0.5));
  const BodyId b = world.CreateBody(Circle({4, 0}, 0.5));
  const BodyId c = world.CreateBody(Static(Box({6, 0}, {1, 1})));
  const engine::AABB everywhere{{-100, -100}, {100, 100}};
  auto all_queries_see = [&](std::vector<BodyId> expected) {
    CHECK(world.OverlapAABB(everywhere) == expected);
    CHECK(world.OverlapShape(BoxShape({50, 50}), {0, 0}, 0) == expected);
    CHECK(IdsOf(world.RayCastAll({0, 0}, {10, 0})) == expected);
    const std::optional<engine::RayHit> first = world.RayCast({0, 0}, {10, 0});
    const std::optional<engine::RayHit> cast = world.ShapeCast(CircleShape(0.1), {0, 0}, 0, {10, 0});
    REQUIRE(first);
    REQUIRE(cast);
    CHECK(first->body == expected.front());
    CHECK(cast->body == expected.front());
  };
  all_queries_see({a, b, c});
  world.SetEnabled(a, false);
  all_queries_see({b, c});
  world.DestroyBody(b);
  all_queries_see({c});
  // The new body takes b's slot with the next generation: reported under its own id only.
  const BodyId d = world.CreateBody(Circle({4, 0}, 0.5));
  REQUIRE(d.index == b.index);
  REQUIRE(d != b);
  all_queries_see({d, c});
  world.SetEnabled(a, true);
  all_queries_see({a, d, c});
}

TEST_CASE("queries with a filter see what a body of that filter would collide with",
          "[queries][filter]") {
  engine::World world(testing::NoGravity());
  engine::BodyDef debris = Circle({2, 0}, 0.5);
  debris.filter.category_bits = 0b10;
  const BodyId ignored = world.CreateBody(debris);
  const BodyId wall = world.CreateBody(Static(Box({6, 0}, {1, 4})));
  // A query that hits category 1 only.
  const engine::Filter solid_only{1, 0b01, 0};
  CHECK(IdsOf(world.RayCastAll({0, 0}, {10, 0})) == std::vector<BodyId>{ignored, wall});
  CHECK(IdsOf(world.RayCastAll({0, 0}, {10, 0}, solid_only)) == std::vector<BodyId>{wall});
  CHECK(world.RayCast({0, 0}, {10, 0}, solid_only)->body == wall);
  CHECK(world.OverlapAABB({{0, -1}, {10, 1}}, solid_only) == std::vector<BodyId>{wall});
  CHECK(world.OverlapShape(BoxShape({5, 1}), {5, 0}, 0, solid_only) == std::vector<BodyId>{wall});
  CHECK(world.ShapeCast(CircleShape(0.2), {0, 0}, 0, {10, 0}, solid_only)->body == wall);
  // A negative group never meets its own members, whatever the bits say.
  engine::Filter same_group;
  same_group.group_index = -7;
  world.SetFilter(wall, same_group);
  CHECK(IdsOf(world.RayCastAll({0, 0}, {10, 0}, same_group)) == std::vector<BodyId>{ignored});
}

TEST_CASE("circle cast: onto a box floor, onto a circle, onto a box's corner, by hand",
          "[queries][cast]") {
  engine::World world(testing::NoGravity());
  const BodyId floor = world.CreateBody(Floor());
  // Falling 10 m from a centre 3 m up, a ball of radius 0.5 touches the floor after the 2.5 m
  // gap between its bottom and the floor: fraction 2.5 / 10.
  std::optional<engine::RayHit> hit = world.ShapeCast(CircleShape(0.5), {0, 3}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, floor, 0.25, {0, 0}, {0, 1});

  const BodyId ball = world.CreateBody(Circle({0, 5}, 1));
  // Onto the ball (centre (0, 5), radius 1) 0.9 m off its axis: the centres are 1.5 apart at
  // the touch, so 1.2 apart vertically: the cast centre stops at y = 6.2 after 3.8 m of 10.
  hit = world.ShapeCast(CircleShape(0.5), {0.9, 10}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, ball, 0.38, {0.6, 5.8}, {0.6, 0.8});

  const BodyId block = world.CreateBody(Static(Box({-5, 5}, {2, 2})));  // corner (−4, 6)
  // 0.3 m past the block's right face, a radius-0.5 ball meets the corner with its centre 0.4
  // above it, y = 6.4, after 3.6 m of 10.
  hit = world.ShapeCast(CircleShape(0.5), {-3.7, 10}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, block, 0.36, {-4, 6}, {0.6, 0.8});
  // Sideways into the block's left face at x = −6: from x = −10, the ball's side reaches it
  // after 3.5 m of 7.
  hit = world.ShapeCast(CircleShape(0.5), {-10, 5.5}, 0, {7, 0});
  REQUIRE(hit);
  CheckHit(*hit, block, 0.5, {-6, 5.5}, {-1, 0});
}

TEST_CASE("circle cast against a turned box: the rounded corner", "[queries][cast]") {
  engine::World world(testing::NoGravity());
  engine::BodyDef diamond = Static(Box({0, 0}, {2, 2}));
  diamond.angle = 3.14159265358979323846 / 4;  // top corner at (0, √2)
  const BodyId body = world.CreateBody(diamond);
  // Straight down onto the top corner: the ball's bottom meets it, centre at √2 + 0.5.
  const std::optional<engine::RayHit> hit = world.ShapeCast(CircleShape(0.5), {0, 10}, 0, {0, -10});
  REQUIRE(hit);
  CHECK(hit->body == body);
  CHECK(hit->fraction == Approx((10 - std::sqrt(2.0) - 0.5) / 10).margin(1e-12));
  CHECK(hit->point.y == Approx(std::sqrt(2.0)).margin(1e-12));
  CHECK(hit->normal.y == Approx(1).margin(1e-12));
}

TEST_CASE("box cast: onto a floor face to face, onto a circle face and corner, by hand",
          "[queries][cast]") {
  engine::World world(testing::NoGravity());
  const BodyId floor = world.CreateBody(Floor());
  // A unit box 3 m up: its bottom at 2.5 falls the 2.5 m gap; face on face, the touch point is
  // the middle of the shared edge.
  std::optional<engine::RayHit> hit = world.ShapeCast(BoxShape({0.5, 0.5}), {0, 3}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, floor, 0.25, {0, 0}, {0, 1});
  // Half off the floor's right end at x = 5: the shared edge is x ∈ [4.8, 5].
  hit = world.ShapeCast(BoxShape({0.5, 0.5}), {5.3, 3}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, floor, 0.25, {4.9, 0}, {0, 1});

  const BodyId ball = world.CreateBody(Circle({0, 5}, 1));
  // Onto the ball's top: the box's bottom face meets it at (0, 6), centre at 6.5, after 3.5 m.
  hit = world.ShapeCast(BoxShape({0.5, 0.5}), {0, 10}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, ball, 0.35, {0, 6}, {0, 1});
  // The box's lower left corner 0.6 m right of the ball's axis meets it at (0.6, 5.8): the box's
  // centre then at (1.1, 6.3), after 3.7 m.
  hit = world.ShapeCast(BoxShape({0.5, 0.5}), {1.1, 10}, 0, {0, -10});
  REQUIRE(hit);
  CheckHit(*hit, ball, 0.37, {0.6, 5.8}, {0.6, 0.8});
}

TEST_CASE("shape cast: the first body met, and nothing within the translation",
          "[queries][cast]") {
  engine::World world(testing::NoGravity());
  const BodyId floor = world.CreateBody(Floor());
  const BodyId crate = world.CreateBody(Static(Box({0, 1}, {2, 2})));  // top at y = 2
  // Slot order would give the floor; the crate's top is met first, after 1 m of the 2.5 m gap.
  std::optional<engine::RayHit> hit = world.ShapeCast(CircleShape(0.5), {0, 3.5}, 0, {0, -4});
  REQUIRE(hit);
  CheckHit(*hit, crate, 0.25, {0, 2}, {0, 1});
  hit = world.ShapeCast(CircleShape(0.5), {4, 3.5}, 0, {0, -4});  // beside the crate
  REQUIRE(hit);
  CheckHit(*hit, floor, 0.75, {4, 0}, {0, 1});
  CHECK_FALSE(world.ShapeCast(CircleShape(0.5), {4, 3.5}, 0, {0, -2.9}));  // stops 0.1 short
  // A turned box passing over the crate, its lowest corner about 0.25 m clear of it.
  CHECK_FALSE(world.ShapeCast(BoxShape({1, 1}), {-8, 3.5}, 0.3, {16, 0}));
}

TEST_CASE("shape cast starting in overlap: fraction 0; only touching: 0 going in, none going out",
          "[queries][cast]") {
  engine::World world(testing::NoGravity());
  const BodyId floor = world.CreateBody(Floor());
  // Sunk 0.1 m into the floor, whichever way it moves: fraction 0, no normal, at the start.
  for (const Vec2 translation : {Vec2{0, -1}, Vec2{0, 1}, Vec2{3, 0}, Vec2{0, 0}}) {
    for (const engine::Shape& shape : {CircleShape(0.5), BoxShape({0.5, 0.5})}) {
      const std::optional<engine::RayHit> hit = world.ShapeCast(shape, {1, 0.4}, 0, translation);
      REQUIRE(hit);
      CheckHit(*hit, floor, 0, {1, 0.4}, {0, 0});
    }
  }
  // Resting exactly on the floor: going down meets it at once, with the floor's normal; going
  // up or along does not meet it at all.
  for (const engine::Shape& shape : {CircleShape(0.5), BoxShape({0.5, 0.5})}) {
    const std::optional<engine::RayHit> down = world.ShapeCast(shape, {1, 0.5}, 0, {0.5, -1});
    REQUIRE(down);
    CheckHit(*down, floor, 0, {1, 0}, {0, 1});
    CHECK_FALSE(world.ShapeCast(shape, {1, 0.5}, 0, {0, 1}));
    CHECK_FALSE(world.ShapeCast(shape, {1, 0.5}, 0, {3, 0}));
  }
}

namespace {

// The fraction at which `shape` moving by `translation` first overlaps `body`, found without the
// sweep: the first of `samples` evenly spaced positions where OverlapShape (the narrow phase's
// collide functions) reports the body, then bisection between it and the one before down to
// rounding. Nothing if no sample overlaps.
std::optional<double> BruteForceTouch(const engine::World& world, BodyId body, const engine::Shape& shape,
                                      Vec2 position, double angle, Vec2 translation, int samples) {
  auto overlaps = [&](double t) {
    const std::vector<BodyId> ids = world.OverlapShape(shape, position + t * translation, angle);
    return std::find(ids.begin(), ids.end(), body) != ids.end();
  };
  for (int k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples;
    if (!overlaps(t)) continue;
    if (k == 0) return 0.0;
    double outside = static_cast<double>(k - 1) / samples, inside = t;
    for (int i = 0; i < 60; ++i) {
      const double middle = 0.5 * (outside + inside);
      (overlaps(middle) ? inside : outside) = middle;
    }
    // The sampling alone puts the touch within one step before `t`.
    CHECK(inside <= t);
    CHECK(inside >= t - 1.0 / samples);
    return inside;
  }
  return std::nullopt;
}

// How far `point` is from the outline of the box at `center` turned by `rotation`, m (inside:
// the distance to the nearest face; outside: to the box, roughly, as only near points matter).
double DistanceToOutline(Vec2 point, Vec2 center, Vec2 half_extents, engine::Rot rotation) {
  const Vec2 local = engine::InvRotate(rotation, point - center);
  return std::abs(std::max(std::abs(local.x) - half_extents.x, std::abs(local.y) - half_extents.y));
}

}  // namespace

namespace {

// A box cast at a static turned box, both checked against the brute-force search.
struct TurnedCase {
  double target_angle;
  double moving_angle;
  Vec2 start;
  Vec2 translation;
};

// Twelve casts aimed past the target's centre (so each meets it), with turns that vary: faces
// onto corners, corners onto faces, and every fourth with both boxes turned alike (face on
// face). Then two along the target's long axis with parallel faces 0.01 m apart, across
// (meeting its end face) and clear (missing it).
std::vector<TurnedCase> TurnedCases() {
  std::vector<TurnedCase> cases;
  for (int i = 0; i < 12; ++i) {
    const double target_angle = 0.37 * i - 1.1;
    const double moving_angle = i % 4 == 0 ? target_angle : 0.53 * i + 0.2;
    const Vec2 start{-3.0 + 0.2 * i, 4.0 - 0.15 * i};
    const Vec2 aim{0.25 * (i % 5) - 0.5, 0.1 * (i % 3) - 0.1};
    cases.push_back({target_angle, moving_angle, start, 1.6 * (aim - start)});
  }
  const engine::Rot turn = engine::MakeRot(0.8);
  const Vec2 along = engine::Rotate(turn, {1, 0}), across = engine::Rotate(turn, {0, 1});
  for (const double gap : {-0.01, 0.01}) {
    cases.push_back({0.8, 0.8, -4.0 * along + (0.4 + 0.2 + gap) * across, 8.0 * along});
  }
  return cases;
}

}  // namespace

TEST_CASE("box cast onto turned boxes agrees with a brute-force search to within 1e-9 m",
          "[queries][cast]") {
  // The sweep is exact up to rounding (the separating axes of both boxes); the search samples
  // 20000 positions along the way (under 0.4 mm apart here) and bisects the first step that
  // overlaps, so a disagreement beyond rounding would show at 1e-9 m, and one at the linear
  // slop (5 mm) by the sampling alone.
  const Vec2 target_half{1.0, 0.4};
  const Vec2 moving_half{0.35, 0.2};
  const engine::Shape moving = BoxShape(moving_half);
  const std::vector<TurnedCase> cases = TurnedCases();
  std::vector<std::optional<double>> fractions;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const TurnedCase& c = cases[i];
    engine::World world(testing::NoGravity());
    engine::BodyDef def = Static(Box({0, 0}, 2 * target_half));
    def.angle = c.target_angle;
    const BodyId target = world.CreateBody(def);
    INFO("case " << i);
    const std::optional<engine::RayHit> hit = world.ShapeCast(moving, c.start, c.moving_angle, c.translation);
    const std::optional<double> expected =
        BruteForceTouch(world, target, moving, c.start, c.moving_angle, c.translation, 20000);
    REQUIRE(hit.has_value() == expected.has_value());
    fractions.push_back(expected);
    if (!hit) continue;
    CHECK(hit->body == target);
    CHECK(std::abs(hit->fraction - *expected) * engine::Length(c.translation) < 1e-9);
    // The touch point lies on both outlines; the normal is a unit vector from the target
    // towards the moving box, against the motion.
    const Vec2 center_then = c.start + hit->fraction * c.translation;
    CHECK(DistanceToOutline(hit->point, {0, 0}, target_half, engine::MakeRot(c.target_angle)) < 1e-9);
    CHECK(DistanceToOutline(hit->point, center_then, moving_half, engine::MakeRot(c.moving_angle)) < 1e-9);
    CHECK(engine::Length(hit->normal) == Approx(1).margin(1e-12));
    CHECK(engine::Dot(hit->normal, center_then) > 0);
    CHECK(engine::Dot(hit->normal, c.translation) < 0);
  }
  // Every aimed cast meets the target; along the long axis, the crossing one meets the end face
  // when the leading face has come 4 − 1 − 0.35 m of 8, and the clear one misses.
  for (std::size_t i = 0; i < 12; ++i) CHECK(fractions[i].has_value());
  REQUIRE(fractions[12]);
  CHECK(*fractions[12] == Approx(2.65 / 8).margin(1e-12));
  CHECK_FALSE(fractions[13]);
}
