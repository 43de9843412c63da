// Solver stress tests with stated thresholds (issue: stacks, mass ratios, overlap recovery,
// circle pours, energy), on the axis-aligned game at 60 Hz with sleeping off.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/world.h"
#include "solver/substep_solver.h"
#include "bench/stress_scenes.h"

namespace {

engine::WorldDef AwakeWorld() {
  engine::WorldDef def;
  def.sleeping = false;  // stability must not lean on sleep
  return def;
}

// The largest distance any dynamic body ends from where it started, over `steps` steps.
double MaxDrift(engine::World& world, int steps) {
  std::vector<engine::Vec2> start;
  for (const engine::BodyId id : world.BodyIds()) start.push_back(world.State(id).position);
  for (int i = 0; i < steps; ++i) world.Step();
  double drift = 0;
  for (const engine::BodyId id : world.BodyIds()) {
    drift = std::max(drift, engine::Length(world.State(id).position - start[id.index]));
  }
  return drift;
}

double MaxOverlap(const engine::World& world) {
  double deepest = 0;
  for (const engine::Contact& c : world.Contacts()) {
    for (int p = 0; p < c.manifold.point_count; ++p) deepest = std::max(deepest, c.manifold.points[p].depth);
  }
  return deepest;
}

}  // namespace

TEST_CASE("a pyramid of base 20 stands 10 s with every box within 5 mm", "[stability]") {
  engine::World world(AwakeWorld());
  stress::AddPyramid(world, 20);
  const double drift = MaxDrift(world, 600);
  INFO("max drift " << drift << " m");
  CHECK(drift < 0.005);
}

TEST_CASE("a pyramid of base 40 stands 10 s with every box within 1 cm", "[stability]") {
  engine::World world(AwakeWorld());
  stress::AddPyramid(world, 40);
  const double drift = MaxDrift(world, 600);
  INFO("max drift " << drift << " m");
  CHECK(drift < 0.01);
}

TEST_CASE("a pyramid of base 20 dropped into place settles where it should, within 5 mm", "[stability]") {
  // Every row starts 2 cm above the one below: the rows fall, land on each other and come to
  // rest touching, row r at y = 0.5 + r (within the slop the contacts leave alone).
  engine::World world(AwakeWorld());
  stress::AddPyramid(world, 20, 0.0, 0.02);
  for (int i = 0; i < 600; ++i) world.Step();
  double worst = 0, fastest = 0;
  engine::BodyId id{1};
  for (int row = 0; row < 20; ++row) {
    for (int i = 0; i < 20 - row; ++i, ++id.index) {
      const engine::Vec2 expected{(i - 0.5 * (19 - row)), 0.5 + row};
      worst = std::max(worst, engine::Length(world.State(id).position - expected));
      fastest = std::max(fastest, engine::Length(world.State(id).velocity));
    }
  }
  INFO("worst distance from the resting place " << worst << " m, fastest " << fastest << " m/s");
  CHECK(worst < 0.005);
  CHECK(fastest < 1e-3);
}

TEST_CASE("a vertical stack of 20 boxes stays within 5 mm", "[stability]") {
  engine::World world(AwakeWorld());
  stress::AddStack(world, 20);
  const double drift = MaxDrift(world, 600);
  INFO("max drift " << drift << " m");
  CHECK(drift < 0.005);
}

TEST_CASE("a heavy box on a column of light ones stands (mass ratio 1000:1 and more)", "[stability]") {
  for (double ratio : {1e3, 1e4}) {
    engine::World world(AwakeWorld());
    stress::AddHeavyOnLight(world, 3, ratio);
    const engine::BodyId heavy = static_cast<engine::BodyId>(world.BodyCount() - 1);
    const double y0 = world.State(heavy).position.y;
    for (int i = 0; i < 600; ++i) world.Step();
    const double sink = y0 - world.State(heavy).position.y;
    INFO("ratio " << ratio << ": the heavy box sank " << sink << " m");
    CHECK(sink < 0.01);
  }
}

TEST_CASE("boxes placed 25% overlapped separate within 1 s, without flying apart", "[stability]") {
  engine::World world(AwakeWorld());
  stress::AddPyramid(world, 4, 0.25);
  const double g = engine::Length(world.Def().gravity);
  double fastest = 0;
  for (int i = 1; i <= 60; ++i) {
    world.Step();
    for (const engine::BodyId id : world.BodyIds()) {
      const double limit = 3.0 + g * i * world.Def().dt;  // push-out speed plus free fall
      fastest = std::max(fastest, engine::Length(world.State(id).velocity));
      REQUIRE(engine::Length(world.State(id).velocity) <= limit);
    }
  }
  INFO("fastest body " << fastest << " m/s");
  CHECK(MaxOverlap(world) < 2 * world.Def().linear_slop);
}

TEST_CASE("2000 circles poured into a box: none escapes, no NaN, overlap < 1 cm after 10 s", "[stability]") {
  for (const bool rotation : {false, true}) {  // turning circles go by colour (SubstepSolver::AllRound)
    INFO((rotation ? "turning" : "axis-aligned"));
    engine::WorldDef def = AwakeWorld();
    def.rotation = rotation;
    engine::World world(def);
    const double width = 20, height = 40;  // 61 rows of 33 start below y = 36
    stress::AddContainer(world, width, height);
    stress::AddCirclePour(world, 2000, 0.25, width);
    for (int i = 0; i < 600; ++i) world.Step();
    const double worst_overlap = MaxOverlap(world);
    for (engine::BodyId id{4}; id.index < world.BodyCount(); ++id.index) {
      const engine::Vec2 p = world.State(id).position;
      REQUIRE(engine::IsFinite(p));
      REQUIRE(std::abs(p.x) < 0.5 * width);
      REQUIRE(p.y > 0);
      REQUIRE(p.y < height);
    }
    INFO("max overlap after 10 s " << worst_overlap << " m");
    CHECK(worst_overlap < 0.01);
  }
}

TEST_CASE("turning circles without gravity in a closed box never gain kinetic energy", "[stability]") {
  // Over 256 contacts of circles alone: colour order and 2 passes (SubstepSolver::AllRound),
  // one contact at a time (no gravity: the warm start's energy scale sums over all of them).
  engine::WorldDef def = AwakeWorld();
  def.rotation = true;
  def.gravity = {0.0, 0.0};
  engine::World world(def);
  const double width = 24.0;
  stress::AddContainer(world, width, width);
  stress::AddCirclePour(world, 1500, 0.25, width, 0.5, 5);
  const auto kinetic = [&] {
    double e = 0.0;
    for (const engine::BodyId id : world.BodyIds()) {
      const engine::BodyInfo& info = world.Info(id);
      const engine::BodyState& s = world.State(id);
      e += 0.5 * info.mass * engine::LengthSquared(s.velocity) +
           0.5 * info.inertia * s.angular_velocity * s.angular_velocity;
    }
    return e;
  };
  double highest = kinetic();
  std::size_t most_contacts = 0;
  for (int i = 0; i < 600; ++i) {
    world.Step();
    most_contacts = std::max(most_contacts, world.Contacts().size());
    const double e = kinetic();
    INFO("step " << i << ": kinetic energy " << e << " J, highest so far " << highest << " J");
    REQUIRE(e <= highest * (1.0 + 1e-9));
    highest = std::max(highest, e);
  }
  CHECK(most_contacts >= engine::detail::SubstepSolver::kMinStripContacts);
}

TEST_CASE("energy never increases in a closed scene with restitution < 1", "[stability]") {
  engine::World world(AwakeWorld());
  stress::AddContainer(world, 10, 12);
  stress::AddCirclePour(world, 150, 0.3, 10, 0.9, 7);
  for (int i = 0; i < 30; ++i) world.CreateBody(stress::Box({-4.0 + 0.3 * i, 8.0 + (i % 3)}, {0.4, 0.4}));
  const double g = -world.Def().gravity.y;
  auto energy = [&] {
    double e = 0;
    for (const engine::BodyId id : world.BodyIds()) {
      const engine::BodyInfo& info = world.Info(id);
      const engine::BodyState& s = world.State(id);
      e += 0.5 * info.mass * engine::LengthSquared(s.velocity) + info.mass * g * s.position.y;
    }
    return e;
  };
  double highest = energy();
  const double e0 = highest;
  for (int i = 0; i < 600; ++i) {
    world.Step();
    const double e = energy();
    INFO("step " << i << ": energy " << e << " J, highest so far " << highest << " J");
    REQUIRE(e <= highest + 1e-6 * std::abs(e0));
    highest = std::max(highest, e);
  }
}
