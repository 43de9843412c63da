// Joints in SIMD lanes: each width's passes give the bits of the joint solver's arithmetic done
// one joint at a time in the same order; a joint net steps to one hash at every width and thread
// count; a hanging net in lanes holds its joints and does not gain energy.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "engine/world.h"
#include "joint_builders.h"
#include "joints/joint_solver.h"
#include "joints/wide_joints.h"
#include "solver/wide_passes.h"
#include "world_builders.h"

namespace {

using engine::BodyId;
using engine::BodyInfo;
using engine::BodyState;
using engine::JointId;
using engine::Vec2;
using engine::detail::JointBlock;
using engine::detail::JointTable;
using engine::detail::JointWork;
using engine::detail::WideJoints;

// Revolute joints with what the lanes must get right: static bodies shared by many joints of a
// colour (never written), a body that cannot turn, a hub with more joints than there are
// colours (the colour whose joints share a body, one to a block), random arms, separations,
// drifts and impulses.
struct Scene {
  std::vector<BodyInfo> infos;
  std::vector<BodyState> states;
  std::vector<Vec2> push;
  std::vector<double> push_angular;
  JointTable table;
  std::vector<JointWork> work;
};

Scene MakeScene(unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Scene scene;
  const int bodies = 150;
  for (int i = 0; i < bodies; ++i) {
    const bool fixed = i < 3, no_turn = i == 5;
    BodyInfo info;
    info.inv_mass = fixed ? 0.0 : 1.0 / (1.0 + 0.5 * (unit(random) + 1.0));
    info.inv_inertia = fixed || no_turn ? 0.0 : 1.0 / (0.2 + 0.1 * unit(random));
    scene.infos.push_back(info);
    BodyState state;
    if (!fixed) {
      state.velocity = {3.0 * unit(random), 3.0 * unit(random)};
      state.angular_velocity = no_turn ? 0.0 : 4.0 * unit(random);
    }
    scene.states.push_back(state);
    scene.push.push_back(fixed ? Vec2{} : Vec2{0.1 * unit(random), 0.1 * unit(random)});
    scene.push_angular.push_back(fixed || no_turn ? 0.0 : 0.1 * unit(random));
  }
  const auto add = [&](int a, int b) {
    engine::detail::Joint j;
    j.def.type = engine::JointType::kRevolute;
    j.a = static_cast<engine::BodyIndex>(a);
    j.b = static_cast<engine::BodyIndex>(b);
    j.impulses.point = {0.2 * unit(random), 0.2 * unit(random)};
    JointWork w{};
    w.slot = static_cast<std::uint32_t>(scene.table.joints.size());
    w.type = j.def.type;
    w.a = j.a;
    w.b = j.b;
    w.ma = scene.infos[a].inv_mass;
    w.mb = scene.infos[b].inv_mass;
    w.ia = scene.infos[a].inv_inertia;
    w.ib = scene.infos[b].inv_inertia;
    w.ra = {0.5 * unit(random), 0.5 * unit(random)};
    w.rb = {0.5 * unit(random), 0.5 * unit(random)};
    w.separation = {0.01 * unit(random), 0.01 * unit(random)};
    w.drift_point = {1e-4 * unit(random), 1e-4 * unit(random)};
    scene.table.joints.push_back(j);
    scene.work.push_back(w);
  };
  for (int b = 3; b < 80; ++b) add(b % 3, b);   // on the static bodies
  for (int b = 4; b < 80; ++b) add(3, b);       // the hub: 76 joints, past 63 colours
  for (int i = 0; i < 300; ++i) {               // the rest at random
    const int a = 4 + static_cast<int>(random() % (bodies - 4));
    const int b = 4 + static_cast<int>(random() % (bodies - 4));
    if (a != b) add(a, b);
  }
  return scene;
}

// What the passes leave behind, to compare bit for bit.
struct Outcome {
  std::vector<BodyState> states;
  std::vector<Vec2> push;
  std::vector<double> push_angular;
  std::vector<Vec2> impulses;
};

template <typename T>
bool SameBits(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0;
}

constexpr double kInvH = 480.0, kRate = 240.0;

// The revolute point's arithmetic as joint_solver.cpp writes it (PointMass, Solve22,
// PointVelocity, ApplyPoint), one joint at a time: what every width must reproduce.
struct Reference {
  static Vec2 Solve(const JointWork& w, Vec2 v) {
    const double m = w.ma + w.mb;
    const double k11 = m + w.ia * w.ra.y * w.ra.y + w.ib * w.rb.y * w.rb.y;
    const double k12 = -w.ia * w.ra.x * w.ra.y - w.ib * w.rb.x * w.rb.y;
    const double k22 = m + w.ia * w.ra.x * w.ra.x + w.ib * w.rb.x * w.rb.x;
    const double det = k11 * k22 - k12 * k12;
    if (!(det > 0.0)) return {};
    const double inv = 1.0 / det;
    return {inv * (k22 * v.x - k12 * v.y), inv * (k11 * v.y - k12 * v.x)};
  }
  static Vec2 Velocity(const JointWork& w, Vec2 va, double wa, Vec2 vb, double wb) {
    return (vb + engine::Cross(wb, w.rb)) - (va + engine::Cross(wa, w.ra));
  }
  static void Apply(const JointWork& w, Vec2 impulse, Vec2* va, double* wa, Vec2* vb, double* wb) {
    Vec2 a = *va, b = *vb;
    double ta = *wa, tb = *wb;
    a -= w.ma * impulse;
    ta -= w.ia * engine::Cross(w.ra, impulse);
    b += w.mb * impulse;
    tb += w.ib * engine::Cross(w.rb, impulse);
    if (w.ma != 0.0 || w.ia != 0.0) *va = a, *wa = ta;  // the lanes write moving bodies only
    if (w.mb != 0.0 || w.ib != 0.0) *vb = b, *wb = tb;
  }
};

// Warm start, two velocity passes, two push-out passes, in the lanes' order. `wide_passes` null:
// the reference one joint at a time, else those wide passes.
Outcome RunPasses(const Scene& scene, const engine::detail::WidePasses* wide_passes) {
  using namespace engine::detail;
  WideJoints wide;
  REQUIRE(wide.Pack(scene.work, scene.table, scene.states.size()) == scene.work.size());
  WorkerPool pool(1);
  wide.LoadFrames(scene.work, pool);
  wide.LoadDrift(scene.work, pool);
  Outcome out{scene.states, scene.push, scene.push_angular, {}};
  if (wide_passes == nullptr) {
    std::vector<Vec2> impulses(scene.work.size());
    for (std::size_t i = 0; i < scene.work.size(); ++i) impulses[i] = scene.table.joints[scene.work[i].slot].impulses.point;
    const auto each = [&](auto&& f) {  // in block order
      for (const std::uint32_t i : wide.work_of) {
        if (i != WideJoints::kNotWide) f(scene.work[i], impulses[i]);
      }
    };
    each([&](const JointWork& w, Vec2& p) {
      BodyState &a = out.states[w.a], &b = out.states[w.b];
      Reference::Apply(w, p, &a.velocity, &a.angular_velocity, &b.velocity, &b.angular_velocity);
    });
    for (int pass = 0; pass < 2; ++pass) {
      each([&](const JointWork& w, Vec2& p) {
        BodyState &a = out.states[w.a], &b = out.states[w.b];
        const Vec2 v = Reference::Velocity(w, a.velocity, a.angular_velocity, b.velocity, b.angular_velocity);
        const Vec2 impulse = -Reference::Solve(w, v + kInvH * w.drift_point);
        p += impulse;
        Reference::Apply(w, impulse, &a.velocity, &a.angular_velocity, &b.velocity, &b.angular_velocity);
      });
    }
    for (int pass = 0; pass < 2; ++pass) {
      each([&](const JointWork& w, Vec2&) {
        Vec2 &va = out.push[w.a], &vb = out.push[w.b];
        double &wa = out.push_angular[w.a], &wb = out.push_angular[w.b];
        const Vec2 target = -kRate * w.separation;
        Reference::Apply(w, Reference::Solve(w, target - Reference::Velocity(w, va, wa, vb, wb)), &va, &wa, &vb, &wb);
      });
    }
    out.impulses = impulses;
    return out;
  }
  const WidePasses& passes = *wide_passes;
  passes.joint_warm_start(wide.blocks.data(), wide.blocks.size(), out.states.data());
  for (int pass = 0; pass < 2; ++pass) passes.joint_solve(wide.blocks.data(), wide.blocks.size(), out.states.data(), kInvH);
  for (int pass = 0; pass < 2; ++pass) {
    passes.joint_push_out(wide.blocks.data(), wide.blocks.size(), out.push.data(), out.push_angular.data(), kRate);
  }
  JointTable table = scene.table;
  wide.UnpackImpulses(scene.work, &table);
  for (const JointWork& w : scene.work) out.impulses.push_back(table.joints[w.slot].impulses.point);
  return out;
}

// A net of `n` × `n` circles of radius 0.4 m, 1 m apart, each joined to its right and lower
// neighbours at the midpoint, hanging from the seven middle bodies of its top row (Box2D's
// joint_grid layout). `mixed`: some joints with limits and some welds (one at a time), and
// short pendulums beside it (small islands: the direct solve writes into their lanes).
struct Net {
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
};

Net AddNet(engine::World& world, int n, bool mixed) {
  Net net;
  const auto pinned = [&](int k, int i) { return i == 0 && std::abs(k - n / 2) <= 3; };
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      engine::BodyDef body = testing::Circle({1.0 * k, -1.0 * i}, 0.4);
      if (pinned(k, i)) body = testing::Static(body);
      net.bodies.push_back(world.CreateBody(body));
    }
  }
  for (int k = 0; k < n; ++k) {
    for (int i = 0; i < n; ++i) {
      const BodyId body = net.bodies[k * n + i];
      if (k + 1 < n && !(pinned(k, i) && pinned(k + 1, i))) {
        engine::JointDef def = testing::Revolute(body, net.bodies[(k + 1) * n + i], {k + 0.5, -1.0 * i});
        if (mixed && (k * n + i) % 23 == 0) {
          def.type = engine::JointType::kWeld;
        } else if (mixed && (k * n + i) % 17 == 0) {
          def.limits = engine::JointLimits{-0.3, 0.3};
        }
        net.joints.push_back(world.CreateJoint(def));
      }
      if (i + 1 < n && !(pinned(k, i) && pinned(k, i + 1))) {
        net.joints.push_back(world.CreateJoint(testing::Revolute(body, net.bodies[k * n + i + 1], {1.0 * k, -i - 0.5})));
      }
    }
  }
  if (mixed) {
    for (int p = 0; p < 4; ++p) {  // three-link pendulums to the side, released horizontally
      const Vec2 pivot{n + 3.0 + 4.0 * p, 0.0};
      BodyId previous = world.CreateBody(testing::Static(testing::Circle(pivot, 0.05)));
      for (int l = 0; l < 3; ++l) {
        const BodyId link = world.CreateBody(testing::Box(pivot + Vec2{0.5 * l + 0.25, 0.0}, {0.5, 0.1}));
        net.joints.push_back(world.CreateJoint(testing::Revolute(previous, link, pivot + Vec2{0.5 * l, 0.0})));
        previous = link;
      }
    }
  }
  return net;
}

std::uint64_t NetHash(int lanes, int threads, engine::ContactSolver solver = engine::ContactSolver::kSubstep) {
  engine::WorldDef def;
  def.solver = solver;
  def.rotation = true;
  def.sleeping = false;
  def.threads = threads;
  def.adapt_threads = false;  // the shared paths, even on a busy machine
  def.substep_features.lanes = lanes;
  engine::World world(def);
  AddNet(world, 50, true);
  for (int s = 0; s < 40; ++s) world.Step();
  return world.StateHash();
}

// Kinetic plus potential energy of the net's circles (radius 0.4 m, density 1), J.
double Energy(const engine::World& world, const Net& net, double g) {
  double energy = 0.0;
  for (const BodyId id : net.bodies) {
    const engine::BodyInfo& info = world.Info(id);
    const BodyState& s = world.State(id);
    energy += 0.5 * info.mass * engine::Dot(s.velocity, s.velocity) +
              0.5 * info.inertia * s.angular_velocity * s.angular_velocity + info.mass * g * s.position.y;
  }
  return energy;
}

}  // namespace

TEST_CASE("wide joints: each width's passes give the bits of the joint solver's arithmetic one joint at a time") {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Scene scene = MakeScene(seed);
    const Outcome reference = RunPasses(scene, nullptr);
    // The passes did something: velocities, push velocities and impulses changed.
    CHECK_FALSE(SameBits(reference.states, scene.states));
    CHECK_FALSE(SameBits(reference.push, scene.push));
    for (const engine::detail::WidePasses* passes : engine::detail::RunnableWidePasses()) {
      INFO("seed " << seed << ", " << passes->lanes << " lanes");
      const Outcome wide = RunPasses(scene, passes);
      CHECK(SameBits(wide.states, reference.states));
      CHECK(SameBits(wide.push, reference.push));
      CHECK(SameBits(wide.push_angular, reference.push_angular));
      CHECK(SameBits(wide.impulses, reference.impulses));
    }
  }
}

TEST_CASE("wide joints: the colouring puts no two joints that share a moving body in one colour") {
  const Scene scene = MakeScene(4);
  WideJoints wide;
  REQUIRE(wide.Pack(scene.work, scene.table, scene.states.size()) == scene.work.size());
  // The hub ran out of colours: its last joints share a colour, one to a block, after the rest.
  REQUIRE(wide.order.group_ends.size() == wide.order.parallel_groups + 1);
  std::uint32_t begin = 0;
  for (std::uint32_t g = 0; g < wide.order.parallel_groups; ++g) {
    std::vector<int> seen(scene.states.size(), 0);
    for (std::uint32_t l = begin * 4; l < wide.order.group_ends[g] * 4; ++l) {
      if (wide.work_of[l] == WideJoints::kNotWide) continue;
      const JointWork& w = scene.work[wide.work_of[l]];
      if (w.ma != 0.0 || w.ia != 0.0) CHECK(++seen[w.a] == 1);
      if (w.mb != 0.0 || w.ib != 0.0) CHECK(++seen[w.b] == 1);
    }
    begin = wide.order.group_ends[g];
  }
  // Fewer than kMinWideJoints that fit: none go in lanes.
  Scene small = scene;
  small.work.resize(engine::detail::kMinWideJoints - 1);
  CHECK(wide.Pack(small.work, small.table, small.states.size()) == 0);
  CHECK(wide.blocks.empty());
}

TEST_CASE("wide joints: a joint net steps to the same hash at every width and thread count") {
  const std::uint64_t one_lane = NetHash(1, 1);
  for (int lanes = 2; lanes <= engine::detail::WidestLanes(); lanes *= 2) {
    INFO(lanes << " lanes");
    CHECK(NetHash(lanes, 1) == one_lane);
  }
  CHECK(NetHash(0, 2) == one_lane);
  // The sequential-impulse baseline solves the same lanes once a step.
  const auto baseline = engine::ContactSolver::kSequentialImpulse;
  CHECK(NetHash(0, 2, baseline) == NetHash(1, 1, baseline));
}

TEST_CASE("wide joints: a 30 x 30 net hanging from seven points holds its joints within 1 cm and gains no energy") {
  // Each body is a rigid cross pinned at its four arms' tips: 3 n² freedoms against 4 n (n − 1)
  // rows, so the net is rigid and hangs where it starts, its joints loaded by its 450 kg.
  engine::WorldDef def;
  def.rotation = true;
  engine::World world(def);
  const Net net = AddNet(world, 30, false);
  REQUIRE(net.joints.size() >= engine::detail::kMinWideJoints);  // in lanes, in colour order
  std::vector<Vec2> starts;
  for (const BodyId id : net.bodies) starts.push_back(world.State(id).position);
  const double g = -def.gravity.y;
  const double start = Energy(world, net, g);
  double gap = 0.0, gained = 0.0;
  for (int step = 0; step < 180; ++step) {  // 3 s
    world.Step();
    gap = std::max(gap, testing::LargestAnchorGap(world, net.joints));
    gained = std::max(gained, Energy(world, net, g) - start);
  }
  CHECK(gap < 0.01);
  // Rigid joints do no work, and the push-out only closes gaps: the energy never rises.
  CHECK(gained <= 0.0);
  double moved = 0.0;
  for (std::size_t i = 0; i < net.bodies.size(); ++i) {
    moved = std::max(moved, engine::Length(world.State(net.bodies[i]).position - starts[i]));
  }
  CHECK(moved < 0.01);
  CHECK(moved > 0.0);  // stepped under its load (a net never stepped would pass the rest)
}
