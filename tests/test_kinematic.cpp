// Kinematic bodies: infinite mass that moves at its own velocity. They feel no force, are never
// pushed, push and carry dynamic bodies, and at rest let what lies on them sleep. Each case runs
// with both contact solvers, and with rotation on and off where turning could matter.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "engine/world.h"
#include "game/scene.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::ContactSolver;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Kinematic;
using testing::Static;

struct Setup {
  ContactSolver solver;
  bool rotation;
};

constexpr Setup kSetups[] = {{ContactSolver::kSubstep, false},
                             {ContactSolver::kSubstep, true},
                             {ContactSolver::kSequentialImpulse, false},
                             {ContactSolver::kSequentialImpulse, true}};

std::string Name(const Setup& s) {
  return std::string(s.solver == ContactSolver::kSubstep ? "substep" : "sequential impulse") +
         (s.rotation ? ", rotation" : ", no rotation");
}

engine::WorldDef Def(const Setup& s) {
  engine::WorldDef def;
  def.solver = s.solver;
  def.rotation = s.rotation;
  return def;
}

engine::BodyDef Floor() { return testing::Floor(40); }

}  // namespace

TEST_CASE("kinematic: moves at its velocity exactly, x = x0 + v t, and feels no gravity", "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      engine::BodyDef def = Kinematic(Box({1, 5}, {2, 0.5}), {1.5, -0.5});
      if (setup.rotation) def.angular_velocity = 0.7;
      const BodyId body = world.CreateBody(def);
      CHECK(world.Info(body).inv_mass == 0.0);
      CHECK(world.IsAwake(body));  // it moves
      const int steps = 90;
      testing::StepTimes(world, steps);
      const double t = steps * world.Def().dt;
      const engine::BodyState& s = world.State(body);
      CHECK(s.velocity == Vec2{1.5, -0.5});
      CHECK(s.position.x == Approx(1 + 1.5 * t).epsilon(1e-12));  // 3.25 m after 1.5 s
      CHECK(s.position.y == Approx(5 - 0.5 * t).epsilon(1e-12));  // 4.25 m
      CHECK(s.angle == Approx(setup.rotation ? 0.7 * t : 0.0).margin(1e-12));
    }
  }
}

TEST_CASE("kinematic: a heavy body hitting it bounces off; it goes on at its own velocity",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::WorldDef def = Def(setup);
      def.gravity = {0, 0};
      engine::World world(def);
      const BodyId wall = world.CreateBody(Kinematic(Box({0, 0}, {1, 2}), {1, 0}));
      // 1000 kg hitting 0.3 m off the wall's centre line, so an unbalanced push would turn it.
      const BodyId heavy = world.CreateBody(testing::WithMass(Box({4, 0.3}, {1, 1}, {-5, 0}), 1000.0));
      testing::StepTimes(world, 120);
      const engine::BodyState& w = world.State(wall);
      CHECK(w.velocity == Vec2{1, 0});
      CHECK(w.angular_velocity == 0.0);
      CHECK(w.angle == 0.0);
      CHECK(w.position.x == Approx(2.0).epsilon(1e-12));
      CHECK(w.position.y == 0.0);
      // Restitution 0.2 of the closing speed 6 m/s: it leaves at 1 + 0.2 · 6 = 2.2 m/s.
      CHECK(world.State(heavy).velocity.x == Approx(2.2).margin(0.05));
      CHECK(world.State(heavy).position.x > w.position.x + 0.99);
    }
  }
}

TEST_CASE("kinematic: a moving platform carries a box, which friction brings to its speed",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      const BodyId platform =
          world.CreateBody(testing::WithMaterial(Kinematic(Box({0, 0}, {6, 0.5}), {1, 0}), 0.0, 0.5));
      const BodyId box = world.CreateBody(testing::WithMaterial(Box({0, 0.75}, {1, 1}), 0.0, 0.5));
      testing::StepTimes(world, 60);  // 1 s; friction μ g = 4.9 m/s² needs 0.2 s
      const engine::BodyState& p = world.State(platform);
      const engine::BodyState& b = world.State(box);
      CHECK(p.position.x == Approx(1.0).epsilon(1e-12));
      CHECK(p.position.y == 0.0);
      CHECK(p.velocity == Vec2{1, 0});
      CHECK(b.velocity.x == Approx(1.0).margin(1e-3));
      CHECK(std::abs(b.velocity.y) < 1e-3);
      CHECK(b.position.y == Approx(0.75).margin(0.01));
      // The box slid back on the platform by v² / (2 μ g) = 0.102 m while it caught up.
      CHECK(p.position.x - b.position.x == Approx(1.0 / (2 * 0.5 * 9.8)).margin(0.02));
      CHECK(b.angle == Approx(0.0).margin(1e-3));
    }
  }
}

TEST_CASE("kinematic: a lift moving up or down and sideways carries a stack of three boxes",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    for (const double vy : {1.0, -1.0}) {
      DYNAMIC_SECTION(Name(setup) << ", vy " << vy) {
        engine::World world(Def(setup));
        const BodyId lift = world.CreateBody(Kinematic(Box({0, 0}, {4, 0.5}), {0.5, vy}));
        BodyId boxes[3];
        for (int i = 0; i < 3; ++i) boxes[i] = world.CreateBody(Box({0, 0.75 + i}, {1, 1}));
        testing::StepTimes(world, 120);
        CHECK(world.State(lift).position.y == Approx(2 * vy).epsilon(1e-12));
        double below = world.State(lift).position.y + 0.25;  // the lift's top
        for (const BodyId box : boxes) {
          const engine::BodyState& s = world.State(box);
          // Each box on the one below (within the slop: 5 mm with sequential impulses), at the
          // lift's velocity, square.
          CHECK(s.position.y - 0.5 - below == Approx(0.0).margin(0.006));
          CHECK(s.velocity.x == Approx(0.5).margin(1e-3));
          CHECK(s.velocity.y == Approx(vy).margin(0.015));
          CHECK(s.angle == Approx(0.0).margin(1e-4));  // 1.6e-5 rad at most, substep with rotation
          below = s.position.y + 0.5;
        }
      }
    }
  }
}

TEST_CASE("kinematic: a sweeping wall pushes boxes ahead of it along the floor", "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      world.CreateBody(Floor());
      // 1 m tall, its bottom 2 cm over the floor, sweeping right at 1 m/s.
      const BodyId wall = world.CreateBody(Kinematic(Box({-3, 0.52}, {0.2, 1}), {1, 0}));
      const BodyId near = world.CreateBody(Box({0, 0.25}, {0.5, 0.5}));
      const BodyId far = world.CreateBody(Box({1, 0.25}, {0.5, 0.5}));
      testing::StepTimes(world, 360);  // 6 s: the wall's face goes from -2.9 to 3.1 m
      REQUIRE_FALSE(world.Fault());
      const engine::BodyState& w = world.State(wall);
      CHECK(w.position.x == Approx(3.0).epsilon(1e-12));
      CHECK(w.velocity == Vec2{1, 0});
      // Friction slows the boxes, so the wall keeps them against its face: the near one touches
      // it, the far one touches the near one, both at the wall's speed.
      const engine::BodyState& n = world.State(near);
      const engine::BodyState& f = world.State(far);
      CHECK(n.position.x == Approx(3.1 + 0.25).margin(0.02));
      CHECK(f.position.x == Approx(3.1 + 0.75).margin(0.04));
      CHECK(n.velocity.x == Approx(1.0).margin(0.05));
      CHECK(f.velocity.x == Approx(1.0).margin(0.05));
      CHECK(n.position.y == Approx(0.25).margin(0.01));
      CHECK(f.position.y == Approx(0.25).margin(0.01));
    }
  }
}

TEST_CASE("kinematic: one at rest lets a box on it sleep; set moving, it wakes the box and carries it",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      const BodyId platform = world.CreateBody(Kinematic(Box({0, 0}, {6, 0.5})));
      const BodyId box = world.CreateBody(Box({0, 0.75}, {1, 1}));
      CHECK_FALSE(world.IsAwake(platform));  // at rest it is not even integrated
      testing::StepTimes(world, 120);  // 2 s; sleep comes after 0.5 s of rest
      CHECK_FALSE(world.IsAwake(box));
      CHECK(world.State(box).position.y == Approx(0.75).margin(0.01));
      CHECK(world.State(platform).position == Vec2{0, 0});

      world.SetLinearVelocity(platform, {1, 0});
      CHECK(world.IsAwake(platform));
      world.Step();
      CHECK(world.IsAwake(box));
      testing::StepTimes(world, 59);
      CHECK(world.State(box).velocity.x == Approx(1.0).margin(1e-3));
      world.SetLinearVelocity(platform, {0, 0});
      CHECK_FALSE(world.IsAwake(platform));
      testing::StepTimes(world, 120);
      CHECK_FALSE(world.IsAwake(box));
    }
  }
}

TEST_CASE("kinematic: a box on a platform slower than the sleep speed goes with it, awake",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      const BodyId platform = world.CreateBody(Kinematic(Box({0, 0}, {6, 0.5}), {0.03, 0}));  // < 0.05 m/s
      const BodyId box = world.CreateBody(Box({0, 0.75}, {1, 1}));
      for (int step = 0; step < 180; ++step) {  // 3 s: six times the time to sleep
        world.Step();
        INFO("step " << step);
        REQUIRE(world.IsAwake(box));
      }
      CHECK(world.State(box).velocity.x == Approx(0.03).margin(1e-6));
      // Only the slip of the start, at most v² / (2 μ g) = 0.15 mm (μ = 0.3; less in steps: the
      // sequential-impulse solver gets there within the first); a box put to sleep would stop
      // and slip again every 0.5 s (0.58 mm in all).
      const double behind = world.State(platform).position.x - world.State(box).position.x;
      CHECK(behind >= 0.0);
      CHECK(behind <= 0.03 * 0.03 / (2 * 0.3 * 9.8));
    }
  }
}

TEST_CASE("kinematic: two kinematic bodies, or one and a static body, pass through each other",
          "[kinematic]") {
  for (const Setup& setup : kSetups) {
    DYNAMIC_SECTION(Name(setup)) {
      engine::World world(Def(setup));
      world.CreateBody(Floor());
      // Both sunk 0.1 m into the floor, crossing each other at t = 1 s.
      const BodyId a = world.CreateBody(Kinematic(Box({-1, 0.4}, {1, 1}), {1, 0}));
      const BodyId b = world.CreateBody(Kinematic(Circle({1, 0.4}, 0.5), {-1, 0}));
      testing::StepTimes(world, 120);
      REQUIRE_FALSE(world.Fault());
      CHECK(world.State(a).position.x == Approx(1.0).epsilon(1e-12));
      CHECK(world.State(b).position.x == Approx(-1.0).epsilon(1e-12));
      CHECK(world.State(a).position.y == 0.4);
      CHECK(world.State(a).velocity == Vec2{1, 0});
      CHECK(world.State(b).velocity == Vec2{-1, 0});
      CHECK(world.Contacts().empty());  // infinite mass against infinite mass: nothing to solve
    }
  }
}

TEST_CASE("kinematic: a ball on a spring from a moving kinematic body is towed along", "[kinematic]") {
  engine::World world(engine::WorldDef{});
  const BodyId hook = world.CreateBody(Kinematic(Box({0, 5}, {0.5, 0.5}), {1, 0}));
  const BodyId ball = world.CreateBody(Circle({0, 4}, 0.25));
  world.AddSpring(testing::Spring(ball, hook, 1.0, 100.0, 5.0));
  testing::StepTimes(world, 300);  // 5 s
  CHECK(world.State(hook).velocity == Vec2{1, 0});  // the spring does not hold it back
  CHECK(world.State(hook).position.x == Approx(5.0).epsilon(1e-12));
  CHECK(world.State(hook).position.y == 5.0);
  // The ball came 5 m along, swinging under the hook as a pendulum (the spring's damping acts
  // along it only): the jerk of the start gives it an amplitude of 1 m/s · √(L/g) = 0.32 m.
  const Vec2 below = world.State(hook).position - world.State(ball).position;
  CHECK(std::abs(below.x) < 0.4);
  CHECK(engine::Length(below) == Approx(1.0).margin(0.1));
}

TEST_CASE("kinematic: assets/scenes/kinematic_platform.json carries, lifts and sweeps for 10 s",
          "[kinematic][scene]") {
  const game::Expected<game::Scene> loaded =
      game::LoadScene(std::string(BALLBOX_ASSETS) + "/scenes/kinematic_platform.json");
  if (!loaded.HasValue()) FAIL(loaded.Error().message);
  const game::Scene& scene = loaded.Value();
  auto id = [&](const std::string& name) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].id == name) return BodyId{static_cast<engine::BodyIndex>(i)};
    }
    FAIL("no body " << name);
    return BodyId{};
  };
  engine::World world = game::BuildWorld(scene);
  testing::StepTimes(world, 600);
  REQUIRE_FALSE(world.Fault());
  // The carrier (0.8 m/s from x = -6) has its riders on it still, at its speed.
  CHECK(world.State(id("carrier")).position.x == Approx(2.0).epsilon(1e-12));
  for (const char* rider : {"rider_low", "rider_high"}) {
    CHECK(world.State(id(rider)).velocity.x == Approx(0.8).margin(1e-3));
    CHECK(world.State(id(rider)).position.x == Approx(2.0 - 0.54).margin(0.01));
  }
  // The lift has raised its box 3.5 m.
  CHECK(world.State(id("lifted")).position.y == Approx(0.7 + 3.5).margin(0.01));
  // The sweeper's face is at -5.35; the crates ride ahead of it, face to face.
  CHECK(world.State(id("crate_a")).position.x == Approx(-5.35 + 0.4).margin(0.01));
  CHECK(world.State(id("crate_b")).position.x == Approx(-5.35 + 1.2).margin(0.02));
  CHECK(world.State(id("paddle")).angle == Approx(-12.0).epsilon(1e-12));
}
