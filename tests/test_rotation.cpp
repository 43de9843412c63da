// Rotation: turned-box narrow phase by hand, inclines and rolling against closed forms (accuracy.md
// S10), rotating stacks against the solver's thresholds, and no angular work when nothing turns.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bench/stress_scenes.h"
#include "narrow_phase/collide.h"
#include "solver/substep_solver.h"
#include "engine/world.h"
#include "world_builders.h"

using engine::Vec2;
using testing::Box;
using testing::Circle;
using testing::Static;
using testing::WithMaterial;

namespace {

constexpr double kPi = 3.14159265358979323846;

void CheckVec(Vec2 v, Vec2 expected, double margin = 1e-12) {
  CHECK(v.x == Approx(expected.x).margin(margin));
  CHECK(v.y == Approx(expected.y).margin(margin));
}

}  // namespace

TEST_CASE("oriented boxes: a diamond's corner in a face gives one point", "[rotation][collide]") {
  // B, a unit square turned 45°, has its lowest corner √½ below its centre; placed so that the
  // corner is 0.1 into A's top face (y = 1).
  const double c = 1.0 + std::sqrt(0.5) - 0.1;
  engine::Manifold m;
  REQUIRE(engine::CollideOrientedBoxes({{0, 0}, {1, 1}, engine::MakeRot(0)},
                                       {{0, c}, {0.5, 0.5}, engine::MakeRot(kPi / 4)}, &m));
  REQUIRE(m.point_count == 1);
  CheckVec(m.normal, {0, 1});
  CheckVec(m.points[0].point, {0, 0.95});  // midway between the corner and the face
  CHECK(m.points[0].depth == Approx(0.1).margin(1e-12));
}

TEST_CASE("oriented boxes: two boxes turned alike, face on face, give two points", "[rotation][collide]") {
  const engine::Rot q = engine::MakeRot(kPi / 6);
  const Vec2 b_center = engine::Rotate(q, {0.25, 1.8});  // 0.2 overlap along the turned y axis
  engine::Manifold m;
  REQUIRE(engine::CollideOrientedBoxes({{0, 0}, {1, 1}, q}, {b_center, {1, 1}, q}, &m));
  REQUIRE(m.point_count == 2);
  CheckVec(m.normal, engine::Rotate(q, {0, 1}));
  for (int i = 0; i < 2; ++i) CHECK(m.points[i].depth == Approx(0.2).margin(1e-12));
  // The overlap runs from x = −0.75 to 1 in the boxes' frame, at height 0.9 (mid-penetration).
  CheckVec(m.points[0].point, engine::Rotate(q, {-0.75, 0.9}));
  CheckVec(m.points[1].point, engine::Rotate(q, {1.0, 0.9}));
  CHECK(m.points[0].id != m.points[1].id);
}

TEST_CASE("oriented boxes: apart beyond the margin is no contact, within it a speculative one", "[rotation][collide]") {
  const engine::Rot q = engine::MakeRot(0.3);
  const engine::OrientedBox a{{0, 0}, {1, 1}, q};
  const engine::OrientedBox b{engine::Rotate(q, {0, 2.05}), {1, 1}, q};
  engine::Manifold m;
  CHECK_FALSE(engine::CollideOrientedBoxes(a, b, &m));
  REQUIRE(engine::CollideOrientedBoxes(a, b, &m, 0.1));
  CHECK(m.points[0].depth == Approx(-0.05).margin(1e-12));
}

TEST_CASE("oriented boxes: a point keeps its id whether or not its end was clipped", "[rotation][collide]") {
  // Two boxes of the same width stacked: B's bottom corners sit at the ends of A's top face, so
  // a shift by a rounding error decides whether an end is clipped. Warm starting matches points
  // by id: an id that flips with the clipping loses a point's impulse at random (this let a
  // heavy box squeeze its column of light boxes apart). Box2D v3 names a clipped point by the
  // reference and incident vertices it lies between, as here.
  const engine::OrientedBox a{{0, 0}, {0.5, 0.5}, engine::MakeRot(0)};
  engine::Manifold flush;
  REQUIRE(engine::CollideOrientedBoxes(a, {{0, 0.999}, {0.5, 0.5}, engine::MakeRot(0)}, &flush));
  REQUIRE(flush.point_count == 2);
  for (double shift : {-1e-12, 1e-12}) {
    engine::Manifold m;
    REQUIRE(engine::CollideOrientedBoxes(a, {{shift, 0.999}, {0.5, 0.5}, engine::MakeRot(0)}, &m));
    REQUIRE(m.point_count == 2);
    INFO("shift " << shift);
    CHECK(m.points[0].id == flush.points[0].id);
    CHECK(m.points[1].id == flush.points[1].id);
  }
}

TEST_CASE("circle against a turned box is the axis-aligned test in the box's frame", "[rotation][collide]") {
  // A 4×1 box turned 90° stands 1 wide and 4 tall: its right face is at x = 0.5.
  engine::Manifold m;
  REQUIRE(engine::CollideCircleOrientedBox({0.9, 0.3}, 0.5, {{0, 0}, {2, 0.5}, engine::MakeRot(kPi / 2)}, &m));
  CheckVec(m.normal, {-1, 0});
  CHECK(m.points[0].depth == Approx(0.1).margin(1e-12));
  CheckVec(m.points[0].point, {0.45, 0.3});
}

namespace {

// A ramp turned by θ with a body resting on its face; returns the world and the body's id.
// Down the slope is −(cos θ, sin θ).
engine::World OnRamp(double theta, engine::BodyDef body, double half_height, double mu) {
  engine::WorldDef def;
  def.rotation = true;
  def.gravity = {0, -9.8};
  def.sleeping = false;
  engine::World world(def);
  engine::BodyDef ramp = WithMaterial(Static(Box({0, 0}, {60, 1})), 0, mu);
  ramp.angle = theta;
  world.CreateBody(ramp);
  const engine::Rot q = engine::MakeRot(theta);
  body.position = engine::Rotate(q, {10.0, 0.5 + half_height});
  if (body.shape.type == engine::ShapeType::kBox) body.angle = theta;
  body.friction = mu;
  body.restitution = 0;
  world.CreateBody(body);
  return world;
}

double SpeedAlongSlope(const engine::World& world, double theta) {
  return -engine::Dot(world.State({1}).velocity, {std::cos(theta), std::sin(theta)});
}

}  // namespace

TEST_CASE("a block slides down a 30° incline at g(sin θ − μ cos θ)", "[rotation][incline]") {
  const double theta = kPi / 6, mu = 0.2;
  engine::World world = OnRamp(theta, Box({}, {1, 1}), 0.5, mu);
  for (int i = 0; i < 30; ++i) world.Step();  // settle into contact
  const double v0 = SpeedAlongSlope(world, theta);
  for (int i = 0; i < 60; ++i) world.Step();
  const double a = (SpeedAlongSlope(world, theta) - v0) / 1.0;
  const double expected = 9.8 * (std::sin(theta) - mu * std::cos(theta));  // 3.203 m/s²
  INFO("measured " << a << " m/s², expected " << expected);
  CHECK(a == Approx(expected).epsilon(0.01));
  CHECK(std::abs(world.State({1}).angle - theta) < 1e-3);  // it slides, it does not tumble
}

TEST_CASE("a block on an incline with tan θ ≤ μ stays put", "[rotation][incline]") {
  const double theta = kPi / 6, mu = 0.6;  // tan 30° = 0.577 < 0.6
  engine::World world = OnRamp(theta, Box({}, {1, 1}), 0.5, mu);
  const Vec2 start = world.State({1}).position;
  for (int i = 0; i < 120; ++i) world.Step();
  INFO("moved " << engine::Length(world.State({1}).position - start) << " m");
  CHECK(engine::Length(world.State({1}).position - start) <= 1e-3);
}

TEST_CASE("a disc rolls down a 30° incline at ⅔·g·sin θ without slipping", "[rotation][incline]") {
  const double theta = kPi / 6, mu = 0.6, r = 0.5;  // rolling needs μ ≥ tan θ / 3
  engine::World world = OnRamp(theta, Circle({}, r), r, mu);
  for (int i = 0; i < 30; ++i) world.Step();
  const double v0 = SpeedAlongSlope(world, theta);
  for (int i = 0; i < 60; ++i) world.Step();
  const double v1 = SpeedAlongSlope(world, theta);
  const double expected = 2.0 / 3.0 * 9.8 * std::sin(theta);  // 3.267 m/s² (a disc, not a sphere)
  INFO("measured " << v1 - v0 << " m/s², expected " << expected);
  CHECK((v1 - v0) / 1.0 == Approx(expected).epsilon(0.01));
  // Rolling: the contact point is at rest, v = ω·r (rolling down to the left turns it
  // counter-clockwise: ω positive).
  CHECK(std::abs(v1 - world.State({1}).angular_velocity * r) <= 1e-3 * v1);
}

TEST_CASE("a disc rolling on a flat floor keeps its height, speed and spin", "[rotation][rolling]") {
  // Rolling without slipping on level ground, no rolling resistance: v and ω·r stay what they
  // were, and the disc stays r above the floor. A circle's contact points lie on the line
  // through its centre, so its own turn moves them along its outline without changing the gap;
  // counting the turn into the gap (as a box's corner must) had the disc find ρ(1 − cos θ) of
  // room each step: at 5 m/s it sank 5.9 mm and slowed 0.4 % in 10 s.
  const double r = 0.25;
  for (const double v : {3.0, 5.0, 10.0}) {
    engine::WorldDef def;
    def.rotation = true;
    def.sleeping = false;
    engine::World world(def);
    world.CreateBody(WithMaterial(Static(Box({0, -0.5}, {400, 1})), 0, 0.6));
    engine::BodyDef disc = WithMaterial(Circle({-150, r}, r, {v, 0}), 0, 0.6);
    disc.angular_velocity = -v / r;  // rolling to the right turns it clockwise
    const engine::BodyId id = world.CreateBody(disc);
    double deepest = 0.0;
    for (int step = 0; step < 600; ++step) {
      world.Step();
      deepest = std::max(deepest, r - world.State(id).position.y);
    }
    const engine::BodyState& end = world.State(id);
    INFO("v " << v << " m/s: sank " << deepest * 1e3 << " mm, speed " << end.velocity.x << ", ω·r "
              << -end.angular_velocity * r);
    CHECK(deepest <= 0.5e-3);
    CHECK(end.velocity.x == Approx(v).epsilon(1e-4));
    CHECK(-end.angular_velocity * r == Approx(v).epsilon(1e-4));
  }
}

TEST_CASE("rotating stacks meet the solver's thresholds", "[rotation][stability]") {
  auto drift_after_10s = [](auto add) {
    engine::WorldDef def;
    def.rotation = true;
    def.sleeping = false;
    engine::World world(def);
    add(world);
    std::vector<Vec2> start;
    for (const engine::BodyId id : world.BodyIds()) start.push_back(world.State(id).position);
    for (int i = 0; i < 600; ++i) world.Step();
    double drift = 0, turn = 0;
    for (const engine::BodyId id : world.BodyIds()) {
      drift = std::max(drift, engine::Length(world.State(id).position - start[id.index]));
      turn = std::max(turn, std::abs(world.State(id).angle));
    }
    return std::pair{drift, turn};
  };
  const auto [pyramid20, turn20] = drift_after_10s([](engine::World& w) { stress::AddPyramid(w, 20); });
  const auto [pyramid40, turn40] = drift_after_10s([](engine::World& w) { stress::AddPyramid(w, 40); });
  const auto [stack20, turn_stack] = drift_after_10s([](engine::World& w) { stress::AddStack(w, 20); });
  INFO("pyramid 20: " << pyramid20 << " m, pyramid 40: " << pyramid40 << " m, stack 20: " << stack20 << " m");
  CHECK(pyramid20 < 0.005);
  CHECK(pyramid40 < 0.01);
  CHECK(stack20 < 0.005);
  CHECK(std::max({turn20, turn40, turn_stack}) < 0.05);  // accuracy.md §3.3: ≤ 0.05 rad
}

namespace {

engine::WorldDef TurningWorld() {
  engine::WorldDef def;
  def.rotation = true;
  def.sleeping = false;
  return def;
}

// Kinetic (linear and angular) and potential energy of every moving body, J.
double Energy(const engine::World& world) {
  const double g = -world.Def().gravity.y;
  double e = 0;
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyInfo& info = world.Info(id);
    const engine::BodyState& s = world.State(id);
    e += 0.5 * info.mass * engine::LengthSquared(s.velocity) +
         0.5 * info.inertia * s.angular_velocity * s.angular_velocity + info.mass * g * s.position.y;
  }
  return e;
}

// A 4×1 m box `ratio` times as heavy as each of the three 1 m boxes under it, its centre
// `offset` to the right of the column's, dropped from `drop` above it.
engine::World HeavyColumn(double ratio, double offset = 0.0, double drop = 0.0) {
  engine::World world(TurningWorld());
  if (offset == 0.0 && drop == 0.0) {
    stress::AddHeavyOnLight(world, 3, ratio);  // the scene of the benchmark and the axis-aligned test
    return world;
  }
  world.CreateBody(stress::Ground({0, -0.5}, {40, 1}));
  for (int i = 0; i < 3; ++i) world.CreateBody(stress::Box({0, 0.5 + i}, {1, 1}));
  world.CreateBody(stress::Box({offset, 3.5 + drop}, {4, 1}, ratio / 4.0));
  return world;
}

}  // namespace

// The mass-ratio stability threshold (accuracy.md §3.3) with rotation on. Gauss-Seidel alone
// cannot hold it (its passes converge ever slower as the ratio grows, and shock propagation
// stays out between turning bodies); the island's contacts are solved directly instead
// (engine/src/direct_solver.cpp, docs/solver.md).
TEST_CASE("a heavy box on a column of light ones stands with rotation on (1000:1 and 10 000:1)",
          "[rotation][stability]") {
  for (double ratio : {1000.0, 10000.0}) {
    engine::World world = HeavyColumn(ratio);
    const engine::BodyId heavy = static_cast<engine::BodyId>(world.BodyCount() - 1);
    const double y0 = world.State(heavy).position.y;
    double sank = 0, slid = 0, turned = 0;
    for (int i = 0; i < 600; ++i) {
      world.Step();
      sank = std::max(sank, y0 - world.State(heavy).position.y);
      for (engine::BodyId id{1}; id.index < world.BodyCount(); ++id.index) {
        slid = std::max(slid, std::abs(world.State(id).position.x));
        turned = std::max(turned, std::abs(world.State(id).angle));
      }
    }
    INFO(ratio << ":1: sank at most " << sank << " m, slid " << slid << " m, turned " << turned << " rad");
    CHECK(sank < 0.01);
    CHECK(slid < 0.001);   // the column stays a column
    CHECK(turned < 0.01);
  }
}

TEST_CASE("a 20×20 box on two 1×1 boxes stands with rotation on (400:1)", "[rotation][stability]") {
  // Solver2D's High Mass Ratio 2 (accuracy.md §3.1, criterion 6 of §3.3): sink ≤ 2 slops, the
  // small boxes not squeezed out.
  engine::World world(TurningWorld());
  world.CreateBody(stress::Ground({0, -0.5}, {60, 1}));
  world.CreateBody(stress::Box({-9.5, 0.5}, {1, 1}));
  world.CreateBody(stress::Box({9.5, 0.5}, {1, 1}));
  world.CreateBody(stress::Box({0, 11}, {20, 20}));
  for (int i = 0; i < 600; ++i) world.Step();
  INFO("sank " << 11 - world.State({3}).position.y << " m; legs at " << world.State({1}).position.x << ", "
               << world.State({2}).position.x);
  CHECK(11 - world.State({3}).position.y <= 2 * world.Def().linear_slop);
  CHECK(world.State({1}).position.x == Approx(-9.5).margin(1e-3));
  CHECK(world.State({2}).position.x == Approx(9.5).margin(1e-3));
}

TEST_CASE("a heavy box on a light column stands while its centre is over the column and topples once past it",
          "[rotation][stability]") {
  // The direct solve leaves bodies free to turn: holding the column must not hold up a load
  // whose centre of mass is beyond the column's edge (x = 0.5).
  for (double offset : {0.3, 0.45}) {
    engine::World world = HeavyColumn(1000, offset);
    for (int i = 0; i < 600; ++i) world.Step();
    INFO("offset " << offset << ": heavy box at y " << world.State({4}).position.y);
    CHECK(world.State({4}).position.y == Approx(3.5).margin(0.01));
  }
  engine::World world = HeavyColumn(1000, 0.6);
  for (int i = 0; i < 600; ++i) world.Step();
  INFO("offset 0.6: heavy box at y " << world.State({4}).position.y);
  CHECK(world.State({4}).position.y < 1.0);  // on the ground (0.5 when flat)
}

TEST_CASE("turning bodies with 1000:1 mass ratios never gain energy", "[rotation][stability]") {
  // A heavy box dropped onto a light column, one shoved along its top, and a box of mixed
  // boxes (every fifth 500 times denser) falling into a pile: what the direct solve does must
  // only ever take energy away.
  auto check = [](engine::World world, const char* name) {
    double highest = Energy(world);
    const double scale = std::abs(highest) + 1.0;
    for (int i = 0; i < 600; ++i) {
      world.Step();
      const double e = Energy(world);
      INFO(name << ", step " << i << ": energy " << e << " J, highest so far " << highest << " J");
      REQUIRE(e <= highest + 1e-9 * scale);
      highest = std::max(highest, e);
    }
  };
  check(HeavyColumn(1000, 0.0, 0.5), "heavy box dropped 0.5 m");
  {
    engine::World world = HeavyColumn(1000);
    world.ApplyLinearImpulseToCenter({4}, {200, 0});  // 0.2 m/s along the column's top
    check(std::move(world), "heavy box shoved");
  }
  engine::World pile(TurningWorld());
  stress::AddContainer(pile, 10, 12);
  for (int i = 0; i < 40; ++i) {
    pile.CreateBody(stress::Box({-4.0 + 0.2 * i, 1.0 + 0.9 * (i % 8)}, {0.5, 0.4}, i % 5 == 0 ? 500.0 : 1.0));
  }
  check(std::move(pile), "mixed pile");
}

TEST_CASE("rotation on with nothing able to turn computes exactly the axis-aligned game", "[rotation][skip]") {
  // Skip proof: with every body fixed_rotation, no angular state is integrated or solved, and
  // the state hash equals the one with rotation off, bit for bit.
  auto run = [](bool rotation) {
    engine::WorldDef def;
    def.rotation = rotation;
    def.substeps = 4;            // the same settings for both: only the rotation flag differs
    def.velocity_iterations = 1;
    engine::World world(def);
    stress::AddContainer(world, 10, 12);
    stress::AddCirclePour(world, 120, 0.3, 10, 0.5, 3);
    for (int i = 0; i < 20; ++i) {
      engine::BodyDef box = stress::Box({-4.0 + 0.4 * i, 9.0 + (i % 3)}, {0.5, 0.3});
      box.fixed_rotation = true;
      world.CreateBody(box);
    }
    for (int i = 0; i < 300; ++i) world.Step();
    return world.StateHash();
  };
  // Circles turn only through friction torque: make them fixed too by building a second
  // variant where the pour's circles cannot turn either.
  auto run_fixed = [](bool rotation) {
    engine::WorldDef def;
    def.rotation = rotation;
    def.substeps = 4;
    def.velocity_iterations = 1;
    engine::World world(def);
    stress::AddContainer(world, 10, 12);
    for (int i = 0; i < 60; ++i) {
      engine::BodyDef ball = Circle({-4.0 + 0.15 * i, 2.0 + 0.7 * (i % 7)}, 0.25, {0.5, 0});
      ball.fixed_rotation = true;
      world.CreateBody(ball);
      engine::BodyDef box = stress::Box({-4.0 + 0.15 * i, 8.0 + 0.5 * (i % 5)}, {0.4, 0.3});
      box.fixed_rotation = true;
      world.CreateBody(box);
    }
    for (int i = 0; i < 300; ++i) world.Step();
    return world.StateHash();
  };
  CHECK(run_fixed(true) == run_fixed(false));
  CHECK(run(true) != run(false));  // free circles do turn with rotation on: the test can fail
}

TEST_CASE("S12: a 2×2 box dropped from y = 4 rests on the ground after 90 steps", "[rotation][stability]") {
  // Box2D's HelloWorld test and thresholds (accuracy.md S12): |x| < 0.01, |y − 1| < 0.01,
  // |angle| < 0.01 rad, with rotation on.
  engine::WorldDef def;
  def.rotation = true;
  def.gravity = {0, -10};
  engine::World world(def);
  world.CreateBody(Static(Box({0, -10}, {100, 20})));
  world.CreateBody(Box({0, 4}, {2, 2}));
  for (int i = 0; i < 90; ++i) world.Step();
  const engine::BodyState& s = world.State({1});
  INFO("(" << s.position.x << ", " << s.position.y << "), angle " << s.angle);
  CHECK(std::abs(s.position.x) < 0.01);
  CHECK(std::abs(s.position.y - 1.0) < 0.01);
  CHECK(std::abs(s.angle) < 0.01);
}

TEST_CASE("turning worlds pick 2 passes for circles and 4 for the rest; set ones are kept", "[rotation]") {
  engine::WorldDef def;
  def.rotation = true;
  CHECK(engine::World(def).Def().velocity_iterations == 4);
  CHECK(engine::World(def).Def().circle_velocity_iterations == 2);
  def.velocity_iterations = 6;  // set: circles take it too
  CHECK(engine::World(def).Def().circle_velocity_iterations == 6);
  def.circle_velocity_iterations = 3;
  CHECK(engine::World(def).Def().velocity_iterations == 6);
  CHECK(engine::World(def).Def().circle_velocity_iterations == 3);
  def = {};  // axis-aligned: one pass for everything
  CHECK(engine::World(def).Def().circle_velocity_iterations == 1);
}

TEST_CASE("a turning pile of circles takes circle_velocity_iterations passes, one with a box velocity_iterations",
          "[rotation]") {
  // 20 × 20 circles in a box, each touching its neighbours from the first step (over 256
  // contacts); `box`: one of them is a box instead.
  const auto pile_hash = [](int passes, int circle_passes, bool box) {
    engine::WorldDef def;
    def.rotation = true;
    def.sleeping = false;
    def.velocity_iterations = passes;
    def.circle_velocity_iterations = circle_passes;
    engine::World world(def);
    stress::AddContainer(world, 10.0, 12.0);
    for (int i = 0; i < 400; ++i) {
      const engine::Vec2 at{-4.75 + 0.5 * (i % 20), 0.25 + 0.5 * (i / 20)};
      world.CreateBody(box && i == 210 ? Box(at, {0.5, 0.5}) : Circle(at, 0.25));
    }
    for (int i = 0; i < 30; ++i) world.Step();
    REQUIRE(world.Contacts().size() >= engine::detail::SubstepSolver::kMinStripContacts);
    return world.StateHash();
  };
  const std::uint64_t automatic = pile_hash(0, 0, false);
  CHECK(automatic == pile_hash(4, 2, false));
  CHECK(automatic == pile_hash(2, 0, false));  // a set velocity_iterations of 2: circles take 2
  CHECK(automatic != pile_hash(4, 4, false));
  const std::uint64_t with_box = pile_hash(0, 0, true);
  CHECK(with_box == pile_hash(4, 4, true));  // the circles' setting is not used
  CHECK(with_box != pile_hash(2, 2, true));  // the passes do matter here
}
