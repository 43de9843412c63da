// Snapshots: a restored world steps on to the same bits as the original, and a snapshot that is
// truncated, corrupt or from a world with other settings is refused with the world unchanged.
#include <catch2/catch.hpp>

#include <cstdint>
#include <random>
#include <vector>

#include "engine/world.h"
#include "game/click.h"
#include "game/default_scene.h"
#include "game/scene.h"
#include "world_builders.h"

namespace {

game::Scene DefaultScene(bool rotation) {
  auto scene = game::ParseScene(game::DefaultSceneJson(), "default", "default");
  REQUIRE(scene.HasValue());
  game::Scene s = scene.Value();
  s.world.rotation = rotation;
  return s;
}

// A number in [0, 1) from the generator's raw bits (std's distributions are not the same on
// every standard library).
double Unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// A click inside a random ball of the world, off its centre by up to 90 % of its radius.
engine::Vec2 ClickOnABall(const engine::World& world, std::mt19937_64& rng) {
  std::vector<engine::BodyId> balls;
  for (const engine::BodyId id : world.BodyIds()) {
    if (world.Info(id).shape.type == engine::ShapeType::kCircle && !world.Info(id).is_static) balls.push_back(id);
  }
  const engine::BodyId ball = balls[static_cast<std::size_t>(Unit(rng) * static_cast<double>(balls.size()))];
  const double r = 0.9 * world.Info(ball).shape.radius;
  return world.State(ball).position + engine::Vec2{r * (2 * Unit(rng) - 1), r * (2 * Unit(rng) - 1)} * 0.7;
}

}  // namespace

TEST_CASE("a restored world and the original stay identical for 10 000 steps of random clicks",
          "[snapshot]") {
  for (const bool rotation : {false, true}) {
    INFO("rotation " << rotation);
    const game::Scene scene = DefaultScene(rotation);
    engine::World original = game::BuildWorld(scene);
    for (int i = 0; i < 120; ++i) original.Step();
    engine::World restored = game::BuildWorld(scene);  // still at step 0
    REQUIRE(restored.RestoreSnapshot(original.TakeSnapshot()));
    CHECK(restored.StepCount() == 120);
    CHECK(restored.StateHash() == original.StateHash());
    std::mt19937_64 rng(20261125);
    int clicks_that_hit = 0, first_difference = -1;
    for (int step = 0; step < 10000; ++step) {
      if (step % 7 == 0) {
        const engine::Vec2 p = ClickOnABall(original, rng);
        const bool hit = game::ApplyClick(original, p, scene.click_max_impulse).has_value();
        game::ApplyClick(restored, p, scene.click_max_impulse);
        clicks_that_hit += hit;
      }
      original.Step();
      restored.Step();
      if (first_difference < 0 && original.StateHash() != restored.StateHash()) first_difference = step;
    }
    CHECK(clicks_that_hit == 1429);  // every click pushed a ball: the scene was stirred
    CHECK(first_difference == -1);
    CHECK(original.TakeSnapshot() == restored.TakeSnapshot());
  }
}

TEST_CASE("rolling back: restoring an earlier snapshot into the same world replays the same steps",
          "[snapshot]") {
  engine::World world = game::BuildWorld(DefaultScene(true));
  for (int i = 0; i < 60; ++i) world.Step();
  const std::vector<std::uint8_t> saved = world.TakeSnapshot();
  std::vector<std::uint64_t> first_run;
  for (int i = 0; i < 300; ++i) world.Step(), first_run.push_back(world.StateHash());
  REQUIRE(world.RestoreSnapshot(saved));
  CHECK(world.StepCount() == 60);
  for (int i = 0; i < 300; ++i) {
    world.Step();
    if (world.StateHash() != first_run[i]) FAIL("differs at step " << 60 + i + 1);
  }
}

TEST_CASE("snapshots carry destroyed slots, disabled bodies, filters, user data and springs",
          "[snapshot]") {
  engine::WorldDef def;
  def.rotation = true;
  engine::World world(def);
  world.CreateBody(testing::Static(testing::Box({0, -0.5}, {20, 1})));
  std::vector<engine::BodyId> ids;
  for (int i = 0; i < 8; ++i) ids.push_back(world.CreateBody(testing::Box({-4.0 + i, 0.5 + 0.1 * i}, {0.8, 0.8})));
  world.DestroyBody(ids[2]);
  world.DestroyBody(ids[5]);
  world.SetEnabled(ids[3], false);
  world.SetFilter(ids[4], {.category_bits = 2, .mask_bits = ~2ull, .group_index = 0});
  world.SetUserData(ids[6], 0xfeedULL);
  engine::SpringDef spring;
  spring.body_a = ids[0];
  spring.body_b = ids[1];
  spring.rest_length = 1.5;
  spring.stiffness = 30.0;
  world.AddSpring(spring);
  for (int i = 0; i < 30; ++i) world.Step();

  engine::World copy(def);
  const engine::RestoreResult restored = copy.RestoreSnapshot(world.TakeSnapshot());
  INFO(restored.error);
  REQUIRE(restored);
  CHECK(!copy.IsValid(ids[2]));
  CHECK(!copy.IsEnabled(ids[3]));
  CHECK(copy.GetFilter(ids[4]).category_bits == 2);
  CHECK(copy.UserData(ids[6]) == 0xfeedULL);
  CHECK(copy.Springs().size() == 1);
  // The next bodies created take the same slots, with the same generations, in both.
  const engine::BodyId a = world.CreateBody(testing::Box({2, 3}, {0.5, 0.5}));
  const engine::BodyId b = copy.CreateBody(testing::Box({2, 3}, {0.5, 0.5}));
  CHECK(a.index == b.index);
  CHECK(a.generation == b.generation);
  CHECK(a.index == ids[5].index);
  CHECK(a.generation == ids[5].generation + 1);
  for (int i = 0; i < 300; ++i) world.Step(), copy.Step();
  CHECK(world.StateHash() == copy.StateHash());
}

TEST_CASE("a truncated, corrupt or foreign snapshot is refused and changes nothing", "[snapshot]") {
  const game::Scene scene = DefaultScene(false);
  engine::World source = game::BuildWorld(scene);
  for (int i = 0; i < 90; ++i) source.Step();
  const std::vector<std::uint8_t> good = source.TakeSnapshot();

  engine::World target = game::BuildWorld(scene);
  const std::uint64_t before = target.StateHash();
  for (std::size_t length = 0; length < good.size(); length += 1 + length / 16) {
    const engine::RestoreResult r = target.RestoreSnapshot(std::span(good).first(length));
    if (r) FAIL("a snapshot cut to " << length << " of " << good.size() << " bytes was accepted");
  }
  std::vector<std::uint8_t> flipped = good;
  flipped[flipped.size() / 2] ^= 0x10;
  const engine::RestoreResult corrupt = target.RestoreSnapshot(flipped);
  CHECK(!corrupt);
  CHECK(corrupt.error.find("corrupt") != std::string::npos);

  game::Scene other_scene = scene;
  other_scene.world.gravity = {0, -1.62};  // the Moon
  engine::World moon = game::BuildWorld(other_scene);
  const engine::RestoreResult foreign = moon.RestoreSnapshot(good);
  CHECK(!foreign);
  CHECK(foreign.error.find("other settings") != std::string::npos);
  game::Scene fewer_passes = scene;  // the passes a turning pile of circles takes
  fewer_passes.world.circle_velocity_iterations = 3;
  CHECK(!game::BuildWorld(fewer_passes).RestoreSnapshot(good));

  CHECK(target.StateHash() == before);
  CHECK(target.StepCount() == 0);
  CHECK(target.RestoreSnapshot(good));
  CHECK(target.StateHash() == source.StateHash());
}
