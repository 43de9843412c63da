// Continuous collision: no tunnelling at any speed, bullets, a measured miss rate with it off
// (which proves the harness sees tunnelling at all), and the ray cast. accuracy.md §3.4.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "engine/world.h"
#include "game/scene.h"
#include "world_builders.h"

using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Static;
using testing::WithMaterial;

namespace {

constexpr double kRadius = 0.05, kWall = 0.1;  // a 0.05 m ball and a 0.1 m wall at x ∈ [0, 0.1]

// Fires the ball at `speed` from `phase` (a fraction of one step's travel) behind x = −1 and
// reports whether it ever ended a step on the far side of the wall.
bool PassesWall(double speed, double phase, bool continuous) {
  engine::WorldDef def;
  def.gravity = {0, 0};
  def.continuous = continuous;
  def.sleeping = false;
  engine::World world(def);
  world.CreateBody(Static(Box({0.5 * kWall, 0}, {kWall, 4})));
  const double x0 = -1.0 - phase * speed * def.dt;
  world.CreateBody(WithMaterial(Circle({x0, 0}, kRadius, {speed, 0}), 0.5, 0));
  const int steps = static_cast<int>(std::ceil(3.0 / (speed * def.dt))) + 3;
  for (int i = 0; i < steps; ++i) {
    world.Step();
    if (world.State({1}).position.x > 0.5 * kWall) return true;  // past the middle: through
  }
  return false;
}

}  // namespace

TEST_CASE("a 0.05 m ball never passes a 0.1 m wall, at 50 to 5000 m/s", "[continuous]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> phase(0.0, 1.0);
  for (double speed : {50.0, 200.0, 1000.0, 5000.0}) {
    for (int k = 0; k < 50; ++k) {
      INFO("speed " << speed << " m/s, try " << k);
      REQUIRE_FALSE(PassesWall(speed, phase(rng), true));
    }
  }
}

TEST_CASE("with continuous collision off, fast balls tunnel at the rate discrete sampling predicts", "[continuous]") {
  // A discrete step sees the ball only where it lands. It is caught when it lands within the
  // catch width c before the wall's middle: its radius, half the wall and the 2 cm speculative
  // gap. So it misses with probability 1 − 1/Π, Π = v·dt / c (accuracy.md §3.4 with the
  // engine's catch width in place of w + D; past the middle the overlap resolves to the far side).
  const double dt = 1.0 / 60.0, catch_width = kRadius + 0.5 * kWall + 0.02;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> phase(0.0, 1.0);
  constexpr int kTries = 400;
  for (double pi : {2.0, 4.0, 8.0}) {
    const double speed = pi * catch_width / dt;
    int misses = 0;
    for (int k = 0; k < kTries; ++k) misses += PassesWall(speed, phase(rng), false) ? 1 : 0;
    const double expected = 1.0 - 1.0 / pi;
    const double sigma = std::sqrt(expected * (1 - expected) / kTries);
    INFO("Π = " << pi << ": missed " << misses << " of " << kTries << ", expected " << expected * kTries);
    CHECK(std::abs(misses / double(kTries) - expected) < 4 * sigma);
    // And the same balls never pass with it on.
    CHECK_FALSE(PassesWall(speed, 0.37, true));
  }
}

TEST_CASE("a bullet does not pass a thin dynamic box, even with continuous collision off", "[continuous]") {
  for (double speed : {300.0, 3000.0}) {
    engine::WorldDef def;
    def.gravity = {0, 0};
    def.continuous = false;  // only the bullet flag keeps it
    engine::World world(def);
    engine::BodyDef bullet = WithMaterial(Circle({-2, 0}, kRadius, {speed, 0}), 0, 0);
    bullet.bullet = true;
    world.CreateBody(bullet);
    world.CreateBody(testing::WithMass(Box({0, 0}, {0.05, 1}), 5));
    for (int i = 0; i < 120; ++i) {
      world.Step();
      INFO("speed " << speed << ", step " << i);
      REQUIRE(world.State({0}).position.x < world.State({1}).position.x);
    }
    CHECK(world.State({1}).velocity.x > 0);  // it was hit and pushed
  }
}

TEST_CASE("a fast ball bouncing in a closed box stays inside for 10 s", "[continuous]") {
  engine::WorldDef def;
  def.gravity = {0, 0};
  def.sleeping = false;
  engine::World world(def);
  const double half = 5.0, t = 0.1;
  world.CreateBody(Static(Box({0, -half - 0.5 * t}, {2 * half + 2 * t, t})));
  world.CreateBody(Static(Box({0, half + 0.5 * t}, {2 * half + 2 * t, t})));
  world.CreateBody(Static(Box({-half - 0.5 * t, 0}, {t, 2 * half})));
  world.CreateBody(Static(Box({half + 0.5 * t, 0}, {t, 2 * half})));
  const double r = 0.1;
  world.CreateBody(WithMaterial(Circle({0.3, -0.2}, r, {300.0 * std::cos(0.7), 300.0 * std::sin(0.7)}), 1.0, 0));
  int bounces = 0;
  double previous_vx = world.State({4}).velocity.x;
  for (int i = 0; i < 600; ++i) {
    world.Step();
    const Vec2 p = world.State({4}).position;
    INFO("step " << i << " at (" << p.x << ", " << p.y << ")");
    REQUIRE(std::abs(p.x) <= half - r + 1e-6);
    REQUIRE(std::abs(p.y) <= half - r + 1e-6);
    if ((world.State({4}).velocity.x > 0) != (previous_vx > 0)) ++bounces;
    previous_vx = world.State({4}).velocity.x;
  }
  CHECK(bounces > 100);  // it really did fly: ~300 m/s·10 s / 10 m
  CHECK(engine::Length(world.State({4}).velocity) == Approx(300.0).epsilon(1e-9));  // e = 1 keeps speed
}

TEST_CASE("continuous collision changes nothing in a scene without fast bodies", "[continuous][skip]") {
  for (const char* name : {"box_pile.json", "bouncing_ball.json"}) {
    game::Expected<game::Scene> scene = game::LoadScene(std::string(BALLBOX_ASSETS) + "/scenes/" + name);
    REQUIRE(scene.HasValue());
    game::Scene off = scene.Value();
    off.world.continuous = false;
    engine::World with = game::BuildWorld(scene.Value());
    engine::World without = game::BuildWorld(off);
    for (int i = 0; i < 600; ++i) {
      with.Step();
      without.Step();
      INFO(name << ", step " << i);
      REQUIRE(with.StateHash() == without.StateHash());
    }
  }
}

TEST_CASE("ray cast: circles, boxes, turned boxes, the nearest hit", "[continuous][ray]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(Circle({5, 0}, 1));                          // 0
  world.CreateBody(Static(Box({10, 0}, {2, 4})));               // 1: x ∈ [9, 11], y ∈ [−2, 2]
  engine::BodyDef diamond = Box({0, 5}, {1, 1});
  diamond.angle = 3.14159265358979323846 / 4;
  world.CreateBody(diamond);                                     // 2
  // Along +x the circle comes first: entered at x = 4, 4 m of a 20 m ray.
  auto hit = world.RayCast({0, 0}, {20, 0});
  REQUIRE(hit);
  CHECK(hit->body == engine::BodyId{0});
  CHECK(hit->fraction == Approx(0.2).epsilon(1e-12));
  CHECK(hit->point.x == Approx(4.0).epsilon(1e-12));
  CHECK(hit->normal.x == Approx(-1.0).epsilon(1e-12));
  // Above the circle, the box's left face at x = 9.
  hit = world.RayCast({0, 1.5}, {20, 1.5});
  REQUIRE(hit);
  CHECK(hit->body == engine::BodyId{1});
  CHECK(hit->point.x == Approx(9.0).epsilon(1e-12));
  CHECK(hit->normal.x == Approx(-1.0).margin(1e-12));
  // Straight down onto the diamond's top corner at y = 5 + √½.
  hit = world.RayCast({0, 10}, {0, 0});
  REQUIRE(hit);
  CHECK(hit->body == engine::BodyId{2});
  CHECK(hit->point.y == Approx(5.0 + std::sqrt(0.5)).epsilon(1e-12));
  // Missing everything, and starting inside a body, are no hits.
  CHECK_FALSE(world.RayCast({0, -3}, {20, -3}));
  CHECK_FALSE(world.RayCast({5, 0}, {5, 0.5}));
}
