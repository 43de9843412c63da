// Bodies over their life: ids and their generations, destroying (what a body takes with it:
// contacts, warm starts, springs, the support of a stack), enabling and disabling, user data.
#include <catch2/catch.hpp>

#include <csignal>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/world.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Floor;
using testing::Static;

constexpr double kG = 9.8;


bool SameState(const engine::BodyState& a, const engine::BodyState& b) {
  return a.position == b.position && a.velocity == b.velocity && a.angle == b.angle &&
         a.angular_velocity == b.angular_velocity;
}

// Steps until every listed body sleeps (at most `max_steps`), and a few more (a sleeping pair
// drops out of the contacts then); true if they all slept.
bool StepUntilAsleep(engine::World& world, std::initializer_list<BodyId> ids, int max_steps = 600) {
  for (int step = 0; step < max_steps; ++step) {
    world.Step();
    bool all = true;
    for (const BodyId id : ids) all = all && !world.IsAwake(id);
    if (!all) continue;
    testing::StepTimes(world, 5);
    return true;
  }
  return false;
}

}  // namespace

TEST_CASE("ids: a destroyed body's id goes stale; its slot is reused with a new generation",
          "[bodies][ids]") {
  engine::World world(engine::WorldDef{});
  const BodyId a = world.CreateBody(Circle({0, 5}, 0.5));
  const BodyId b = world.CreateBody(Circle({2, 5}, 0.5));
  const BodyId c = world.CreateBody(Circle({4, 5}, 0.5));
  CHECK(a == BodyId{0, 0});
  CHECK(b == BodyId{1, 0});
  CHECK(c == BodyId{2, 0});
  CHECK(world.IsValid(b));

  world.DestroyBody(b);
  CHECK_FALSE(world.IsValid(b));
  CHECK(world.IsValid(a));
  CHECK(world.IsValid(c));
  CHECK_FALSE(world.IsValid(BodyId{7, 0}));  // never made

  const BodyId d = world.CreateBody(Box({-3, 5}, {1, 1}));
  CHECK(d.index == 1);        // the freed slot
  CHECK(d.generation == 1);   // one body destroyed there before
  CHECK(world.IsValid(d));
  CHECK_FALSE(world.IsValid(b));  // the old id names the slot, not the new body
  CHECK(world.IdAt(1) == d);
  CHECK(world.State(d).position == Vec2{-3, 5});

  world.DestroyBody(d);
  const BodyId e = world.CreateBody(Circle({0, 9}, 0.5));
  CHECK(e == BodyId{1, 2});
  CHECK_FALSE(world.IsValid(d));
  CHECK_FALSE(world.IsValid(b));
}

TEST_CASE("ids: BodyIds, BodyCount and the state hash skip destroyed bodies", "[bodies][ids]") {
  // The world with a body destroyed hashes like a world that never had it: the hash walks the
  // live bodies in slot order.
  engine::World world(testing::NoGravity());
  const BodyId a = world.CreateBody(Circle({0, 0}, 0.5, {1, 0}));
  const BodyId b = world.CreateBody(Circle({0, 3}, 0.5, {0, 1}));
  const BodyId c = world.CreateBody(Box({0, 6}, {1, 1}, {-1, 0}));
  engine::World without_b(testing::NoGravity());
  without_b.CreateBody(Circle({0, 0}, 0.5, {1, 0}));
  without_b.CreateBody(Box({0, 6}, {1, 1}, {-1, 0}));

  const std::uint64_t with_b = world.StateHash();
  world.DestroyBody(b);
  CHECK(world.BodyCount() == 2);
  REQUIRE(world.BodyIds().size() == 2);
  CHECK(world.BodyIds()[0] == a);
  CHECK(world.BodyIds()[1] == c);
  CHECK(world.StateHash() != with_b);
  CHECK(world.StateHash() == without_b.StateHash());
  testing::StepTimes(world, 30);
  testing::StepTimes(without_b, 30);
  CHECK(world.StateHash() == without_b.StateHash());

  // A body in the freed slot comes back in slot order: between a and c.
  const BodyId d = world.CreateBody(Circle({5, 5}, 0.25));
  REQUIRE(world.BodyIds().size() == 3);
  CHECK(world.BodyIds()[1] == d);
}

TEST_CASE("destroy: the body under a sleeping stack goes and the stack wakes and falls",
          "[bodies][destroy]") {
  for (const engine::ContactSolver solver : testing::kBothSolvers) {
    DYNAMIC_SECTION("solver " << static_cast<int>(solver)) {
      engine::WorldDef def;
      def.solver = solver;
      engine::World world(def);
      world.CreateBody(Floor());
      const BodyId bottom = world.CreateBody(Box({0, 0.5}, {1, 1}));
      const BodyId middle = world.CreateBody(Box({0, 1.5}, {1, 1}));
      const BodyId top = world.CreateBody(Box({0, 2.5}, {1, 1}));
      REQUIRE(StepUntilAsleep(world, {bottom, middle, top}));
      const double middle_y = world.State(middle).position.y;
      CHECK(middle_y == Approx(1.5).margin(0.01));

      world.DestroyBody(bottom);
      CHECK(world.IsAwake(middle));
      CHECK(world.IsAwake(top));
      testing::StepTimes(world, 120);  // 2 s: a 1 m fall takes 0.45 s
      // Each box has dropped by the height of the one taken away.
      CHECK(world.State(middle).position.y == Approx(0.5).margin(0.01));
      CHECK(world.State(top).position.y == Approx(1.5).margin(0.02));
    }
  }
}

TEST_CASE("destroy: a static shelf under sleeping boxes goes and they fall", "[bodies][destroy]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(Floor());
  const BodyId shelf = world.CreateBody(Static(Box({0, 2.5}, {4, 1})));  // top at y = 3
  const BodyId box = world.CreateBody(Box({0, 3.5}, {1, 1}));
  REQUIRE(StepUntilAsleep(world, {box}));
  world.DestroyBody(shelf);
  CHECK(world.IsAwake(box));
  testing::StepTimes(world, 120);
  CHECK(world.State(box).position.y == Approx(0.5).margin(0.01));  // on the floor, 3 m lower
}

TEST_CASE("destroy: a body in the freed slot falls exactly as in a fresh world (no warm start leaks)",
          "[bodies][destroy]") {
  engine::WorldDef def;
  def.sleeping = false;  // the resting ball keeps its contact (and its impulses) every step
  SECTION("in free fall: y0 + g h^2 n(n+1)/2, semi-implicit Euler's closed form") {
    engine::World world(def);
    world.CreateBody(Floor());
    const BodyId old = world.CreateBody(Circle({0, 0.5}, 0.5));
    testing::StepTimes(world, 60);
    world.DestroyBody(old);
    const BodyId ball = world.CreateBody(Circle({1, 10}, 0.5));
    REQUIRE(ball.index == old.index);
    engine::World fresh(def);
    fresh.CreateBody(Floor());
    const BodyId fresh_ball = fresh.CreateBody(Circle({1, 10}, 0.5));
    const int steps = 60;
    testing::StepTimes(world, steps);
    testing::StepTimes(fresh, steps);
    CHECK(SameState(world.State(ball), fresh.State(fresh_ball)));
    const int substeps = world.Def().substeps;  // 4: the substep solver moves in quarter steps
    const auto fall = testing::SemiImplicitFall(10, 0, -kG, def.dt / substeps, steps * substeps);
    CHECK(world.State(ball).position.y == Approx(fall.position).epsilon(1e-12));
    CHECK(world.State(ball).velocity.y == Approx(fall.velocity).epsilon(1e-12));
    CHECK(world.State(ball).position.x == 1.0);
  }
  SECTION("a new stack where the old one stood: the same slots, contacts and features") {
    // A lone contact would hide a leak (the solve takes back a wrong warm start exactly); two
    // boxes on each other, solved by passes, keep part of it: with the narrow phase's contacts
    // of the destroyed boxes left in place, the new top box ends 4e-16 m lower after one step.
    for (const bool rotation : {false, true}) {
      for (const engine::ContactSolver solver : testing::kBothSolvers) {
        def.solver = solver;
        def.rotation = rotation;
        engine::World world(def);
        world.CreateBody(Floor());
        const BodyId old_bottom = world.CreateBody(testing::WithMass(Box({0, 0.5}, {1, 1}), 50.0));
        const BodyId old_top = world.CreateBody(testing::WithMass(Box({0, 1.5}, {1, 1}), 50.0));
        testing::StepTimes(world, 60);
        world.DestroyBody(old_top);
        world.DestroyBody(old_bottom);
        const BodyId bottom = world.CreateBody(Box({0, 0.5}, {1, 1}));  // the last freed slot first
        const BodyId top = world.CreateBody(Box({0, 1.5}, {1, 1}));
        REQUIRE(bottom.index == old_bottom.index);
        REQUIRE(top.index == old_top.index);
        engine::World fresh(def);
        fresh.CreateBody(Floor());
        const BodyId fresh_bottom = fresh.CreateBody(Box({0, 0.5}, {1, 1}));
        const BodyId fresh_top = fresh.CreateBody(Box({0, 1.5}, {1, 1}));
        for (int step = 0; step < 30; ++step) {
          world.Step();
          fresh.Step();
          INFO("solver " << static_cast<int>(solver) << ", rotation " << rotation << ", step " << step);
          REQUIRE(SameState(world.State(bottom), fresh.State(fresh_bottom)));
          REQUIRE(SameState(world.State(top), fresh.State(fresh_top)));
        }
      }
    }
  }
}

TEST_CASE("destroy: the body's springs go with it", "[bodies][destroy]") {
  engine::WorldDef def;
  engine::World world(def);
  const BodyId anchor_ball = world.CreateBody(Circle({0, 5}, 0.25));
  const BodyId hanging = world.CreateBody(Circle({0, 3}, 0.25));
  const BodyId other = world.CreateBody(Circle({3, 5}, 0.25));
  world.AddSpring(testing::Spring(hanging, anchor_ball, 1.0, 50));
  engine::SpringDef fixed;  // the other ball hangs from a world point
  fixed.body_a = other;
  fixed.local_b = {3, 6};
  fixed.rest_length = 1.0;
  fixed.stiffness = 50;
  world.AddSpring(fixed);
  testing::StepTimes(world, 10);
  REQUIRE(world.Springs().size() == 2);

  world.DestroyBody(anchor_ball);
  REQUIRE(world.Springs().size() == 1);
  CHECK(world.Springs()[0].body_a == other);
  // Nothing pulls the hanging ball any more: from here it falls freely, step for step.
  const engine::BodyState start = world.State(hanging);
  const int substeps = world.Def().substeps;
  const int steps = 30;
  testing::StepTimes(world, steps);
  const auto fall =
      testing::SemiImplicitFall(start.position.y, start.velocity.y, -kG, def.dt / substeps, steps * substeps);
  CHECK(world.State(hanging).position.y == Approx(fall.position).epsilon(1e-12));
  CHECK(world.State(hanging).velocity.y == Approx(fall.velocity).epsilon(1e-12));
}

TEST_CASE("destroy: a stale id passed to State() aborts, naming the call", "[bodies][ids]") {
  engine::World world(engine::WorldDef{});
  const BodyId id = world.CreateBody(Circle({0, 0}, 0.5));
  world.DestroyBody(id);
  int pipe_fds[2];
  REQUIRE(pipe(pipe_fds) == 0);
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {  // the child: stderr into the pipe, then the bad call
    std::signal(SIGABRT, SIG_DFL);  // not Catch's handler, which would report a failure
    dup2(pipe_fds[1], STDERR_FILENO);
    close(pipe_fds[0]);
    (void)world.State(id);
    _exit(0);  // only if the call came back
  }
  close(pipe_fds[1]);
  std::string message;
  char buffer[256];
  for (ssize_t n; (n = read(pipe_fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  close(pipe_fds[0]);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGABRT);
  CHECK(message == "engine precondition failed: State: body id {0, 0} is stale (its body was destroyed)\n");
}

TEST_CASE("enable: a disabled floor lets a ball through; enabled again, it holds the next one",
          "[bodies][enable]") {
  for (const engine::ContactSolver solver : testing::kBothSolvers) {
    DYNAMIC_SECTION("solver " << static_cast<int>(solver)) {
      engine::WorldDef def;
      def.solver = solver;
      engine::World world(def);
      const BodyId floor = world.CreateBody(Floor());
      const BodyId ball = world.CreateBody(Circle({0, 2}, 0.5));
      world.SetEnabled(floor, false);
      CHECK_FALSE(world.IsEnabled(floor));
      const int steps = 60;
      testing::StepTimes(world, steps);
      const int substeps = solver == engine::ContactSolver::kSubstep ? world.Def().substeps : 1;
      const auto fall = testing::SemiImplicitFall(2, 0, -kG, def.dt / substeps, steps * substeps);
      CHECK(world.State(ball).position.y == Approx(fall.position).epsilon(1e-12));  // -2.9 m
      CHECK(world.Contacts().empty());

      world.SetEnabled(floor, true);
      const BodyId second = world.CreateBody(Circle({3, 2}, 0.5));
      testing::StepTimes(world, 120);
      CHECK(world.State(second).position.y == Approx(0.5).margin(0.01));  // rests on the floor
      CHECK(world.State(ball).position.y < -5);                           // still falling below
    }
  }
}

TEST_CASE("enable: a disabled body does not move, stays in BodyIds and the hash", "[bodies][enable]") {
  engine::World world(engine::WorldDef{});
  engine::BodyDef def = Circle({0, 2}, 0.5, {1, 3});
  def.enabled = false;
  const BodyId ball = world.CreateBody(def);
  CHECK_FALSE(world.IsEnabled(ball));
  CHECK_FALSE(world.IsAwake(ball));
  const std::uint64_t hash = world.StateHash();
  testing::StepTimes(world, 30);
  CHECK(world.State(ball).position == Vec2{0, 2});
  CHECK(world.State(ball).velocity == Vec2{1, 3});  // kept, not simulated
  CHECK(world.StateHash() == hash);
  REQUIRE(world.BodyIds().size() == 1);
  CHECK(world.BodyIds()[0] == ball);
  engine::World empty(engine::WorldDef{});
  CHECK(world.StateHash() != empty.StateHash());  // the disabled ball is hashed

  world.ApplyLinearImpulseToCenter(ball, {5, 5});  // ignored while disabled
  world.ApplyForceToCenter(ball, {100, 0});
  world.Step();
  CHECK(world.State(ball).velocity == Vec2{1, 3});

  world.SetEnabled(ball, true);
  world.Step();  // moves on from the kept state
  CHECK(world.State(ball).position.x > 0.0);
  CHECK(world.State(ball).velocity.x == 1.0);
}

TEST_CASE("enable: a disabled box is not hit by a ball rolling into it", "[bodies][enable]") {
  engine::World world(testing::NoGravity());
  const BodyId ball = world.CreateBody(Circle({0, 0}, 0.5, {2, 0}));
  const BodyId wall = world.CreateBody(Box({2, 0}, {0.5, 2}));
  world.SetEnabled(wall, false);
  testing::StepTimes(world, 120);  // 4 m: through the wall's place
  CHECK(world.State(ball).velocity == Vec2{2, 0});
  CHECK(world.State(ball).position.x == Approx(4.0).epsilon(1e-12));
  CHECK(world.State(wall).position == Vec2{2, 0});
}

TEST_CASE("user data: set in the definition, changed, kept over steps; a new body in the slot has its own",
          "[bodies]") {
  engine::World world(engine::WorldDef{});
  engine::BodyDef def = Circle({0, 5}, 0.5);
  def.user_data = 0xfeedface12345678ull;
  const BodyId a = world.CreateBody(def);
  const BodyId b = world.CreateBody(Circle({2, 5}, 0.5));
  CHECK(world.UserData(a) == 0xfeedface12345678ull);
  CHECK(world.UserData(b) == 0);
  world.SetUserData(b, 42);
  testing::StepTimes(world, 10);
  CHECK(world.UserData(a) == 0xfeedface12345678ull);
  CHECK(world.UserData(b) == 42);
  world.DestroyBody(b);
  const BodyId c = world.CreateBody(Circle({2, 5}, 0.5));
  CHECK(c.index == b.index);
  CHECK(world.UserData(c) == 0);
}

TEST_CASE("destroy, disable: a body gone or disabled no longer pulls by gravitation", "[bodies][enable]") {
  for (const int what : {0, 1, 2}) {  // kept, disabled, destroyed
    DYNAMIC_SECTION((what == 0 ? "kept" : what == 1 ? "disabled" : "destroyed")) {
      engine::WorldDef def = testing::NoGravity();
      def.gravitational_constant = 1.0;
      engine::World world(def);
      const BodyId a = world.CreateBody(testing::WithMass(Circle({0, 0}, 0.5), 1.0));
      const BodyId b = world.CreateBody(testing::WithMass(Circle({10, 0}, 0.5), 100.0));
      if (what == 1) world.SetEnabled(b, false);
      if (what == 2) world.DestroyBody(b);
      testing::StepTimes(world, 60);
      if (what == 0) {
        // G m / r² = 1 m/s² towards b at 10 m, 1.11 m/s² at 9.5 m, where a is after 1 s.
        CHECK(world.State(a).velocity.x > 1.0);
        CHECK(world.State(a).velocity.x < 1.11);
      } else {
        CHECK(world.State(a).velocity == Vec2{});
        CHECK(world.State(a).position == Vec2{});
      }
    }
  }
}
