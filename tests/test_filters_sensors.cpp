// Collision filters (categories, masks, groups) and sensors (overlap events, no collision).
#include <catch2/catch.hpp>

#include <vector>

#include "engine/world.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::Filter;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Floor;
using testing::Sensor;
using testing::Static;

constexpr double kG = 9.8;

Filter Make(std::uint64_t category, std::uint64_t mask, std::int32_t group = 0) {
  Filter f;
  f.category_bits = category;
  f.mask_bits = mask;
  f.group_index = group;
  return f;
}

engine::BodyDef WithFilter(engine::BodyDef def, const Filter& filter) {
  def.filter = filter;
  return def;
}

struct SensorStep {
  int step;
  engine::SensorEvent event;
};

struct SensorLog {
  std::vector<SensorStep> begins;
  std::vector<SensorStep> ends;
};

SensorLog RecordSensors(engine::World& world, int steps) {
  SensorLog log;
  for (int step = 1; step <= steps; ++step) {
    world.Step();
    for (const auto& e : world.Events().sensor_begin) log.begins.push_back({step, e});
    for (const auto& e : world.Events().sensor_end) log.ends.push_back({step, e});
  }
  return log;
}

}  // namespace

TEST_CASE("filters: ShouldCollide by hand, groups overriding masks", "[filters]") {
  const Filter everything;  // category 1, every mask bit, no group
  CHECK(engine::ShouldCollide(everything, everything));
  // Each one's category must be in the other's mask, both ways.
  CHECK(engine::ShouldCollide(Make(0b01, 0b10), Make(0b10, 0b01)));
  CHECK_FALSE(engine::ShouldCollide(Make(0b01, 0b01), Make(0b10, 0b10)));
  CHECK_FALSE(engine::ShouldCollide(Make(0b01, ~0ull), Make(0b10, 0b10)));  // one side refuses
  CHECK_FALSE(engine::ShouldCollide(Make(0b10, 0b10), Make(0b01, ~0ull)));
  CHECK_FALSE(engine::ShouldCollide(Make(0, ~0ull), everything));  // no category at all
  // The same positive group always collides, the same negative group never, whatever the masks.
  CHECK(engine::ShouldCollide(Make(0b01, 0b01, 3), Make(0b10, 0b10, 3)));
  CHECK_FALSE(engine::ShouldCollide(Make(0b01, ~0ull, -3), Make(0b01, ~0ull, -3)));
  // Different groups (or group 0) leave it to the masks.
  CHECK_FALSE(engine::ShouldCollide(Make(0b01, 0b01, 3), Make(0b10, 0b10, 4)));
  CHECK(engine::ShouldCollide(Make(0b01, ~0ull, -3), Make(0b01, ~0ull, -4)));
  CHECK(engine::ShouldCollide(Make(0b01, ~0ull, -3), Make(0b01, ~0ull, 0)));
  CHECK_FALSE(engine::ShouldCollide(Make(0b01, 0b01, 0), Make(0b10, 0b10, 0)));
}

TEST_CASE("filters: two boxes whose filters refuse each other pass through, exactly as alone", "[filters]") {
  struct Case {
    const char* name;
    Filter a, b;
    bool collide;
  };
  const Case cases[] = {{"masks refuse", Make(0b01, 0b01), Make(0b10, 0b10), false},
                        {"same negative group", Make(1, ~0ull, -1), Make(1, ~0ull, -1), false},
                        {"same positive group over masks", Make(0b01, 0b01, 2), Make(0b10, 0b10, 2), true},
                        {"defaults", Filter{}, Filter{}, true}};
  for (const Case& c : cases) {
    DYNAMIC_SECTION(c.name) {
      engine::World world(testing::NoGravity());
      const BodyId a = world.CreateBody(WithFilter(Box({-2, 0}, {1, 1}, {1, 0}), c.a));
      const BodyId b = world.CreateBody(WithFilter(Box({2, 0}, {1, 1}, {-1, 0}), c.b));
      CHECK(world.GetFilter(a) == c.a);
      testing::StepTimes(world, 240);  // 4 s: alone, each would end where the other began
      if (c.collide) {
        CHECK(world.State(a).position.x < -0.49);
        CHECK(world.State(b).position.x > 0.49);
      } else {
        CHECK(world.State(a).position.x == Approx(2.0).epsilon(1e-12));
        CHECK(world.State(b).position.x == Approx(-2.0).epsilon(1e-12));
        CHECK(world.State(a).velocity == Vec2{1, 0});
      }
    }
  }
}

TEST_CASE("filters: SetFilter between steps lets a resting ball fall through the floor", "[filters]") {
  for (const bool on_floor : {false, true}) {
    DYNAMIC_SECTION("filter set on the " << (on_floor ? "floor" : "ball")) {
      engine::World world(engine::WorldDef{});
      const BodyId floor = world.CreateBody(Floor());  // category 1
      const BodyId ball = world.CreateBody(Circle({0, 0.5}, 0.5));
      testing::StepTimes(world, 120);
      REQUIRE_FALSE(world.IsAwake(ball));  // asleep: the filter must wake it
      if (on_floor) {
        world.SetFilter(floor, Make(1, ~0ull ^ 1ull));  // the floor refuses category 1
      } else {
        world.SetFilter(ball, Make(2, ~0ull ^ 1ull));  // the ball refuses the floor's category
      }
      CHECK(world.IsAwake(ball));
      testing::StepTimes(world, 60);
      CHECK(world.State(ball).position.y < -2.0);
      // Put back, the filter holds the next ball.
      world.SetFilter(floor, Filter{});
      const BodyId next = world.CreateBody(Circle({3, 2}, 0.5));
      testing::StepTimes(world, 120);
      CHECK(world.State(next).position.y == Approx(0.5).margin(0.01));
    }
  }
}

TEST_CASE("sensors: a ball falling through a sensor box begins and ends at the free-fall steps",
          "[sensors]") {
  engine::World world(engine::WorldDef{});
  const BodyId sensor = world.CreateBody(Sensor(Static(Box({0, 2.5}, {2, 1}))));  // y from 2 to 3
  const double r = 0.25, y0 = 6.0;
  const BodyId ball = world.CreateBody(Circle({0, y0}, r));
  engine::World alone(engine::WorldDef{});
  const BodyId alone_ball = alone.CreateBody(Circle({0, y0}, r));

  // The steps from the closed form: it begins once its bottom reaches the top, y - r <= 3, and
  // ends once its top has left the bottom, y + r < 2.
  const int n = world.Def().substeps;
  const double h = world.Def().dt / n;
  int begin_step = 0, end_step = 0;
  for (int step = 1; step <= 120 && end_step == 0; ++step) {
    const double y = testing::SemiImplicitFall(y0, 0, -kG, h, static_cast<long long>(step) * n).position;
    if (begin_step == 0 && y - r <= 3.0) begin_step = step;
    if (y + r < 2.0) end_step = step;
  }
  REQUIRE(begin_step == 45);  // 2.75 m of fall: t = 0.749 s
  REQUIRE(end_step == 56);    // 4.25 m: t = 0.931 s

  SensorLog log;
  for (int step = 1; step <= 90; ++step) {
    world.Step();
    alone.Step();
    for (const auto& e : world.Events().sensor_begin) log.begins.push_back({step, e});
    for (const auto& e : world.Events().sensor_end) log.ends.push_back({step, e});
    // The sensor never slows it: the same bits as a ball alone.
    REQUIRE(world.State(ball).position == alone.State(alone_ball).position);
    REQUIRE(world.State(ball).velocity == alone.State(alone_ball).velocity);
  }
  REQUIRE(log.begins.size() == 1);
  REQUIRE(log.ends.size() == 1);
  CHECK(log.begins[0].event.sensor == sensor);
  CHECK(log.begins[0].event.visitor == ball);
  CHECK(log.ends[0].event.sensor == sensor);
  CHECK(log.ends[0].event.visitor == ball);
  CHECK(log.begins[0].step == Approx(begin_step).margin(1));
  CHECK(log.ends[0].step == Approx(end_step).margin(1));
  CHECK(world.Contacts().empty());
  const auto fall = testing::SemiImplicitFall(y0, 0, -kG, h, 90LL * n);
  CHECK(world.State(ball).position.y == Approx(fall.position).epsilon(1e-12));
}

TEST_CASE("sensors: two sensors never report each other, and a sensor body collides with nothing",
          "[sensors]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  world.CreateBody(Sensor(Static(Box({0, 2.5}, {2, 1}))));
  const BodyId falling = world.CreateBody(Sensor(Circle({0, 4}, 0.25)));  // through both
  const SensorLog log = RecordSensors(world, 60);
  CHECK(log.begins.size() == 1);  // the floor, once the falling sensor reaches it
  for (const SensorStep& s : log.begins) CHECK(s.event.sensor == falling);
  CHECK(world.State(falling).position.y < -0.5);  // through the floor as well
  CHECK(world.Contacts().empty());
}

TEST_CASE("sensors: a ball that falls asleep inside a sensor stays reported inside", "[sensors]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId sensor = world.CreateBody(Sensor(Static(Box({0, 0.51}, {2, 1}))));  // 1 cm over the floor
  const BodyId ball = world.CreateBody(Circle({0, 2}, 0.25));
  const SensorLog log = RecordSensors(world, 240);
  CHECK_FALSE(world.IsAwake(ball));
  REQUIRE(log.begins.size() == 1);
  CHECK(log.begins[0].event.sensor == sensor);
  CHECK(log.begins[0].event.visitor == ball);
  CHECK(log.ends.empty());
  // Taken away, it ends after the next step.
  world.DestroyBody(ball);
  world.Step();
  REQUIRE(world.Events().sensor_end.size() == 1);
  CHECK(world.Events().sensor_end[0].visitor == ball);
}

TEST_CASE("sensors: a kinematic body sweeping through a sensor is reported in and out", "[sensors]") {
  engine::World world(engine::WorldDef{});
  const BodyId sensor = world.CreateBody(Sensor(Static(Box({0, 0}, {1, 1}))));
  const BodyId mover = world.CreateBody(testing::Kinematic(Box({-2, 0}, {0.5, 0.5}), {1, 0}));
  const SensorLog log = RecordSensors(world, 240);
  REQUIRE(log.begins.size() == 1);
  REQUIRE(log.ends.size() == 1);
  CHECK(log.begins[0].event.sensor == sensor);
  CHECK(log.begins[0].event.visitor == mover);
  // Touching while its centre is within 0.75 m of the sensor's: from t = 1.25 s to 2.75 s.
  CHECK(log.begins[0].step == Approx(75).margin(1));
  CHECK(log.ends[0].step == Approx(165).margin(1));
}

TEST_CASE("sensors: a static body in a static sensor is a visitor too, reported once", "[sensors]") {
  engine::World world(engine::WorldDef{});
  const BodyId wall = world.CreateBody(Static(Box({0, 1}, {0.5, 2})));
  const BodyId sensor = world.CreateBody(Sensor(Static(Box({0.5, 1}, {1, 1}))));  // over the wall's side
  const SensorLog log = RecordSensors(world, 60);
  REQUIRE(log.begins.size() == 1);
  CHECK(log.begins[0].step == 1);
  CHECK(log.begins[0].event.sensor == sensor);
  CHECK(log.begins[0].event.visitor == wall);
  CHECK(log.ends.empty());
}

// Step updates the sensors while some sensor exists or ends of removed ones wait: the last
// sensor's overlaps, queued when it is destroyed, are reported after the next step.
TEST_CASE("sensors: destroying the last sensor ends its overlaps after the next step", "[sensors]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId sensor = world.CreateBody(Sensor(Static(Box({0, 0.51}, {2, 1}))));
  const BodyId ball = world.CreateBody(Circle({0, 0.25}, 0.25));
  world.Step();
  REQUIRE(world.Events().sensor_begin.size() == 1);
  world.DestroyBody(sensor);
  world.Step();
  REQUIRE(world.Events().sensor_end.size() == 1);
  CHECK(world.Events().sensor_end[0].sensor == sensor);
  CHECK(world.Events().sensor_end[0].visitor == ball);
}
