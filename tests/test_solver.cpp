// The soft-step solver with its impact pass: true restitution, Newton's cradle, friction, sleep.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "bench/work_precision_scenarios.h"
#include "engine/world.h"
#include "world_builders.h"

using testing::Box;
using testing::Circle;
using testing::Static;
using testing::WithMass;
using testing::WithMaterial;

namespace wp = work_precision;

namespace {

constexpr engine::Integrator kIntegrators[] = {
    engine::Integrator::kSemiImplicitEuler, engine::Integrator::kExplicitEuler, engine::Integrator::kVelocityVerlet,
    engine::Integrator::kMidpoint, engine::Integrator::kRungeKutta4};

// Apex heights (above the contact height) of a ball of restitution e dropped from h0 onto a
// static floor, one per flight after each bounce, sampled at the end of every step.
std::vector<double> BounceApexes(double e, double h0, int bounces, engine::WorldDef def) {
  const double r = 0.5;
  engine::World world(def);
  world.CreateBody(Static(Box({0, -0.5}, {4, 1})));
  world.CreateBody(WithMaterial(Circle({0, h0 + r}, r), e, 0.3));
  std::vector<double> apexes;
  double previous_vy = 0, highest = 0;
  bool flying_up = false;
  for (int i = 0; i < 120 / def.dt && static_cast<int>(apexes.size()) < bounces; ++i) {
    world.Step();
    const engine::BodyState& s = world.State({1});
    if (previous_vy <= 0 && s.velocity.y > 0) flying_up = true, highest = 0;  // a bounce
    highest = std::max(highest, s.position.y - r);
    if (flying_up && s.velocity.y <= 0) {
      apexes.push_back(highest);
      flying_up = false;
    }
    previous_vy = s.velocity.y;
  }
  return apexes;
}

}  // namespace

TEST_CASE("a ball dropped from 10 m bounces to e^2n·h within 0.5% for five bounces", "[solver]") {
  engine::WorldDef def;
  def.gravity = {0, -9.81};
  // e = 0.5 bounces only three times above the 1 m/s restitution threshold: the fourth impact
  // comes at √(2g·e⁶·h) = 0.87 m/s, and the ball then rests (the next test).
  for (auto [e, bounces] : {std::pair{0.5, 3}, std::pair{0.8, 5}, std::pair{0.95, 5}}) {
    const std::vector<double> apexes = BounceApexes(e, 10.0, bounces, def);
    REQUIRE(static_cast<int>(apexes.size()) == bounces);
    for (std::size_t n = 0; n < apexes.size(); ++n) {
      const double expected = std::pow(e, 2.0 * (n + 1)) * 10.0;
      INFO("e = " << e << ", bounce " << n + 1 << ": apex " << apexes[n] << " m, e^2n·h = " << expected);
      CHECK(std::abs(apexes[n] - expected) / expected < 0.005);
      // Never gains energy. Semi-implicit Euler keeps H = ½v² + g·y − ½·g·h·v, so a sampled
      // height can exceed H/g by at most g·h²/8 (h the substep), never more.
      const double h = def.dt / def.substeps;
      CHECK(apexes[n] <= expected + 9.81 * h * h / 8);
    }
  }
}

TEST_CASE("S7 at 60 Hz: every integrator bounces to e^2n·h0 within 0.5% and never higher", "[solver][integrators]") {
  // accuracy.md S7: h0 = 1 m, e = 0.8. The impact pass places each bounce on the integrator's own
  // free flight, so no method's bounce may gain what another's would lose.
  const double e = 0.8, h0 = 1.0;
  for (engine::Integrator integrator : kIntegrators) {
    for (int substeps : {1, 4}) {
      engine::WorldDef def;
      def.gravity = {0, -9.81};
      def.integrator = integrator;
      def.substeps = substeps;
      const std::vector<double> apexes = BounceApexes(e, h0, 5, def);
      REQUIRE(apexes.size() == 5);
      const double h = def.dt / substeps;
      for (std::size_t n = 0; n < apexes.size(); ++n) {
        const double expected = std::pow(e, 2.0 * (n + 1)) * h0;
        INFO("integrator " << static_cast<int>(integrator) << ", " << substeps << " substeps, bounce " << n + 1
                           << ": apex " << apexes[n] << " m, e^2n·h0 = " << expected);
        CHECK(std::abs(apexes[n] - expected) / expected < 0.005);
        // Every method's step points lie on a parabola of the right energy (the Euler pair's up to
        // g·h²/8 above the true apex); a sampled apex can only fall short of it.
        CHECK(apexes[n] <= expected + 9.81 * h * h / 8);
      }
    }
  }
}

TEST_CASE("S7: Verlet, midpoint and RK4 bounce exactly (time of impact), at any step", "[solver][integrators]") {
  // They integrate constant acceleration exactly, and the impact pass reflects that parabola
  // at its root: the whole trajectory is the closed form's to rounding.
  const wp::Scenario s7 = wp::Scenarios().back();
  REQUIRE(s7.id == "S7");
  for (engine::Integrator integrator :
       {engine::Integrator::kVelocityVerlet, engine::Integrator::kMidpoint, engine::Integrator::kRungeKutta4}) {
    for (int rate : {30, 60, 240, 960}) {
      INFO("integrator " << static_cast<int>(integrator) << ", h = 1/" << rate);
      CHECK(wp::Measure(s7, integrator, rate).position_error < 1e-9);
    }
  }
}

TEST_CASE("S7: the Euler pair's trajectory converges at first order, never below the floor", "[solver][integrators]") {
  // Their step points follow the exact flight shifted by h/2 in time, so the largest position
  // error is about the impact speed times h/2, at every h. Bounces used to be triggered when free
  // flight would end within the slop (5 mm) of the floor, and then mirrored to e·s below it: an
  // error of up to (1 + e)·slop ≈ 9 mm that did not shrink with h.
  const wp::Scenario s7 = wp::Scenarios().back();
  REQUIRE(s7.id == "S7");
  const double impact_speed = std::sqrt(2 * wp::kG * wp::kBounceHeight);
  for (engine::Integrator integrator : {engine::Integrator::kSemiImplicitEuler, engine::Integrator::kExplicitEuler}) {
    for (int rate : {60, 120, 240, 480, 960, 1920, 3840}) {
      const wp::Figures f = wp::Measure(s7, integrator, rate);
      const double shift = 0.5 * impact_speed / rate;
      INFO("integrator " << static_cast<int>(integrator) << ", h = 1/" << rate << ": error " << f.position_error
                         << " m, speed·h/2 = " << shift << " m");
      CHECK(f.position_error >= 0.9 * shift);
      // Semi-implicit Euler within 1 %; explicit Euler up to 12 % more at some h (1/480 s), where the
      // contact solver's speculative bound (which assumes positions move with the kicked velocity)
      // stops the ball a little early on the step before an impact.
      CHECK(f.position_error <= (integrator == engine::Integrator::kSemiImplicitEuler ? 1.01 : 1.2) * shift);
    }
    engine::World world = s7.build(integrator, 1.0 / 3840);
    double lowest = 1.0;
    for (int step = 0; step < 3 * 3840; ++step) {
      world.Step();
      lowest = std::min(lowest, s7.observed(world).y);
    }
    INFO("integrator " << static_cast<int>(integrator) << ": lowest contact height " << lowest << " m");
    CHECK(lowest >= 0.0);
  }
}

TEST_CASE("a bouncing ball comes to rest and stays quiet (restitution threshold)", "[solver]") {
  engine::WorldDef def;
  def.sleeping = false;
  engine::World world(def);
  world.CreateBody(Static(Box({0, -0.5}, {4, 1})));
  world.CreateBody(WithMaterial(Circle({0, 1.5}, 0.5), 0.8, 0.3));
  for (int i = 0; i < 600; ++i) world.Step();
  // e = 0.8 from 1 m: impacts slower than 1 m/s stop bouncing; long before 10 s it rests.
  for (int i = 0; i < 60; ++i) {
    world.Step();
    REQUIRE(std::abs(world.State({1}).velocity.y) < 1e-6);
    // A soft contact settles a hair past the slop it leaves alone (0.07 mm here).
    REQUIRE(std::abs(world.State({1}).position.y - 0.5) < def.linear_slop + 5e-4);
  }
}

TEST_CASE("Newton's cradle: the last ball leaves at the striker's speed", "[solver]") {
  for (double gap : {0.0, 1e-3}) {
    engine::WorldDef def;
    def.gravity = {0, 0};
    engine::World world(def);
    const double v0 = 3.0;
    world.CreateBody(WithMaterial(Circle({-3, 0}, 0.5, {v0, 0}), 1.0, 0.0));
    for (int i = 0; i < 5; ++i) world.CreateBody(WithMaterial(Circle({i * (1.0 + gap), 0}, 0.5), 1.0, 0.0));
    double momentum_before = v0;
    for (int i = 0; i < 120; ++i) world.Step();
    INFO("gap " << gap);
    CHECK(world.State({5}).velocity.x == Approx(v0).epsilon(0.01));
    double momentum = 0, energy = 0;
    for (engine::BodyId id{0}; id.index < 6; ++id.index) {
      if (id.index < 5) CHECK(std::abs(world.State(id).velocity.x) < 0.01 * v0);
      CHECK(world.State(id).velocity.y == 0.0);
      momentum += world.Info(id).mass * world.State(id).velocity.x;
      energy += 0.5 * world.Info(id).mass * world.State(id).velocity.x * world.State(id).velocity.x;
    }
    const double mass = world.Info({0}).mass;
    CHECK(momentum == Approx(mass * momentum_before).epsilon(1e-12));
    CHECK(energy == Approx(0.5 * mass * v0 * v0).epsilon(0.01));
  }
}

TEST_CASE("soft step: head-on collision of masses 1 and 3 follows the collision law", "[solver]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(WithMaterial(WithMass(Circle({0, 0}, 0.5, {4, 0}), 1), 1.0, 0));
  world.CreateBody(WithMaterial(WithMass(Circle({1, 0}, 0.5, {-2, 0}), 3), 1.0, 0));
  world.Step();
  CHECK(world.State({0}).velocity.x == Approx(-5.0).epsilon(1e-12));
  CHECK(world.State({1}).velocity.x == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("a sliding box stops after v²/(2μg) within v·dt, then stays put", "[solver][friction]") {
  for (auto solver : {engine::ContactSolver::kSubstep, engine::ContactSolver::kSequentialImpulse}) {
    engine::WorldDef def;
    def.gravity = {0, -9.81};
    def.solver = solver;
    engine::World world(def);
    world.CreateBody(WithMaterial(Static(Box({0, -0.5}, {100, 1})), 0, 0.5));
    const double v0 = 10, mu = 0.5;
    world.CreateBody(WithMaterial(Box({0, 0.5}, {1, 1}, {v0, 0}), 0, 0.5));
    for (int i = 0; i < 180; ++i) world.Step();
    const double stop = world.State({1}).position.x;
    INFO("solver " << static_cast<int>(solver) << ": stopped at " << stop << " m, v²/(2μg) = "
                   << v0 * v0 / (2 * mu * 9.81));
    CHECK(std::abs(stop - v0 * v0 / (2 * mu * 9.81)) <= v0 * def.dt);
    for (int i = 0; i < 120; ++i) world.Step();  // 2 s more: no creep
    CHECK(std::abs(world.State({1}).position.x - stop) <= 1e-6);
    CHECK(world.State({1}).velocity.x == 0.0);
  }
}

TEST_CASE("a box pushed sideways with less than μmg does not creep", "[solver][friction]") {
  // A steady sideways push of 0.9·μ·m·g, as gravity tilted so: tan θ = 0.9·μ < μ (S10, static).
  // Every integrator: one that moves a held body by its free drift would creep 22 mm in 2 s.
  const double mu = 0.6, g = 9.81;
  engine::WorldDef def;
  def.gravity = {0.9 * mu * g, -g};
  for (const engine::Integrator integrator : kIntegrators) {
    for (const engine::ContactSolver solver : {engine::ContactSolver::kSubstep, engine::ContactSolver::kSequentialImpulse}) {
      engine::WorldDef held = def;
      held.integrator = integrator;
      held.solver = solver;
      engine::World world(held);
      world.CreateBody(WithMaterial(Static(Box({0, -0.5}, {20, 1})), 0, mu));
      world.CreateBody(WithMaterial(Box({0, 0.5}, {1, 1}), 0, mu));
      for (int i = 0; i < 120; ++i) world.Step();
      INFO("integrator " << static_cast<int>(integrator) << ", solver " << static_cast<int>(solver));
      CHECK(std::abs(world.State({1}).position.x) <= 1e-9);
    }
  }

  // The same push a little over μmg slides, at (1.1 − 1)·μ·g.
  engine::WorldDef slipping = def;
  slipping.gravity = {1.1 * mu * g, -g};
  engine::World sliding(slipping);
  sliding.CreateBody(WithMaterial(Static(Box({0, -0.5}, {200, 1})), 0, mu));
  sliding.CreateBody(WithMaterial(Box({0, 0.5}, {1, 1}), 0, mu));
  for (int i = 0; i < 60; ++i) sliding.Step();
  CHECK(sliding.State({1}).velocity.x == Approx(0.1 * mu * g * 1.0).epsilon(1e-9));
}

TEST_CASE("a box resting on the floor stays on it with every integrator, not hovering", "[solver][integrators]") {
  // Free drift moves a body by v₀·h + ½·a·h² (Verlet, midpoint, RK4); the contact cancels the
  // gravity kick, so a body moved by its drift and not by its velocity would rise ½·g·h² a step
  // and hover 1.4 mm over the floor, then fall back at every step.
  for (const engine::Integrator integrator : kIntegrators) {
    engine::WorldDef def;
    def.integrator = integrator;
    def.sleeping = false;
    engine::World world(def);
    world.CreateBody(Static(Box({0, -0.5}, {20, 1})));
    world.CreateBody(Box({0, 0.5}, {1, 1}));
    double highest = 0.5, lowest = 0.5, fastest = 0;
    for (int i = 0; i < 120; ++i) {
      world.Step();
      highest = std::max(highest, world.State({1}).position.y);
      lowest = std::min(lowest, world.State({1}).position.y);
      fastest = std::max(fastest, engine::Length(world.State({1}).velocity));
    }
    INFO("integrator " << static_cast<int>(integrator) << ": y in [" << lowest << ", " << highest
                       << "], fastest " << fastest << " m/s");
    CHECK(highest - 0.5 <= 1e-9);
    CHECK(0.5 - lowest <= 1e-9);
    CHECK(fastest <= 1e-9);
  }
}

TEST_CASE("resting bodies fall asleep after half a second and stop costing work", "[solver][sleep]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Static(Box({0, -0.5}, {20, 1})));
  for (int i = 0; i < 3; ++i) world.CreateBody(Box({0, 0.5 + i}, {1, 1}));
  int first_asleep = -1;
  for (int i = 1; i <= 60 && first_asleep < 0; ++i) {
    world.Step();
    if (!world.IsAwake({1})) first_asleep = i;
  }
  // Resting from the start, they sleep once 0.5 s (30 steps) of rest have been counted.
  CHECK(first_asleep == 30);
  for (engine::BodyId id{1}; id.index < 4; ++id.index) CHECK_FALSE(world.IsAwake(id));
  world.Step();
  CHECK(world.Contacts().empty());  // nothing left to collide or solve
  for (engine::BodyId id{1}; id.index < 4; ++id.index) CHECK(world.State(id).position.y == 0.5 + (id.index - 1));
}

TEST_CASE("a sleeping stack wakes when something lands on it, and a click wakes a body", "[solver][sleep]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Static(Box({0, -0.5}, {20, 1})));
  for (int i = 0; i < 3; ++i) world.CreateBody(Box({0, 0.5 + i}, {1, 1}));
  world.CreateBody(Box({8, 0.5}, {1, 1}));  // a separate island
  for (int i = 0; i < 40; ++i) world.Step();
  REQUIRE_FALSE(world.IsAwake({1}));
  const engine::BodyId ball = world.CreateBody(Circle({0, 6}, 0.5));
  bool woke = false;
  for (int i = 0; i < 90 && !woke; ++i) {
    world.Step();
    woke = world.IsAwake({1}) && world.IsAwake({2}) && world.IsAwake({3});
  }
  CHECK(woke);                      // the whole island, down to the bottom box
  CHECK_FALSE(world.IsAwake({4}));    // but not the box standing apart
  CHECK(world.State(ball).position.y > 3.0);  // the ball rests on the stack, not in it

  world.ApplyLinearImpulseToCenter({4}, {1, 0});
  CHECK(world.IsAwake({4}));
  world.Step();
  CHECK(world.State({4}).position.x > 8.0);
}

TEST_CASE("with sleeping off, nothing sleeps", "[solver][sleep]") {
  engine::WorldDef def;
  def.sleeping = false;
  engine::World world(def);
  world.CreateBody(Static(Box({0, -0.5}, {20, 1})));
  world.CreateBody(Box({0, 0.5}, {1, 1}));
  for (int i = 0; i < 120; ++i) world.Step();
  CHECK(world.IsAwake({1}));
  CHECK(world.Contacts().size() == 1);
}
