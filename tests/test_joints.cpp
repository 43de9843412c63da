// Joints against closed forms: the pendulum's large-amplitude period, a spring joint's frequency,
// a slider's acceleration down its axis, a motor's speed and torque cap, a rope's length; stiff
// chains and a 1000:1 mass ratio.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "joint_builders.h"
#include "world_builders.h"

using engine::BodyId;
using engine::JointDef;
using engine::JointFrame;
using engine::JointId;
using engine::JointType;
using engine::Vec2;
using engine::World;
using engine::WorldDef;

namespace {

constexpr double kG = 9.8;
constexpr double kPi = std::numbers::pi;

WorldDef Turning(engine::ContactSolver solver = engine::ContactSolver::kSubstep) {
  WorldDef def;
  def.rotation = true;
  def.solver = solver;
  return def;
}

// The complete elliptic integral of the first kind K(k), by the arithmetic-geometric mean.
double EllipticK(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  return kPi / (2.0 * a);
}

// Times (s) at which x(t) crosses zero downwards, interpolated between steps.
struct Crossings {
  std::vector<double> times;
  double previous = 0.0;
  bool started = false;
  void Add(double x, double t, double dt) {
    if (started && previous > 0.0 && x <= 0.0) times.push_back(t - dt * x / (x - previous));
    previous = x;
    started = true;
  }
  double MeanPeriod() const { return (times.back() - times.front()) / static_cast<double>(times.size() - 1); }
};

BodyId Pivot(World& world, Vec2 at = {0, 0}) { return world.CreateBody(testing::Static(testing::Circle(at, 0.05))); }

}  // namespace

TEST_CASE("a pendulum released from horizontal swings with the large-amplitude period and keeps its height",
          "[joints]") {
  World world(Turning());
  const BodyId pivot = Pivot(world);
  const double length = 1.0, radius = 0.1, mass = 1.0;
  const BodyId bob = world.CreateBody(testing::WithMass(testing::Circle({length, 0}, radius), mass));
  world.CreateJoint(testing::Revolute(pivot, bob, {0, 0}));
  // A compound pendulum: I about the pivot = m·L² + m·r²/2; θ0 = π/2.
  const double inertia = mass * length * length + 0.5 * mass * radius * radius;
  const double expected = 4.0 * std::sqrt(inertia / (mass * kG * length)) * EllipticK(std::sin(kPi / 4.0));
  Crossings crossings;
  double highest_late = -1.0, highest = -1.0;
  const double dt = world.Def().dt;
  for (int step = 1; step <= 600; ++step) {
    world.Step();
    const Vec2 p = world.State(bob).position;
    crossings.Add(p.x, step * dt, dt);
    highest = std::max(highest, p.y);
    if (step > 480) highest_late = std::max(highest_late, p.y);  // the last two seconds
  }
  REQUIRE(crossings.times.size() >= 4);
  CHECK(crossings.MeanPeriod() == Approx(expected).epsilon(0.005));
  // It swings back up to its starting height (y = 0) within 2 % of its drop, and never above.
  CHECK(highest_late >= -0.02 * length);
  CHECK(highest <= 0.02 * length);
}

TEST_CASE("a 1 Hz spring joint oscillates at 1 Hz and, undamped, keeps its amplitude", "[joints]") {
  World world(testing::NoGravity());
  const BodyId anchor = Pivot(world);
  const BodyId ball = world.CreateBody(testing::WithMass(testing::Circle({1.1, 0}, 0.1), 2.0));
  JointDef spring = testing::Distance(anchor, ball, {0, 0}, {1.1, 0});
  spring.length = 1.0;
  spring.spring = engine::JointSpring{1.0, 0.0};
  world.CreateJoint(spring);
  Crossings crossings;
  double late_amplitude = 0.0;
  const double dt = world.Def().dt;
  for (int step = 1; step <= 600; ++step) {
    world.Step();
    const double x = world.State(ball).position.x - 1.0;
    crossings.Add(x, step * dt, dt);
    if (step > 480) late_amplitude = std::max(late_amplitude, std::abs(x));
  }
  REQUIRE(crossings.times.size() >= 9);
  CHECK(1.0 / crossings.MeanPeriod() == Approx(1.0).epsilon(0.01));
  CHECK(late_amplitude == Approx(0.1).epsilon(0.02));
}

TEST_CASE("a damped spring joint decays at the rate its damping ratio gives", "[joints]") {
  World world(testing::NoGravity());
  const BodyId anchor = Pivot(world);
  const BodyId ball = world.CreateBody(testing::WithMass(testing::Circle({1.1, 0}, 0.1), 1.0));
  JointDef spring = testing::Distance(anchor, ball, {0, 0}, {1.1, 0});
  spring.length = 1.0;
  const double zeta = 0.05;
  spring.spring = engine::JointSpring{1.0, zeta};
  world.CreateJoint(spring);
  // x(t) = A·e^(−ζωt)·cos(ω_d·t + φ): after 3 s the envelope is e^(−ζ·2π·3) of the start.
  testing::StepTimes(world, 180);
  double envelope = 0.0;
  for (int step = 0; step < 60; ++step) {  // one period around t = 3 s
    world.Step();
    envelope = std::max(envelope, std::abs(world.State(ball).position.x - 1.0));
  }
  const double expected = 0.1 * std::exp(-zeta * 2.0 * kPi * 3.0);
  CHECK(envelope == Approx(expected).epsilon(0.05));
}

TEST_CASE("a slider on a 30 degree prismatic axis accelerates at g sin(theta) and stops at its limit",
          "[joints]") {
  World world(Turning());
  const BodyId ground = world.CreateBody(testing::Static(testing::Box({0, -5}, {0.2, 0.2})));
  const BodyId slider = world.CreateBody(testing::WithMass(testing::Box({0, 0}, {0.4, 0.2}), 1.0));
  const double theta = kPi / 6.0;
  JointDef def;
  def.type = JointType::kPrismatic;
  def.body_a = ground;
  def.body_b = slider;
  def.anchor = {0, 0};
  def.axis = {std::cos(theta), std::sin(theta)};
  def.limits = engine::JointLimits{-1.0, 1.0};
  const JointId joint = world.CreateJoint(def);
  std::vector<double> x;
  double lowest = 0.0, off_axis = 0.0, turned = 0.0;
  for (int step = 1; step <= 300; ++step) {
    world.Step();
    const JointFrame f = world.Joint(joint);
    x.push_back(f.translation);
    lowest = std::min(lowest, f.translation);
    off_axis = std::max(off_axis, std::abs(engine::Cross(def.axis, f.anchor_b - f.anchor_a)));
    turned = std::max(turned, std::abs(f.angle));
  }
  // Second differences of x over 10 steps at t ≈ 0.33 s (before the limit): the acceleration.
  const double span = 10.0 * world.Def().dt;
  const double acceleration = -(x[29] - 2.0 * x[19] + x[9]) / (span * span);
  CHECK(acceleration == Approx(kG * std::sin(theta)).epsilon(0.005));
  CHECK(lowest >= -1.0 - 0.005);
  CHECK(x.back() == Approx(-1.0).margin(0.005));
  CHECK(off_axis < 1e-6);
  CHECK(turned < 1e-9);
}

TEST_CASE("a revolute motor accelerates at its torque cap and then holds its speed", "[joints]") {
  World world(testing::NoGravity());
  // (A world without gravity, but with rotation.)
  WorldDef def = testing::NoGravity();
  def.rotation = true;
  world = World(def);
  const BodyId axle = Pivot(world);
  const double mass = 2.0, radius = 0.5, cap = 0.5, speed = 3.0;
  const BodyId wheel = world.CreateBody(testing::WithMass(testing::Circle({0, 0}, radius), mass));
  JointDef motor = testing::Revolute(axle, wheel, {0, 0});
  motor.motor = engine::JointMotor{speed, cap};
  world.CreateJoint(motor);
  const double inertia = 0.5 * mass * radius * radius;
  testing::StepTimes(world, 30);  // 0.5 s at the cap: ω = cap·t / I
  CHECK(world.State(wheel).angular_velocity == Approx(cap * 0.5 / inertia).epsilon(1e-9));
  testing::StepTimes(world, 150);
  CHECK(world.State(wheel).angular_velocity == Approx(speed).margin(1e-3));
}

TEST_CASE("a rope stops a falling ball at its length", "[joints]") {
  World world(Turning());
  const BodyId anchor = Pivot(world);
  const BodyId ball = world.CreateBody(testing::WithMass(testing::Circle({0, -0.2}, 0.1), 1.0));
  JointDef rope = testing::Distance(anchor, ball, {0, 0}, {0, -0.2});
  rope.max_length = 1.0;
  const JointId joint = world.CreateJoint(rope);
  double longest = 0.0;
  for (int step = 0; step < 300; ++step) {
    world.Step();
    longest = std::max(longest, world.Joint(joint).translation);
  }
  CHECK(longest <= 1.0 + 0.005);
  CHECK(world.Joint(joint).translation == Approx(1.0).margin(0.005));  // hanging taut at the end
  // The rope only pulls: a ball thrown up towards the anchor is not held back on the way; only
  // gravity slows it.
  world.SetLinearVelocity(ball, {0, 3});
  world.Step();
  CHECK(world.State(ball).velocity.y == Approx(3.0 - kG * world.Def().dt).epsilon(1e-12));
}

TEST_CASE("a 20-link chain released horizontally keeps every joint within 2 mm for 10 s", "[joints]") {
  World world(Turning());
  BodyId previous = Pivot(world);
  std::vector<JointId> joints;
  for (int i = 0; i < 20; ++i) {
    const BodyId link = world.CreateBody(testing::Box({0.25 + 0.5 * i, 0}, {0.5, 0.1}));
    joints.push_back(world.CreateJoint(testing::Revolute(previous, link, {0.5 * i, 0})));
    previous = link;
  }
  double gap = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    gap = std::max(gap, testing::LargestAnchorGap(world, joints));
  }
  CHECK(gap < 0.002);
  // The chain fell: its tip is far below the start (a chain that is not stepped keeps gap 0).
  CHECK(world.State(previous).position.y < -3.0);
}

TEST_CASE("a 50 kg weight on ten 50 g links (1000:1) sinks less than 1 cm", "[joints]") {
  World world(Turning());
  BodyId previous = Pivot(world);
  std::vector<JointId> joints;
  for (int i = 0; i < 10; ++i) {
    const BodyId link = world.CreateBody(testing::WithMass(testing::Box({0, -0.125 - 0.25 * i}, {0.04, 0.25}), 0.05));
    joints.push_back(world.CreateJoint(testing::Revolute(previous, link, {0, -0.25 * i})));
    previous = link;
  }
  const double rigid_y = -2.5 - 0.25;
  const BodyId weight = world.CreateBody(testing::WithMass(testing::Box({0, rigid_y}, {0.5, 0.5}), 50.0));
  joints.push_back(world.CreateJoint(testing::Revolute(previous, weight, {0, -2.5})));
  double sink = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    sink = std::max(sink, rigid_y - world.State(weight).position.y);
  }
  CHECK(sink < 0.01);
  CHECK(testing::LargestAnchorGap(world, joints) < 0.001);
}

TEST_CASE("a rigid weld holds two boxes as one body through a swing", "[joints]") {
  World world(Turning());
  const BodyId pivot = Pivot(world);
  const BodyId upper = world.CreateBody(testing::Box({0.5, 0}, {1.0, 0.2}));
  const BodyId lower = world.CreateBody(testing::Box({1.5, 0}, {1.0, 0.2}));
  const JointId hinge = world.CreateJoint(testing::Revolute(pivot, upper, {0, 0}));
  JointDef weld;
  weld.type = JointType::kWeld;
  weld.body_a = upper;
  weld.body_b = lower;
  weld.anchor = {1.0, 0};
  const JointId joint = world.CreateJoint(weld);
  double bend = 0.0, gap = 0.0;
  for (int step = 0; step < 300; ++step) {
    world.Step();
    bend = std::max(bend, std::abs(world.Joint(joint).angle));
    gap = std::max(gap, testing::LargestAnchorGap(world, std::vector<JointId>{hinge, joint}));
  }
  CHECK(bend < 1e-3);
  CHECK(gap < 0.001);
  CHECK(world.State(lower).position.y < -1.0);  // it swung down
}

TEST_CASE("a revolute joint's limits hold the relative angle", "[joints]") {
  World world(Turning());
  const BodyId pivot = Pivot(world);
  const BodyId arm = world.CreateBody(testing::Box({0.5, 0}, {1.0, 0.1}));
  JointDef hinge = testing::Revolute(pivot, arm, {0, 0});
  hinge.limits = engine::JointLimits{-0.5, 0.25};
  const JointId joint = world.CreateJoint(hinge);
  double lowest = 0.0;
  for (int step = 0; step < 300; ++step) {
    world.Step();
    lowest = std::min(lowest, world.Joint(joint).angle);
  }
  CHECK(lowest >= -0.5 - 0.005);
  CHECK(world.Joint(joint).angle == Approx(-0.5).margin(0.005));  // resting on the lower limit
}

TEST_CASE("a target joint pulls a body to its target, no harder than its cap", "[joints]") {
  World world(Turning());
  const BodyId box = world.CreateBody(testing::WithMass(testing::Box({0, 0}, {0.5, 0.5}), 1.0));
  JointDef grab;
  grab.type = JointType::kTarget;
  grab.body_b = box;
  grab.anchor = {0.1, 0.1};
  grab.target = {2.0, 1.0};
  grab.spring = engine::JointSpring{5.0, 0.7};
  grab.max_force = 1000.0 * kG;
  const JointId joint = world.CreateJoint(grab);
  testing::StepTimes(world, 180);
  const JointFrame f = world.Joint(joint);
  // Held against gravity by a 5 Hz spring: it sags g/ω² = 1 cm below the target at most.
  CHECK(engine::Length(f.anchor_b - grab.target) < 0.011);
  world.SetJointTarget(joint, {-1.0, 1.0});
  testing::StepTimes(world, 180);
  CHECK(engine::Length(world.Joint(joint).anchor_b - Vec2{-1.0, 1.0}) < 0.011);
  // A cap below the weight cannot hold the body up.
  World weak(Turning());
  const BodyId falling = weak.CreateBody(testing::WithMass(testing::Box({0, 0}, {0.5, 0.5}), 1.0));
  grab.body_b = falling;
  grab.anchor = {0, 0};
  grab.target = {0, 0};
  grab.max_force = 0.5 * kG;
  weak.CreateJoint(grab);
  testing::StepTimes(weak, 60);
  // Net downward force at least m·g − cap = 4.9 N: after 1 s it has fallen at least ½·4.9·1².
  CHECK(weak.State(falling).position.y < -0.5 * 4.9 * 0.99);
}

TEST_CASE("joined bodies do not collide unless the joint says so", "[joints]") {
  for (const bool collide : {false, true}) {
    World world(testing::NoGravity());
    const BodyId a = world.CreateBody(testing::Circle({0, 0}, 0.5));
    const BodyId b = world.CreateBody(testing::Circle({0.6, 0}, 0.5));  // overlapping by 0.4
    JointDef rope = testing::Distance(a, b, {0, 0}, {0.6, 0});
    rope.max_length = 10.0;
    rope.collide = collide;
    world.CreateJoint(rope);
    testing::StepTimes(world, 60);
    const double distance = engine::Length(world.State(b).position - world.State(a).position);
    if (collide) {
      CHECK(distance >= 1.0 - 0.01);  // pushed apart to touching
    } else {
      CHECK(distance == Approx(0.6).margin(1e-12));  // left overlapping
      CHECK(world.Contacts().empty());
    }
  }
}

TEST_CASE("destroying a body destroys its joints and its slot is reused with a new generation", "[joints]") {
  World world(Turning());
  const BodyId pivot = Pivot(world);
  const BodyId bob = world.CreateBody(testing::Circle({1, 0}, 0.1));
  const JointId first = world.CreateJoint(testing::Revolute(pivot, bob, {0, 0}));
  const BodyId other = world.CreateBody(testing::Circle({0, -1}, 0.1));
  const JointId second = world.CreateJoint(testing::Revolute(pivot, other, {0, 0}));
  world.DestroyBody(bob);
  CHECK_FALSE(world.IsValid(first));
  CHECK(world.IsValid(second));
  REQUIRE(world.JointIds().size() == 1);
  CHECK(world.JointIds()[0] == second);
  const BodyId again = world.CreateBody(testing::Circle({1, 0}, 0.1));
  const JointId third = world.CreateJoint(testing::Revolute(pivot, again, {0, 0}));
  CHECK(third.index == first.index);
  CHECK(third.generation == first.generation + 1);
  CHECK_FALSE(world.IsValid(first));
}

TEST_CASE("a world whose joints are gone steps to the same bits as one that never had any", "[joints]") {
  auto pile = [](World& world) {
    world.CreateBody(testing::Floor());
    for (int i = 0; i < 6; ++i) world.CreateBody(testing::Box({0.1 * i, 0.6 + 1.1 * i}, {1, 1}));
  };
  World plain(Turning()), touched(Turning());
  pile(plain);
  pile(touched);
  const JointId joint = touched.CreateJoint(testing::Revolute(touched.BodyIds()[1], touched.BodyIds()[2], {0, 1}));
  touched.DestroyJoint(joint);
  testing::StepTimes(plain, 300);
  testing::StepTimes(touched, 300);
  CHECK(plain.StateHash() == touched.StateHash());
}

TEST_CASE("a snapshot of a world with joints steps on to the same bits", "[joints][snapshot]") {
  auto build = [](World& world) {
    BodyId previous = world.CreateBody(testing::Static(testing::Circle({0, 0}, 0.05)));
    for (int i = 0; i < 5; ++i) {
      const BodyId link = world.CreateBody(testing::Box({0.25 + 0.5 * i, 0}, {0.5, 0.1}));
      JointDef hinge = testing::Revolute(previous, link, {0.5 * i, 0});
      if (i == 0) hinge.motor = engine::JointMotor{1.0, 5.0};
      world.CreateJoint(hinge);
      previous = link;
    }
  };
  World original(Turning()), copy(Turning());
  build(original);
  build(copy);
  testing::StepTimes(original, 100);
  REQUIRE(static_cast<bool>(copy.RestoreSnapshot(original.TakeSnapshot())));
  testing::StepTimes(original, 100);
  testing::StepTimes(copy, 100);
  CHECK(original.StateHash() == copy.StateHash());
  CHECK(copy.JointIds().size() == 5);
}

TEST_CASE("the sequential-impulse baseline holds a pendulum and a hanging chain", "[joints]") {
  World world(Turning(engine::ContactSolver::kSequentialImpulse));
  const BodyId pivot = Pivot(world);
  const BodyId bob = world.CreateBody(testing::Circle({1, 0}, 0.1));
  std::vector<JointId> joints{world.CreateJoint(testing::Revolute(pivot, bob, {0, 0}))};
  BodyId previous = Pivot(world, {5, 0});
  for (int i = 0; i < 10; ++i) {
    const BodyId link = world.CreateBody(testing::Box({5, -0.125 - 0.25 * i}, {0.04, 0.25}));
    joints.push_back(world.CreateJoint(testing::Revolute(previous, link, {5, -0.25 * i})));
    previous = link;
  }
  world.SetLinearVelocity(previous, {2, 0});
  double gap = 0.0;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    gap = std::max(gap, testing::LargestAnchorGap(world, joints));
  }
  CHECK(gap < 0.005);
  CHECK(world.State(bob).position.y < 0.0);
}

TEST_CASE("a pendulum at rest sleeps, and a new motor speed wakes it", "[joints]") {
  World world(Turning());
  const BodyId pivot = Pivot(world);
  const BodyId bob = world.CreateBody(testing::Circle({0, -1}, 0.1));
  JointDef hinge = testing::Revolute(pivot, bob, {0, 0});
  hinge.motor = engine::JointMotor{0.0, 0.01};
  const JointId joint = world.CreateJoint(hinge);
  testing::StepTimes(world, 120);
  CHECK_FALSE(world.IsAwake(bob));
  world.SetMotorSpeed(joint, 1.0);
  CHECK(world.IsAwake(bob));
}
