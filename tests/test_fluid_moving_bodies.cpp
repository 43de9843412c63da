// Fluid against bodies that move by themselves: a kinematic paddle sweeping through water keeps
// the water out, every substep, as a static wall does.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "engine/world.h"
#include "world_builders.h"

namespace {

using engine::Vec2;

// Signed distance from p to an axis-aligned box (negative inside).
double BoxDistance(Vec2 p, Vec2 center, Vec2 half) {
  const double dx = std::abs(p.x - center.x) - half.x;
  const double dy = std::abs(p.y - center.y) - half.y;
  if (dx <= 0.0 && dy <= 0.0) return std::max(dx, dy);
  return std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
}

}  // namespace

TEST_CASE("a kinematic paddle sweeping through water leaves no particle inside it", "[fluid]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(testing::Static(testing::Box({0.0, -0.5}, {4.0, 1.0})));
  world.CreateBody(testing::Static(testing::Box({-1.5, 1.0}, {1.0, 3.0})));
  world.CreateBody(testing::Static(testing::Box({1.5, 1.0}, {1.0, 3.0})));
  engine::FluidDef water;
  water.region = {{-0.7, 0.0}, {1.0, 0.5}};
  water.spacing = 0.05;
  world.AddFluid(water);
  const Vec2 half{0.05, 0.4};
  engine::BodyDef paddle = testing::Box({-0.85, 0.45}, {2.0 * half.x, 2.0 * half.y});
  paddle.is_kinematic = true;
  paddle.velocity = {1.5, 0.0};  // 2.5 cm a step, half a particle: a plane left where it was would show
  const engine::BodyId id = world.CreateBody(paddle);
  const double radius = 0.5 * water.spacing;
  double deepest = 0.0;  // the most a particle's disc reaches into the paddle, m
  for (int step = 0; step < 40; ++step) {
    world.Step();
    const Vec2 center = world.State(id).position;
    for (const Vec2 p : world.FluidPositions()) deepest = std::max(deepest, radius - BoxDistance(p, center, half));
  }
  INFO("paddle at x = " << world.State(id).position.x << ", deepest reach into it " << deepest << " m");
  CHECK(world.State(id).position.x > 0.1);  // it swept 1 m of water
  CHECK(deepest < 0.002);
}
