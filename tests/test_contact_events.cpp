// Contact events (World::Events): begin with the approach speed, point and normal, hits above
// WorldDef::hit_speed, end when bodies part or one goes, and none for sleep or when turned off.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "engine/world.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::ContactSolver;
using engine::Vec2;
using testing::Box;
using testing::Circle;

// The floor: restitution 0, so a pair bounces with the other body's.
engine::BodyDef Floor() { return testing::WithMaterial(testing::Floor(), 0.0, 0.3); }

// Every event of `steps` steps, each with the step (1-based) that reported it.
struct Recorded {
  std::vector<std::pair<int, engine::ContactBeginEvent>> begins;
  std::vector<std::pair<int, engine::ContactEndEvent>> ends;
  std::vector<std::pair<int, engine::ContactBeginEvent>> hits;
};

Recorded Record(engine::World& world, int steps) {
  Recorded r;
  for (int step = 1; step <= steps; ++step) {
    world.Step();
    const engine::StepEvents& e = world.Events();
    for (const auto& b : e.contact_begin) r.begins.emplace_back(step, b);
    for (const auto& b : e.contact_end) r.ends.emplace_back(step, b);
    for (const auto& b : e.hits) r.hits.emplace_back(step, b);
  }
  return r;
}

}  // namespace

TEST_CASE("contact events: a ball dropped 2 m begins touching once, at the impact speed", "[events][contact]") {
  for (const ContactSolver solver : testing::kBothSolvers) {
    DYNAMIC_SECTION("solver " << static_cast<int>(solver)) {
      engine::WorldDef def;
      def.solver = solver;
      engine::World world(def);
      const BodyId floor = world.CreateBody(Floor());
      const BodyId ball = world.CreateBody(testing::WithMaterial(Circle({0.3, 2.5}, 0.5), 0.0, 0.3));
      const Recorded r = Record(world, 180);
      REQUIRE(r.begins.size() == 1);
      const engine::ContactBeginEvent& begin = r.begins[0].second;
      CHECK(begin.a == floor);  // the lower slot first; the normal points from it to the ball
      CHECK(begin.b == ball);
      CHECK(begin.normal.x == Approx(0.0).margin(1e-12));
      CHECK(begin.normal.y == Approx(1.0).epsilon(1e-12));
      CHECK(begin.point.x == Approx(0.3).margin(1e-9));
      CHECK(begin.point.y == Approx(0.0).margin(0.02));
      // √(2 g h) = √(2 · 9.8 · 2) = 6.26 m/s, at t = √(2 h / g) = 0.639 s: step 38 or 39.
      CHECK(begin.approach_speed == Approx(std::sqrt(2 * 9.8 * 2)).epsilon(0.03));
      CHECK(r.begins[0].first == Approx(0.639 * 60).margin(2));
      REQUIRE(r.hits.size() == 1);  // above the default hit speed of 1 m/s
      CHECK(r.hits[0].first == r.begins[0].first);
      CHECK(r.hits[0].second.approach_speed == begin.approach_speed);
      CHECK(r.ends.empty());  // it stays, then sleeps on the floor
      CHECK_FALSE(world.IsAwake(ball));
    }
  }
}

TEST_CASE("contact events: below the hit speed a contact begins but is no hit", "[events][contact]") {
  engine::WorldDef def;
  def.hit_speed = 10.0;
  engine::World world(def);
  world.CreateBody(Floor());
  world.CreateBody(testing::WithMaterial(Circle({0, 2.5}, 0.5), 0.0, 0.3));
  const Recorded r = Record(world, 120);
  CHECK(r.begins.size() == 1);
  CHECK(r.hits.empty());
}

TEST_CASE("contact events: a bouncing ball's contact ends after each bounce", "[events][contact]") {
  engine::World world(engine::WorldDef{});
  const BodyId floor = world.CreateBody(Floor());
  const BodyId ball = world.CreateBody(testing::WithMaterial(Circle({0, 2.5}, 0.5), 0.8, 0.3));
  const Recorded r = Record(world, 150);
  REQUIRE(r.begins.size() >= 2);
  REQUIRE(r.ends.size() >= 1);
  CHECK(r.ends[0].first > r.begins[0].first);
  CHECK(r.ends[0].first <= r.begins[0].first + 2);  // it leaves at once
  CHECK(r.begins[1].first > r.ends[0].first);       // and lands again
  CHECK(r.ends[0].second.a == floor);
  CHECK(r.ends[0].second.b == ball);
  // The second landing: e · 6.26 m/s up, falling back at the same speed.
  CHECK(r.begins[1].second.approach_speed == Approx(0.8 * std::sqrt(2 * 9.8 * 2)).epsilon(0.05));
}

TEST_CASE("contact events: a box that rests and falls asleep does not end its contact", "[events][contact]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId box = world.CreateBody(Box({0, 0.5}, {1, 1}));
  const Recorded r = Record(world, 180);
  CHECK(r.begins.size() == 1);
  CHECK(r.begins[0].first == 1);  // placed touching
  CHECK(r.hits.empty());          // at rest: no approach
  CHECK(r.ends.empty());
  CHECK_FALSE(world.IsAwake(box));
}

TEST_CASE("contact events: destroying or disabling a touching body ends its contact after the next step",
          "[events][contact]") {
  for (const bool destroy : {true, false}) {
    DYNAMIC_SECTION((destroy ? "destroyed" : "disabled")) {
      engine::World world(engine::WorldDef{});
      const BodyId floor = world.CreateBody(Floor());
      const BodyId box = world.CreateBody(Box({0, 0.5}, {1, 1}));
      const BodyId other = world.CreateBody(Box({3, 0.5}, {1, 1}));
      testing::StepTimes(world, 10);
      if (destroy) {
        world.DestroyBody(box);
      } else {
        world.SetEnabled(box, false);
      }
      world.Step();
      REQUIRE(world.Events().contact_end.size() == 1);
      CHECK(world.Events().contact_end[0].a == floor);
      CHECK(world.Events().contact_end[0].b == box);  // stale, once destroyed
      CHECK(world.Events().contact_begin.empty());
      world.Step();
      CHECK(world.Events().contact_end.empty());  // reported once
      CHECK(world.IsValid(other));
    }
  }
}

TEST_CASE("contact events: off, a drop reports nothing", "[events][contact]") {
  engine::WorldDef def;
  def.contact_events = false;
  engine::World world(def);
  world.CreateBody(Floor());
  const BodyId ball = world.CreateBody(testing::WithMaterial(Circle({0, 2.5}, 0.5), 0.8, 0.3));
  const Recorded r = Record(world, 150);
  CHECK(r.begins.empty());
  CHECK(r.ends.empty());
  CHECK(r.hits.empty());
  world.DestroyBody(ball);
  world.Step();
  CHECK(world.Events().contact_end.empty());
}
