// Moving bodies by hand between steps: the setters, applied forces and torques (for one step),
// impulses (at once), and what static and kinematic bodies ignore; setters wake sleepers.
#include <catch2/catch.hpp>

#include "engine/world.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::ContactSolver;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Floor;
using testing::Static;

// A 1 m square of 2 kg: I = m (w² + h²) / 12 = 1/3 kg·m².
engine::BodyDef UnitBox(Vec2 position) { return testing::WithMass(Box(position, {1, 1}), 2.0); }
constexpr double kUnitBoxInertia = 1.0 / 3.0;

engine::WorldDef Rotating(ContactSolver solver = ContactSolver::kSubstep) {
  engine::WorldDef def = testing::NoGravity();
  def.rotation = true;
  def.solver = solver;
  return def;
}

// How many free steps of the integrator make one world step.
int SubstepsOf(const engine::World& world) {
  return world.Def().solver == ContactSolver::kSubstep ? world.Def().substeps : 1;
}

}  // namespace

TEST_CASE("control: SetLinearVelocity, then a step, gives the semi-implicit Euler step from it",
          "[control]") {
  for (const ContactSolver solver : testing::kBothSolvers) {
    engine::WorldDef def;
    def.solver = solver;
    engine::World world(def);
    const BodyId ball = world.CreateBody(Circle({0, 5}, 0.5));
    world.Step();
    world.SetLinearVelocity(ball, {3, 4});
    CHECK(world.State(ball).velocity == Vec2{3, 4});
    const Vec2 start = world.State(ball).position;
    world.Step();
    // The same arithmetic by hand: each free step v += g h, then x += v h.
    const int n = SubstepsOf(world);
    const double h = def.dt / n;
    Vec2 v{3, 4}, x = start;
    for (int k = 0; k < n; ++k) {
      v = v + def.gravity * h;
      x = x + v * h;
    }
    INFO("solver " << static_cast<int>(solver));
    CHECK(world.State(ball).velocity == v);  // (3, 4 - 9.8/60)
    CHECK(world.State(ball).position == x);
  }
}

TEST_CASE("control: a force for one step changes the velocity by F dt / m, then is gone", "[control]") {
  for (const ContactSolver solver : testing::kBothSolvers) {
    INFO("solver " << static_cast<int>(solver));
    engine::WorldDef def;
    def.solver = solver;
    engine::World world(def);
    const BodyId box = world.CreateBody(UnitBox({0, 5}));
    world.ApplyForceToCenter(box, {10, -4});
    world.Step();
    const double dt = def.dt;
    const Vec2 after_one{10 * dt / 2, (-4 / 2.0 - 9.8) * dt};  // (F/m + g) dt
    CHECK(world.State(box).velocity.x == Approx(after_one.x).epsilon(1e-12));
    CHECK(world.State(box).velocity.y == Approx(after_one.y).epsilon(1e-12));
    world.Step();  // gravity alone now
    CHECK(world.State(box).velocity.x == Approx(after_one.x).epsilon(1e-12));
    CHECK(world.State(box).velocity.y == Approx(after_one.y - 9.8 * dt).epsilon(1e-12));
  }
}

TEST_CASE("control: a force off the centre adds the torque r x F; without rotation it only pushes",
          "[control]") {
  for (const bool rotation : {true, false}) {
    INFO("rotation " << rotation);
    engine::WorldDef def = Rotating();
    def.rotation = rotation;
    engine::World world(def);
    const BodyId box = world.CreateBody(UnitBox({0, 0}));
    world.ApplyForce(box, {0, 6}, {0.5, 0});  // r = (0.5, 0): τ = 0.5 · 6 = 3 N·m
    world.Step();
    const double dt = def.dt;
    CHECK(world.State(box).velocity.x == 0.0);
    CHECK(world.State(box).velocity.y == Approx(6 / 2.0 * dt).epsilon(1e-12));
    CHECK(world.State(box).angular_velocity == Approx(rotation ? 3 * dt / kUnitBoxInertia : 0.0).margin(1e-14));
    world.Step();  // the force and its torque were for one step
    CHECK(world.State(box).velocity.y == Approx(6 / 2.0 * dt).epsilon(1e-12));
    CHECK(world.State(box).angular_velocity == Approx(rotation ? 0.15 : 0.0).epsilon(1e-12));
  }
}

TEST_CASE("control: a torque for one step changes the spin by tau dt / I", "[control]") {
  engine::World world(Rotating());
  const BodyId box = world.CreateBody(UnitBox({0, 0}));
  world.ApplyTorque(box, 2.0);
  world.Step();
  CHECK(world.State(box).angular_velocity == Approx(2.0 / 60 / kUnitBoxInertia).epsilon(1e-12));  // 0.1 rad/s
  CHECK(world.State(box).velocity == Vec2{});
}

TEST_CASE("control: an impulse at a point changes v by J/m and the spin by (r x J)/I at once",
          "[control]") {
  engine::World world(Rotating());
  const BodyId box = world.CreateBody(UnitBox({1, 1}));
  world.ApplyLinearImpulse(box, {1, 2}, {1.5, 1.5});  // r = (0.5, 0.5): r × J = 1 - 0.5 = 0.5
  CHECK(world.State(box).velocity == Vec2{0.5, 1.0});
  CHECK(world.State(box).angular_velocity == Approx(0.5 / kUnitBoxInertia).epsilon(1e-14));  // 1.5
  world.ApplyAngularImpulse(box, 0.3);
  CHECK(world.State(box).angular_velocity == Approx(1.5 + 0.3 / kUnitBoxInertia).epsilon(1e-14));  // 2.4
  world.ApplyLinearImpulseToCenter(box, {-1, 0});
  CHECK(world.State(box).velocity == Vec2{0.0, 1.0});
  CHECK(world.State(box).angular_velocity == Approx(2.4).epsilon(1e-14));
}

TEST_CASE("control: static and kinematic bodies ignore forces, torques and impulses", "[control]") {
  engine::WorldDef def = Rotating();
  def.gravity = {0, -9.8};
  engine::World world(def);
  const BodyId wall = world.CreateBody(Static(Box({5, 0}, {1, 4})));
  const BodyId mover = world.CreateBody(testing::Kinematic(Box({-5, 0}, {1, 1}), {1, 0}));
  for (const BodyId id : {wall, mover}) {
    world.ApplyForce(id, {100, 100}, world.State(id).position + Vec2{0.5, 0.5});
    world.ApplyForceToCenter(id, {100, 0});
    world.ApplyTorque(id, 50);
    world.ApplyLinearImpulse(id, {10, 10}, world.State(id).position + Vec2{0.5, 0});
    world.ApplyLinearImpulseToCenter(id, {10, 0});
    world.ApplyAngularImpulse(id, 5);
  }
  CHECK(world.State(mover).velocity == Vec2{1, 0});
  CHECK(world.State(mover).angular_velocity == 0.0);
  testing::StepTimes(world, 60);
  CHECK(world.State(wall).position == Vec2{5, 0});
  CHECK(world.State(wall).velocity == Vec2{});
  CHECK(world.State(wall).angular_velocity == 0.0);
  CHECK(world.State(mover).velocity == Vec2{1, 0});
  CHECK(world.State(mover).angular_velocity == 0.0);
  CHECK(world.State(mover).position.x == Approx(-4.0).epsilon(1e-12));
  CHECK(world.State(mover).position.y == 0.0);

  // A static body takes placement only; velocity setters leave it at rest.
  world.SetLinearVelocity(wall, {1, 1});
  world.SetAngularVelocity(wall, 1);
  CHECK(world.State(wall).velocity == Vec2{});
  CHECK(world.State(wall).angular_velocity == 0.0);
}

TEST_CASE("control: without rotation a body's spin cannot be set", "[control]") {
  engine::World world(testing::NoGravity());
  const BodyId box = world.CreateBody(UnitBox({0, 0}));
  world.SetAngularVelocity(box, 3.0);
  world.SetAngle(box, 0.25);  // placement is kept as given
  world.Step();
  CHECK(world.State(box).angular_velocity == 0.0);
  CHECK(world.State(box).angle == 0.25);
}

TEST_CASE("control: SetPosition wakes a sleeping body, which falls from its new place", "[control]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId box = world.CreateBody(Box({0, 0.5}, {1, 1}));
  testing::StepTimes(world, 120);
  REQUIRE_FALSE(world.IsAwake(box));
  world.SetPosition(box, {2, 3});
  CHECK(world.IsAwake(box));
  CHECK(world.State(box).position == Vec2{2, 3});
  testing::StepTimes(world, 120);
  CHECK(world.State(box).position.x == Approx(2.0).margin(1e-9));
  CHECK(world.State(box).position.y == Approx(0.5).margin(0.01));
}

TEST_CASE("control: moving a static shelf wakes the sleeping boxes on it, which fall", "[control]") {
  for (const ContactSolver solver : testing::kBothSolvers) {
    INFO("solver " << static_cast<int>(solver));
    engine::WorldDef def;
    def.solver = solver;
    engine::World world(def);
    world.CreateBody(Floor());
    const BodyId shelf = world.CreateBody(Static(Box({0, 2.5}, {4, 1})));  // top at y = 3
    const BodyId box = world.CreateBody(Box({0, 3.5}, {1, 1}));
    testing::StepTimes(world, 120);
    REQUIRE_FALSE(world.IsAwake(box));
    world.SetPosition(shelf, {8, 2.5});  // out from under the box
    CHECK(world.IsAwake(box));
    testing::StepTimes(world, 120);
    CHECK(world.State(box).position.y == Approx(0.5).margin(0.01));
  }
}

TEST_CASE("control: a static body placed onto sleeping boxes wakes them", "[control]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId box = world.CreateBody(Box({0, 0.5}, {1, 1}));
  const BodyId block = world.CreateBody(Static(Box({6, 0.5}, {1, 1})));
  testing::StepTimes(world, 120);
  REQUIRE_FALSE(world.IsAwake(box));
  world.SetPosition(block, {0.6, 0.5});  // overlapping the box by 0.4 m
  CHECK(world.IsAwake(box));
  testing::StepTimes(world, 60);
  CHECK(world.State(box).position.x < -0.39);  // pushed out, to the left
}
