// Forces beyond the calibrated scenarios: spring torque and angular momentum with rotation on,
// bit-identical state hashes when a force is present but unused (the "skip" proofs of design.md),
// forces meeting sleep, and drag stiffer than the step (integrated implicitly).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "engine/world.h"
#include "game/scene.h"
#include "world_builders.h"

namespace {

using engine::Integrator;
using engine::Vec2;

constexpr Integrator kIntegrators[] = {Integrator::kSemiImplicitEuler, Integrator::kExplicitEuler,
                                       Integrator::kVelocityVerlet, Integrator::kMidpoint,
                                       Integrator::kRungeKutta4};

const char* Name(Integrator integrator) {
  switch (integrator) {
    case Integrator::kSemiImplicitEuler: return "semi-implicit Euler";
    case Integrator::kExplicitEuler: return "explicit Euler";
    case Integrator::kVelocityVerlet: return "velocity Verlet";
    case Integrator::kMidpoint: return "midpoint";
    case Integrator::kRungeKutta4: return "RK4";
  }
  return "?";
}

engine::SpringDef Spring(engine::BodyIndex a, Vec2 local_a, std::optional<engine::BodyIndex> b, Vec2 local_b,
                         double rest_length, double stiffness, double damping) {
  engine::SpringDef s;
  s.body_a = {a};
  s.local_a = local_a;
  if (b) s.body_b = engine::BodyId{*b};
  s.local_b = local_b;
  s.rest_length = rest_length;
  s.stiffness = stiffness;
  s.damping = damping;
  return s;
}

// Σ r × m·v + I·ω about the origin.
double AngularMomentum(const engine::World& world) {
  double total = 0.0;
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    const engine::BodyInfo& info = world.Info(id);
    total += info.mass * engine::Cross(s.position, s.velocity) + info.inertia * s.angular_velocity;
  }
  return total;
}

// Two boxes and a disc, spinning and drifting, joined by four damped springs attached off their
// centres: no gravity, no anchor to the world, and far enough apart that they never touch, so
// no external force or torque acts on the system.
engine::World SpringCluster(engine::WorldDef def) {
  def.gravity = {0, 0};
  def.rotation = true;
  def.sleeping = false;
  engine::World world(def);
  engine::BodyDef a = testing::WithMass(testing::Box({-3, 0.5}, {1, 0.5}, {0.1, -0.15}), 2.0);
  a.angle = 0.3;
  a.angular_velocity = 0.5;
  engine::BodyDef b = testing::WithMass(testing::Box({3, -0.5}, {0.6, 1.2}, {-0.05, 0.2}), 1.0);
  b.angle = -0.2;
  b.angular_velocity = -0.7;
  engine::BodyDef c = testing::WithMass(testing::Circle({0, 4}, 0.3, {0.25, 0}), 0.5);
  c.angular_velocity = 1.0;
  world.CreateBody(a);
  world.CreateBody(b);
  world.CreateBody(c);
  world.AddSpring(Spring(0, {0.5, 0.25}, 1, {-0.3, 0.6}, 5.0, 1.5, 0.2));
  world.AddSpring(Spring(0, {0.5, -0.25}, 1, {-0.3, -0.6}, 4.5, 1.5, 0.2));
  world.AddSpring(Spring(2, {0.3, 0}, 1, {0.3, 0.6}, 4.0, 0.75, 0.2));
  world.AddSpring(Spring(2, {-0.2, -0.2}, 0, {-0.5, 0.25}, 4.0, 0.75, 0.2));
  return world;
}

struct MomentumRun {
  double max_relative_error = 0.0;
  double max_spin = 0.0;  // the largest |ω| seen: the test is void if nothing turns
  bool contacts = false;
};

MomentumRun RunCluster(engine::World world, int steps) {
  MomentumRun run;
  const double l0 = AngularMomentum(world);
  for (int step = 0; step < steps; ++step) {
    world.Step();
    run.max_relative_error = std::max(run.max_relative_error, std::abs(AngularMomentum(world) - l0) / std::abs(l0));
    for (const engine::BodyId id : world.BodyIds()) {
      run.max_spin = std::max(run.max_spin, std::abs(world.State(id).angular_velocity));
    }
    run.contacts = run.contacts || !world.Contacts().empty();
  }
  return run;
}

engine::WorldDef Seed(Integrator integrator, double dt) {
  engine::WorldDef def;
  def.integrator = integrator;
  def.dt = dt;
  def.solver = engine::ContactSolver::kSequentialImpulse;
  return def;
}

}  // namespace

TEST_CASE("a spring attached at the centre makes no rotation", "[forces]") {
  for (Integrator integrator : kIntegrators) {
    for (engine::ContactSolver solver : {engine::ContactSolver::kSubstep, engine::ContactSolver::kSequentialImpulse}) {
      for (bool centred : {true, false}) {
        INFO(Name(integrator) << (solver == engine::ContactSolver::kSequentialImpulse ? ", seed" : ", substep")
                              << (centred ? ", centred" : ", off-centre (control)"));
        engine::WorldDef def;
        def.integrator = integrator;
        def.solver = solver;
        def.rotation = true;
        def.sleeping = false;
        engine::World world(def);
        // A box swinging and bouncing on a spring from a world anchor, and a second box hanging
        // from it by another spring: every spring force passes through a centre.
        world.CreateBody(testing::WithMass(testing::Box({1.5, -2}, {1, 0.5}, {2, 0}), 1.0));
        world.CreateBody(testing::WithMass(testing::Box({1.5, -4}, {0.4, 0.8}, {0, 1}), 0.5));
        const Vec2 attach = centred ? Vec2{0, 0} : Vec2{0.5, 0.25};
        world.AddSpring(Spring(0, attach, std::nullopt, {0, 0}, 2.0, 40.0, 0.5));
        world.AddSpring(Spring(1, {0, 0}, 0, {0, 0}, 2.0, 20.0, 0.1));
        bool still = true;
        for (int step = 0; step < 600; ++step) {
          world.Step();
          for (engine::BodyId id{0}; id.index < 2; ++id.index) {
            still = still && world.State(id).angle == 0.0 && world.State(id).angular_velocity == 0.0;
          }
        }
        REQUIRE(world.Contacts().empty());
        CHECK(still == centred);
      }
    }
  }
}

TEST_CASE("angular momentum is conserved without external torque", "[forces]") {
  // The substep solver at 4 substeps (h = 1/240 s), 60 s. Symplectic Euler and Verlet conserve
  // Σ r × m·v + I·ω exactly in real arithmetic (each kick is equal and opposite forces on one line
  // of action, each drift keeps r × v), so only roundoff may remain: 1e-12 (measured ~1e-14).
  // RK4's error is O(h⁴): at most 1e-9 (measured ~4e-12). Midpoint's is O(h²) (measured ~5.2e-6)
  // and explicit Euler's O(h) (measured ~1.7e-3): their bounds are 2× the measurement, and what
  // pins them down independently is their order (next test) and Euler's exact per-step change.
  struct Case {
    Integrator integrator;
    double tolerance;
  };
  for (Case c : {Case{Integrator::kSemiImplicitEuler, 1e-12}, Case{Integrator::kVelocityVerlet, 1e-12},
                 Case{Integrator::kRungeKutta4, 1e-9}, Case{Integrator::kMidpoint, 1e-5},
                 Case{Integrator::kExplicitEuler, 3.5e-3}}) {
    engine::WorldDef def;
    def.integrator = c.integrator;
    def.substeps = 4;
    const MomentumRun run = RunCluster(SpringCluster(def), 3600);
    INFO(Name(c.integrator) << ": max relative error of angular momentum " << run.max_relative_error);
    REQUIRE_FALSE(run.contacts);
    CHECK(run.max_spin > 1.0);
    CHECK(run.max_relative_error <= c.tolerance);
  }
}

TEST_CASE("angular momentum error converges at each method's order", "[forces]") {
  // One step per frame (the seed solver) at h = 1/60, 1/120 and 1/240 over 20 s.
  struct Case {
    Integrator integrator;
    double order;
  };
  for (Case c : {Case{Integrator::kExplicitEuler, 1}, Case{Integrator::kMidpoint, 2},
                 Case{Integrator::kRungeKutta4, 4}}) {
    double errors[3];
    for (int i = 0; i < 3; ++i) {
      const int rate = 60 << i;
      const MomentumRun run = RunCluster(SpringCluster(Seed(c.integrator, 1.0 / rate)), 20 * rate);
      REQUIRE_FALSE(run.contacts);
      errors[i] = run.max_relative_error;
    }
    INFO(Name(c.integrator) << ": " << errors[0] << ", " << errors[1] << ", " << errors[2]);
    CHECK(std::abs(std::log2(errors[0] / errors[1]) - c.order) <= 0.1);
    CHECK(std::abs(std::log2(errors[1] / errors[2]) - c.order) <= 0.1);
  }
}

TEST_CASE("explicit Euler changes angular momentum by exactly h·Σ m·v_n × v_(n+1) per step", "[forces]") {
  // x' = x + h·v, v' = v + h·a, θ' = θ + h·ω, ω' = ω + h·α: the internal torques cancel at the old
  // positions, leaving L' − L = h²·Σ m·v × a = h·Σ m·v_n × v_(n+1), the discrete law to test
  // against (as S1 tests the Euler pair against its discrete parabola).
  const double h = 1.0 / 60.0;
  engine::World world = SpringCluster(Seed(Integrator::kExplicitEuler, h));
  const std::size_t n = world.BodyCount();
  std::vector<Vec2> before(n);
  double largest_change = 0.0;
  for (int step = 0; step < 1200; ++step) {
    for (engine::BodyId id{0}; id.index < n; ++id.index) before[id.index] = world.State(id).velocity;
    const double l_before = AngularMomentum(world);
    world.Step();
    double predicted = 0.0;
    for (engine::BodyId id{0}; id.index < n; ++id.index) {
      predicted += h * world.Info(id).mass * engine::Cross(before[id.index], world.State(id).velocity);
    }
    const double change = AngularMomentum(world) - l_before;
    largest_change = std::max(largest_change, std::abs(change));
    INFO("step " << step << ": change " << change << ", predicted " << predicted);
    REQUIRE(std::abs(change - predicted) <= 1e-13);
  }
  CHECK(largest_change > 1e-7);  // the law is tested on changes far above the roundoff
}

namespace {

// What a run adds to the small scene of SameRun: world settings, body settings (by index), and
// anything added once the bodies exist (springs).
struct Variation {
  std::function<void(engine::WorldDef*)> world = nullptr;
  std::function<void(std::size_t, engine::BodyDef*)> body = nullptr;
  std::function<void(engine::World*)> after = nullptr;
};

// Steps both worlds 240 times (4 s at 60 Hz); true if their state hashes match after every step.
bool SameHashesFor4Seconds(engine::World& plain, engine::World& other) {
  bool same = true;
  for (int step = 0; step < 240; ++step) {
    plain.Step();
    other.Step();
    same = same && plain.StateHash() == other.StateHash();
  }
  return same;
}

// A small scene with contacts, stacking and sliding (and spin, with rotation), run for 4 s twice:
// as `base` makes it, and with `changed` on top. True if the state hashes match at every step.
bool SameRun(Integrator integrator, bool rotation, const Variation& base, const Variation& changed) {
  engine::WorldDef def;
  def.integrator = integrator;
  def.rotation = rotation;
  if (base.world) base.world(&def);
  engine::WorldDef changed_def = def;
  if (changed.world) changed.world(&changed_def);
  engine::World plain(def), other(changed_def);
  std::vector<engine::BodyDef> bodies = {
      testing::Static(testing::Box({0, -0.5}, {12, 1})),
      testing::Static(testing::Circle({2.5, 1.5}, 0.5)),
      testing::Circle({-1, 3}, 0.4, {1, 0}),
      testing::Circle({2.3, 4}, 0.3),
      testing::WithMass(testing::Box({-0.8, 1}, {1, 0.6}, {0.5, -1}), 2.0),
      testing::Box({-3, 0.5}, {0.8, 0.8}, {4, 0}),
  };
  if (rotation) bodies[5].angular_velocity = 2.0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (base.body) base.body(i, &bodies[i]);
    plain.CreateBody(bodies[i]);
    if (changed.body) changed.body(i, &bodies[i]);
    other.CreateBody(bodies[i]);
  }
  if (base.after) base.after(&plain), base.after(&other);
  if (changed.after) changed.after(&other);
  return SameHashesFor4Seconds(plain, other);
}

// `unused` must change no bit with any integrator, with rotation off and on; `used` (the
// control, showing the scene exercises the feature) must change some.
void CheckSkip(const Variation& unused, const Variation& used, const Variation& base = {}) {
  for (bool rotation : {false, true}) {
    for (Integrator integrator : kIntegrators) {
      INFO(Name(integrator) << (rotation ? ", rotation" : ", no rotation"));
      CHECK(SameRun(integrator, rotation, base, unused));
      CHECK_FALSE(SameRun(integrator, rotation, base, used));
    }
  }
}

}  // namespace

TEST_CASE("skip: a spring of stiffness 0 and damping 0 changes no bit", "[forces][skip]") {
  // Off-centre, between two bodies and to the world: a pull of exactly zero, and no torque.
  CheckSkip({.after = [](engine::World* w) {
               w->AddSpring(Spring(2, {0.2, 0.1}, 4, {-0.3, 0.2}, 1.0, 0.0, 0.0));
               w->AddSpring(Spring(5, {0.4, -0.4}, std::nullopt, {0, 6}, 0.5, 0.0, 0.0));
             }},
            {.after = [](engine::World* w) { w->AddSpring(Spring(2, {0.2, 0.1}, 4, {-0.3, 0.2}, 1.0, 5.0, 0.0)); }});
}

TEST_CASE("skip: springs with nothing to pull, among springs that pull, change no bit", "[forces][skip]") {
  // The force pass sees only the springs that act, in the order they were added: a chain of
  // three bodies hung from the world, with idle springs before, between and after the real ones
  // (and one to a static body), steps bit for bit like the chain alone. The control, one of them
  // given a stiffness, must differ.
  auto run = [](Integrator integrator, bool rotation, double idle_stiffness) {
    engine::WorldDef def;
    def.integrator = integrator;
    def.rotation = rotation;
    engine::World plain(def), other(def);
    for (engine::World* w : {&plain, &other}) {
      w->CreateBody(testing::Static(testing::Box({0, -0.5}, {12, 1})));
      for (int i = 0; i < 3; ++i) w->CreateBody(testing::WithMass(testing::Box({1.0 * i, 4 - 1.0 * i}, {0.6, 0.3}), 1.0));
    }
    const engine::SpringDef pulls[] = {Spring(1, {0.2, 0.1}, std::nullopt, {0, 6}, 1.5, 40.0, 0.5),
                                       Spring(1, {-0.3, 0}, 2, {0.1, 0.1}, 1.0, 25.0, 0.0),
                                       Spring(2, {0, 0}, 3, {0.3, -0.1}, 1.2, 0.0, 2.0)};
    const engine::SpringDef idle[] = {Spring(3, {0.1, 0}, std::nullopt, {4, 4}, 0.5, idle_stiffness, 0.0),
                                      Spring(2, {0.2, -0.1}, 1, {0, 0}, 2.0, 0.0, 0.0),
                                      Spring(3, {0, 0.1}, 0, {1, 0.5}, 0.0, 0.0, 0.0),
                                      Spring(1, {0, 0}, 3, {0, 0}, 3.0, 0.0, 0.0)};
    for (const engine::SpringDef& spring : pulls) plain.AddSpring(spring);
    other.AddSpring(idle[0]);
    other.AddSpring(pulls[0]);
    other.AddSpring(idle[1]);
    other.AddSpring(pulls[1]);
    other.AddSpring(idle[2]);
    other.AddSpring(pulls[2]);
    other.AddSpring(idle[3]);
    return SameHashesFor4Seconds(plain, other);
  };
  for (bool rotation : {false, true}) {
    for (Integrator integrator : kIntegrators) {
      INFO(Name(integrator) << (rotation ? ", rotation" : ", no rotation"));
      CHECK(run(integrator, rotation, 0.0));
      CHECK_FALSE(run(integrator, rotation, 5.0));
    }
  }
}

TEST_CASE("skip: linear and angular damping of 0, or with nothing to damp, change no bit", "[forces][skip]") {
  // Given as 0 on moving bodies (the default, spelled out), and given at all on static bodies,
  // which never move.
  CheckSkip({.body = [](std::size_t, engine::BodyDef* b) {
               b->linear_damping = b->is_static ? 5.0 : 0.0;
               b->angular_damping = b->is_static ? 5.0 : 0.0;
             }},
            {.body = [](std::size_t i, engine::BodyDef* b) {
               if (i == 4) b->linear_damping = 0.1;
             }});
  // Angular damping without rotation: nothing turns, so there is nothing to damp.
  for (Integrator integrator : kIntegrators) {
    INFO(Name(integrator));
    CHECK(SameRun(integrator, false, {}, {.body = [](std::size_t, engine::BodyDef* b) { b->angular_damping = 3.0; }}));
  }
}

TEST_CASE("skip: drag coefficients in a vacuum, or a fluid with no drag, change no bit", "[forces][skip]") {
  // fluid_density 0 with drag coefficients set on every body...
  CheckSkip({.body = [](std::size_t, engine::BodyDef* b) { b->drag_coefficient = 2.0; }},
            {.world = [](engine::WorldDef* d) { d->fluid_density = 1.2; }});
  // ...and a fluid where every body's drag coefficient is 0.
  CheckSkip({.world = [](engine::WorldDef* d) { d->fluid_density = 1.2; },
             .body = [](std::size_t, engine::BodyDef* b) { b->drag_coefficient = 0.0; }},
            {.world = [](engine::WorldDef* d) { d->fluid_density = 1.2; }});
}

TEST_CASE("skip: gravitational_constant 0, or a single dynamic body, changes no bit", "[forces][skip]") {
  const Variation with_g{.world = [](engine::WorldDef* d) { d->gravitational_constant = 1e3; }};
  CheckSkip({.world = [](engine::WorldDef* d) { d->gravitational_constant = 0.0; }}, with_g);
  // Gravitation acts between dynamic bodies only: with one, G has nobody to pull on.
  const Variation one_dynamic{.body = [](std::size_t i, engine::BodyDef* b) {
    if (i != 4) *b = testing::Static(*b);
  }};
  for (bool rotation : {false, true}) {
    for (Integrator integrator : kIntegrators) {
      INFO(Name(integrator) << (rotation ? ", rotation" : ", no rotation"));
      CHECK(SameRun(integrator, rotation, one_dynamic, with_g));
    }
  }
}

TEST_CASE("skip: a scene file with every force key at its unused value runs bit for bit like one without",
          "[forces][skip]") {
  const std::string bodies = R"(
    { "shape": "box", "size": [12, 1], "position": [0, -0.5], "static": true, "linear_damping": 2 },
    { "shape": "circle", "radius": 0.4, "position": [-1, 3], "velocity": [1, 0] EXTRA },
    { "shape": "box", "size": [1, 0.6], "position": [-0.8, 1], "velocity": [0.5, -1], "angular_velocity": 2 EXTRA },
    { "shape": "circle", "radius": 0.3, "position": [0.3, 4] EXTRA })";
  auto scene_text = [&](bool keys) {
    std::string b = bodies;
    const std::string extra = keys ? R"(, "linear_damping": 0, "angular_damping": 0, "drag_coefficient": 0.8)" : "";
    for (std::size_t at = b.find("EXTRA"); at != std::string::npos; at = b.find("EXTRA")) b.replace(at, 5, extra);
    if (!keys) {
      const std::size_t damping = b.find(R"(, "linear_damping": 2)");
      b.erase(damping, std::string(R"(, "linear_damping": 2)").size());
    }
    const std::string world_keys = keys ? R"("fluid_density": 0, "gravitational_constant": 0,
      "springs": [{ "a": "body1", "b": "body2", "anchor_a": [0.1, 0.2], "stiffness": 0, "damping": 0 }],)"
                                        : "";
    return R"({ "rotation": true, )" + world_keys + R"( "bodies": [)" + b + "]}";
  };
  for (const char* integrator : {"semi_implicit_euler", "explicit_euler", "velocity_verlet", "midpoint", "rk4"}) {
    INFO(integrator);
    auto load = [&](bool keys) {
      std::string text = scene_text(keys);
      text.insert(1, std::string(R"( "integrator": ")") + integrator + "\",");
      const game::Expected<game::Scene> scene = game::ParseScene(text, "skip.json", "skip");
      if (!scene.HasValue()) FAIL(scene.Error().message);
      return scene.Value();
    };
    const game::Scene with_keys = load(true), without_keys = load(false);
    REQUIRE(with_keys.springs.size() == 1);
    engine::World a = game::BuildWorld(with_keys), b = game::BuildWorld(without_keys);
    bool same = true;
    for (int step = 0; step < 240; ++step) {
      a.Step();
      b.Step();
      same = same && a.StateHash() == b.StateHash();
    }
    CHECK(same);
  }
}

TEST_CASE("a spring wakes the sleeping body at its other end", "[forces]") {
  // Islands built from contacts alone would leave box a asleep while b is pulled back towards
  // where a lies, as if a were nailed down.
  engine::World world(engine::WorldDef{});
  world.CreateBody(testing::Static(testing::Box({0, -0.5}, {20, 1})));
  const engine::BodyId a = world.CreateBody(testing::WithMass(testing::Box({-2, 0.5}, {1, 1}), 1.0));
  const engine::BodyId b = world.CreateBody(testing::WithMass(testing::Box({2, 0.5}, {1, 1}), 1.0));
  world.AddSpring(Spring(a.index, {0, 0}, b.index, {0, 0}, 4.0, 50.0, 1.0));
  for (int step = 0; step < 120; ++step) world.Step();
  REQUIRE_FALSE(world.IsAwake(a));
  REQUIRE_FALSE(world.IsAwake(b));
  world.ApplyLinearImpulseToCenter(b, {5, 0});
  world.Step();
  CHECK(world.IsAwake(a));
  for (int step = 0; step < 119; ++step) world.Step();
  CHECK(world.State(a).position.x > -2.0 + 1e-3);  // a stretched spring pulls a towards b
}

TEST_CASE("a body sinking at a steady speed below the sleep speed keeps sinking", "[forces]") {
  // A 10 g ball of radius 0.1 m in water sinks at its terminal speed √(m·g/c) = 4.6 cm/s, under
  // the 5 cm/s sleep speed: a sleep rule that looked at speed alone would freeze it in mid-water.
  engine::WorldDef def;
  def.fluid_density = 1000.0;
  def.gravity = {0, -9.8};
  engine::World world(def);
  world.CreateBody(testing::WithMass(testing::Circle({0, 3}, 0.1), 0.01));
  const double c = 0.5 * 1000.0 * 0.47 * 0.2;
  const double terminal = std::sqrt(0.01 * 9.8 / c);
  REQUIRE(terminal < def.sleep_speed);
  for (int step = 0; step < 120; ++step) world.Step();
  CHECK(world.IsAwake({0}));
  CHECK(world.State({0}).velocity.y == Approx(-terminal).epsilon(1e-6));
}

TEST_CASE("quadratic drag on a light body in water settles at its terminal speed", "[forces]") {
  // Stiff drag: explicitly, each (sub)step of length h multiplies a velocity error near terminal
  // speed by 1 − h·λ, λ = 2·√(c·g/m); a 10 g ball of radius 0.25 m in water (v_t = 2.9 cm/s,
  // v_t/g = 2.9 ms) at 4 substeps (h = 4.2 ms) would settle at +1.6 cm/s, upward. Such a body
  // takes an implicit Euler step, whose rest point is exactly the terminal speed, in every method.
  for (Integrator integrator : kIntegrators) {
    INFO(Name(integrator));
    engine::WorldDef def;
    def.integrator = integrator;
    def.fluid_density = 1000.0;
    def.sleeping = false;
    engine::World world(def);
    world.CreateBody(testing::WithMass(testing::Circle({0, 3}, 0.25), 0.01));
    const double c = 0.5 * 1000.0 * 0.47 * 0.5;
    const double terminal = std::sqrt(0.01 * 9.8 / c);
    for (int step = 0; step < 120; ++step) world.Step();
    CHECK(world.State({0}).velocity.y == Approx(-terminal).epsilon(0.01));
  }
}
