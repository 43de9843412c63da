// Each of the substep solver's optional mechanisms (WorldDef::substep_features) does what it is
// there for: switched off, the effect it exists for goes away; on (the default), it holds.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "world_builders.h"

using testing::Box;
using testing::Circle;
using testing::Static;
using testing::WithMaterial;

namespace {

// The highest point a ball of restitution e, dropped from 2 m onto a static floor, reaches after
// its first bounce (its centre, above the floor's surface).
double FirstApex(const engine::SubstepFeatures& features) {
  engine::WorldDef def;
  def.substep_features = features;
  engine::World world(def);
  world.CreateBody(Static(Box({0, -0.5}, {10, 1})));
  const engine::BodyId ball = world.CreateBody(WithMaterial(Circle({0, 2.5}, 0.5), 0.8, 0.3));
  bool fell = false;
  double apex = 0.0;
  for (int i = 0; i < 300; ++i) {
    world.Step();
    const engine::BodyState& s = world.State(ball);
    if (s.velocity.y > 0.0) fell = true;  // bounced
    if (fell) apex = std::max(apex, s.position.y - 0.5);
    if (fell && s.velocity.y < 0.0) break;
  }
  return apex;
}

// How far the heavy box on a column of three light ones (`ratio` times their mass) has sunk
// after 10 s, m.
double HeavyBoxSink(bool rotation, double ratio, const engine::SubstepFeatures& features) {
  engine::WorldDef def;
  def.sleeping = false;
  def.rotation = rotation;
  def.substep_features = features;
  engine::World world(def);
  stress::AddHeavyOnLight(world, 3, ratio);
  const engine::BodyId heavy = static_cast<engine::BodyId>(world.BodyCount() - 1);
  const double y0 = world.State(heavy).position.y;
  double sank = 0.0;
  for (int i = 0; i < 600; ++i) {
    world.Step();
    sank = std::max(sank, y0 - world.State(heavy).position.y);
  }
  return sank;
}

// The largest rise of kinetic energy from one step to the next, as a fraction of the start, in a
// packed grid of circles in a closed box without gravity (docs/solver.md, "Warm start").
double WorstEnergyRise(const engine::SubstepFeatures& features) {
  engine::WorldDef def;
  def.gravity = {};
  def.sleeping = false;
  def.substep_features = features;
  engine::World world(def);
  const double inner = 15.0, h = 0.5 * inner;
  world.CreateBody(Static(Box({0, -h - 0.5}, {inner + 2, 1})));
  world.CreateBody(Static(Box({0, h + 0.5}, {inner + 2, 1})));
  world.CreateBody(Static(Box({-h - 0.5, 0}, {1, inner})));
  world.CreateBody(Static(Box({h + 0.5, 0}, {1, inner})));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> speed(-1.0, 1.0);
  for (int i = 0; i < 15 * 15; ++i) {
    const engine::Vec2 at{0.96 * (i % 15 - 7), 0.96 * (i / 15 - 7)};
    world.CreateBody(WithMaterial(Circle(at, 0.5, {speed(rng), speed(rng)}), 0.2, 0.6));
  }
  const double start = testing::LinearKineticEnergy(world);
  double previous = start, worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    world.Step();
    const double e = testing::LinearKineticEnergy(world);
    worst = std::max(worst, (e - previous) / start);
    previous = e;
  }
  return worst;
}

}  // namespace

TEST_CASE("impact pass: a ball of restitution 0.8 bounces to e² of its drop, and not without it",
          "[solver][features]") {
  const double drop = 2.0;
  const double with = FirstApex({});
  engine::SubstepFeatures off;
  off.impact_pass = false;
  const double without = FirstApex(off);
  INFO("apex after the first bounce: " << with << " m with the impact pass, " << without << " m without");
  CHECK(with == Approx(0.64 * drop).epsilon(0.005));
  CHECK(without < 0.1 * drop);  // the contact solve alone is inelastic
}

TEST_CASE("shock propagation: a box 10 000 times the mass of each box under it stands, and sinks "
          "without it", "[solver][features]") {
  const double with = HeavyBoxSink(false, 1e4, {});
  engine::SubstepFeatures off;
  off.shock_propagation = false;
  const double without = HeavyBoxSink(false, 1e4, off);
  INFO("sank " << with << " m with shock propagation, " << without << " m without");
  CHECK(with < 0.001);
  CHECK(without > 0.05);
}

TEST_CASE("direct solve: with rotation a 1000:1 column stands, and sinks without it", "[solver][features]") {
  const double with = HeavyBoxSink(true, 1e3, {});
  engine::SubstepFeatures off;
  off.direct_solve = false;
  const double without = HeavyBoxSink(true, 1e3, off);
  INFO("sank " << with << " m with the direct solve, " << without << " m without");
  CHECK(with < 0.001);
  CHECK(without > 0.01);
}

TEST_CASE("energy limit: a packed cluster without applied forces never gains kinetic energy, and "
          "does without it", "[solver][features]") {
  const double with = WorstEnergyRise({});
  engine::SubstepFeatures off;
  off.energy_limit = false;
  const double without = WorstEnergyRise(off);
  INFO("largest rise in one step: " << with << " of the start with the limit, " << without << " without");
  CHECK(with <= 1e-9);
  CHECK(without > 0.01);
}

TEST_CASE("block solver: a wide box resting on its face with rotation on stays level", "[solver][features]") {
  auto max_turn = [](const engine::SubstepFeatures& features) {
    engine::WorldDef def;
    def.rotation = true;
    def.sleeping = false;
    def.substep_features = features;
    engine::World world(def);
    world.CreateBody(Static(Box({0, -0.5}, {10, 1})));
    engine::BodyId top{0};
    for (int i = 0; i < 5; ++i) top = world.CreateBody(Box({0, 0.25 + 0.5 * i}, {2, 0.5}));
    double turned = 0.0;
    for (int i = 0; i < 600; ++i) {
      world.Step();
      for (engine::BodyId id{1}; id.index <= top.index; ++id.index) turned = std::max(turned, std::abs(world.State(id).angle));
    }
    return turned;
  };
  const double with = max_turn({});
  engine::SubstepFeatures off;
  off.block_solver = false;
  const double without = max_turn(off);
  INFO("largest turn: " << with << " rad with the block solver, " << without << " rad without");
  CHECK(with < 1e-6);
  CHECK(without > with);
}

TEST_CASE("colour order: off, the contacts are solved in pair order, which changes the bits but not "
          "the physics", "[solver][features]") {
  auto pour = [](const engine::SubstepFeatures& features) {
    engine::WorldDef def;
    def.sleeping = false;
    def.substep_features = features;
    engine::World world(def);
    stress::AddContainer(world, 10, 20);
    stress::AddCirclePour(world, 400, 0.25, 10);
    for (int i = 0; i < 300; ++i) world.Step();
    return world;
  };
  engine::SubstepFeatures off;
  off.colour_order = false;
  const engine::World by_colour = pour({});
  const engine::World by_pair = pour(off);
  double overlap = 0.0;
  for (const engine::Contact& c : by_pair.Contacts()) overlap = std::max(overlap, c.manifold.points[0].depth);
  bool contained = true;
  for (engine::BodyId id{4}; id.index < by_pair.BodyCount(); ++id.index) {
    const engine::Vec2 p = by_pair.State(id).position;
    contained = contained && std::abs(p.x) < 5 && p.y > 0 && p.y < 20;
  }
  INFO("400 circles poured, solved in pair order: deepest overlap " << overlap << " m after 5 s");
  CHECK(contained);
  CHECK(overlap < 0.01);
  CHECK(by_colour.StateHash() != by_pair.StateHash());
}
