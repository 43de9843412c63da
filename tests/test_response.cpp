// Collision response: impulses against the closed-form collision laws and conservation laws.
#include <catch2/catch.hpp>

#include <random>

#include "engine/world.h"
#include "world_builders.h"

using testing::Box;
using testing::Circle;
using testing::NoGravity;
using testing::Static;
using testing::WithMass;
using testing::WithMaterial;

namespace {

engine::Vec2 Momentum(const engine::World& world) {
  engine::Vec2 p;
  for (const engine::BodyId id : world.BodyIds()) {
    p += world.Info(id).mass * world.State(id).velocity;
  }
  return p;
}

// Two touching balls of masses 1 and 3 meeting head on at 4 and −2 m/s.
engine::World HeadOn(double restitution) {
  engine::World world(NoGravity());
  world.CreateBody(WithMaterial(WithMass(Circle({0, 0}, 0.5, {4, 0}), 1), restitution, 0));
  world.CreateBody(WithMaterial(WithMass(Circle({1, 0}, 0.5, {-2, 0}), 3), restitution, 0));
  world.Step();
  return world;
}

}  // namespace

TEST_CASE("head-on collision of masses 1 and 3 follows the collision law", "[response]") {
  // v1' = ((m1 − e·m2)·v1 + (1+e)·m2·v2)/(m1 + m2), v2' likewise (accuracy.md S8).
  SECTION("elastic: -5 and 1 m/s, energy kept") {
    engine::World world = HeadOn(1.0);
    CHECK(world.State({0}).velocity.x == Approx(-5.0).epsilon(1e-12));
    CHECK(world.State({1}).velocity.x == Approx(1.0).epsilon(1e-12));
    CHECK(testing::LinearKineticEnergy(world) == Approx(14.0).epsilon(1e-12));
  }
  SECTION("e = 0.5: -2.75 and 0.25 m/s, loses ½·μ·(1 − e²)·Δv² = 10.125 J") {
    engine::World world = HeadOn(0.5);
    CHECK(world.State({0}).velocity.x == Approx(-2.75).epsilon(1e-12));
    CHECK(world.State({1}).velocity.x == Approx(0.25).epsilon(1e-12));
    CHECK(14.0 - testing::LinearKineticEnergy(world) == Approx(10.125).epsilon(1e-12));
  }
  SECTION("the pair uses the larger restitution") {
    engine::World world(NoGravity());
    world.CreateBody(WithMaterial(WithMass(Circle({0, 0}, 0.5, {4, 0}), 1), 1.0, 0));
    world.CreateBody(WithMaterial(WithMass(Circle({1, 0}, 0.5, {-2, 0}), 3), 0.0, 0));
    world.Step();
    CHECK(world.State({0}).velocity.x == Approx(-5.0).epsilon(1e-12));
  }
}

TEST_CASE("bodies already separating get no impulse, touching at rest neither", "[response]") {
  engine::World world(NoGravity());
  world.CreateBody(Circle({0, 0}, 0.5, {-1, 0}));
  world.CreateBody(Circle({0.9, 0}, 0.5, {1, 0}));  // overlapping but flying apart
  world.CreateBody(Circle({5, 0}, 0.5));
  world.CreateBody(Circle({6, 0}, 0.5));  // touching, both at rest: zero relative velocity
  world.Step();
  CHECK(world.Contacts().size() == 2);
  CHECK(world.State({0}).velocity == engine::Vec2{-1, 0});
  CHECK(world.State({1}).velocity == engine::Vec2{1, 0});
  CHECK(world.State({2}).velocity == engine::Vec2{});
  CHECK(world.State({3}).velocity == engine::Vec2{});
}

TEST_CASE("momentum is conserved in collisions without gravity", "[response]") {
  engine::World world(NoGravity());
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> pos(-4, 4), vel(-3, 3), size(0.3, 0.8), e(0, 1), mu(0, 1);
  for (int i = 0; i < 30; ++i) {
    const engine::Vec2 p{pos(rng), pos(rng)}, v{vel(rng), vel(rng)};
    engine::BodyDef def = i % 2 ? Circle(p, size(rng), v) : Box(p, {size(rng), size(rng)}, v);
    world.CreateBody(WithMaterial(def, e(rng), mu(rng)));
  }
  const engine::Vec2 p0 = Momentum(world);
  const double e0 = testing::LinearKineticEnergy(world);
  int contacts = 0;
  for (int i = 0; i < 600; ++i) {
    world.Step();
    contacts += static_cast<int>(world.Contacts().size());
    const engine::Vec2 p = Momentum(world);
    REQUIRE(p.x == Approx(p0.x).margin(1e-10));
    REQUIRE(p.y == Approx(p0.y).margin(1e-10));
    REQUIRE(testing::LinearKineticEnergy(world) <= e0 * (1 + 1e-12));  // restitution ≤ 1 never adds energy
  }
  CHECK(contacts > 100);  // the bodies really did collide
}

TEST_CASE("sliding friction decelerates at the pair's geometric-mean mu times g", "[response]") {
  engine::WorldDef def;
  def.gravity = {0, -10};
  engine::World world(def);
  world.CreateBody(WithMaterial(Static(Box({0, -0.5}, {100, 1})), 0, 0.8));
  world.CreateBody(WithMaterial(Box({0, 0.5}, {1, 1}, {5, 0}), 0, 0.2));
  const double mu = std::sqrt(0.8 * 0.2);  // 0.4
  for (int n = 1; n <= 60; ++n) {
    world.Step();
    REQUIRE(world.State({1}).velocity.x == Approx(5.0 - mu * 10.0 * n * def.dt).epsilon(1e-12));
  }
  // Stopping distance v²/(2μg) = 3.125 m, within one step's travel (accuracy.md S11).
  for (int n = 0; n < 120; ++n) world.Step();
  CHECK(world.State({1}).velocity.x == 0.0);
  CHECK(world.State({1}).position.x == Approx(25.0 / (2 * mu * 10.0)).margin(5.0 * def.dt));
}

TEST_CASE("a box resting on the floor stays within 1 mm over 10 s", "[response]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Static(Box({0, -0.5}, {20, 1})));
  world.CreateBody(Box({0, 0.5}, {1, 1}));
  world.CreateBody(WithMass(Box({3, 1}, {2, 2}), 50));
  for (int i = 0; i < 600; ++i) {
    world.Step();
    REQUIRE(std::abs(world.State({1}).position.y - 0.5) <= 1e-3);
    REQUIRE(std::abs(world.State({2}).position.y - 1.0) <= 1e-3);
    REQUIRE(world.State({1}).position.x == 0.0);
  }
}

namespace {

// Drops a ball (e = 0.8) from 10 m onto a static floor and returns the ball's mechanical energy
// per kg, ½v² + g·(y − r), in each free flight after a bounce, starting with the drop itself.
std::vector<double> FlightEnergies(double dt, int bounces) {
  const double g = 9.81, r = 0.5;
  engine::WorldDef def;
  def.gravity = {0, -g};
  def.dt = dt;
  def.solver = engine::ContactSolver::kSequentialImpulse;
  engine::World world(def);
  world.CreateBody(Static(Box({0, -0.5}, {4, 1})));
  world.CreateBody(WithMaterial(Circle({0, 10.0 + r}, r), 0.8, 0.3));
  std::vector<double> energies = {g * 10.0};
  bool in_contact = false;
  for (int i = 0; i < 20.0 / dt && static_cast<int>(energies.size()) <= bounces; ++i) {
    world.Step();
    const bool touching = !world.Contacts().empty();
    if (in_contact && !touching) {
      const engine::BodyState& s = world.State({1});
      energies.push_back(0.5 * engine::LengthSquared(s.velocity) + g * (s.position.y - r));
    }
    in_contact = touching;
  }
  return energies;
}

}  // namespace

TEST_CASE("sequential impulse: a ball dropped on the floor keeps e² of its energy per bounce", "[response][sequential_impulse]") {
  // The seed method meets the floor up to one step late: at a depth p ≤ v·dt below the surface,
  // with the speed gained on the way down, and position correction lifts it back for free. So
  // per bounce E'/E − e² ∈ [0, (1 + e²)·p/H] with p/H ≤ √(2g/H)·dt (H = height before bounce);
  // slop can lose a hair of energy, hence a small negative allowance.
  const double e2 = 0.64, g = 9.81, dt = 1.0 / 60.0;
  const std::vector<double> energies = FlightEnergies(dt, 5);
  REQUIRE(energies.size() == 6);
  for (std::size_t n = 1; n < energies.size(); ++n) {
    const double height = energies[n - 1] / g;
    const double ratio = energies[n] / energies[n - 1];
    const double bound = (1 + e2) * std::sqrt(2 * g / height) * dt;
    INFO("bounce " << n << ": kept " << ratio << " of the energy, e² = " << e2 << ", bound " << bound);
    CHECK(ratio - e2 >= -1e-3);
    CHECK(ratio - e2 <= bound);
  }
}

TEST_CASE("sequential impulse: the bounce energy error shrinks in proportion to the step (first order)", "[response][sequential_impulse]") {
  const double e2 = 0.64;
  const double coarse = FlightEnergies(1.0 / 60.0, 1)[1] / (9.81 * 10.0) - e2;
  const double fine = FlightEnergies(1.0 / 240.0, 1)[1] / (9.81 * 10.0) - e2;
  INFO("error at 60 Hz " << coarse << ", at 240 Hz " << fine);
  CHECK(coarse > 0);
  CHECK(coarse / fine == Approx(4.0).epsilon(0.25));
}
