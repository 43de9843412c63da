// The wide solver (SubstepFeatures::lanes): its passes at every width the processor has give the
// bits of the one-at-a-time passes, on hand-made contacts with the awkward cases in them, and a
// world steps to the same state hash at every width and thread count.
#include <catch2/catch.hpp>
#include <cstring>
#include <random>
#include <vector>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "solver/contact_order.h"
#include "solver/substep_passes.h"
#include "solver/wide_passes.h"
#include "world_builders.h"

namespace {

using engine::BodyInfo;
using engine::BodyState;
using engine::Contact;
using engine::Vec2;
using engine::LinearConstraint;

// Bodies and contacts with what the passes must get right: static bodies shared by many
// contacts of a colour (never written), a hub with more contacts than there are colours (the
// colour whose contacts share a body, one to a block), gaps and overlaps, separations of -0.0,
// friction 0, tangent impulses at the cone's edge (dropped when sliding along them).
struct Scene {
  std::vector<BodyInfo> infos;
  std::vector<BodyState> states;
  std::vector<Vec2> start_positions;
  std::vector<Contact> contacts;
};

Scene MakeScene(unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Scene scene;
  const int bodies = 150;
  for (int i = 0; i < bodies; ++i) {
    BodyInfo info;
    const bool fixed = i < 3;  // three static bodies
    info.mass = fixed ? 0.0 : 1.0 + 0.5 * (unit(random) + 1.0);
    info.inv_mass = fixed ? 0.0 : 1.0 / info.mass;
    scene.infos.push_back(info);
    BodyState state;
    state.position = {10.0 * unit(random), 10.0 * unit(random)};
    state.velocity = {3.0 * unit(random), 3.0 * unit(random)};
    scene.states.push_back(state);
    scene.start_positions.push_back(state.position + Vec2{0.01 * unit(random), 0.01 * unit(random)});
  }
  const auto add = [&](int a, int b, int k) {
    Contact c;
    c.a = static_cast<engine::BodyIndex>(a);
    c.b = static_cast<engine::BodyIndex>(b);
    const double turn = 3.2 * unit(random);
    c.manifold.normal = {std::cos(turn), std::sin(turn)};
    c.manifold.point_count = 1 + k % 2;
    const double depth = k % 7 == 0 ? 0.0 : 0.02 * unit(random);
    c.manifold.points[0] = {{0.0, 0.0}, depth, 0};
    c.manifold.points[1] = {{0.0, 0.0}, depth - 0.001, 1};
    c.restitution = 0.2;
    c.friction = k % 5 == 0 ? 0.0 : 0.6;
    c.normal_impulse[0] = k % 3 == 0 ? 0.0 : 0.5 * (unit(random) + 1.0);
    // At the cone's edge, either way: dropped by the warm start where the pair slides along it.
    // Just inside it, within the warm start's margin for rounding (1e-9): dropped too.
    const double edge = c.friction * c.normal_impulse[0] * (k % 12 == 4 ? 1.0 - 5e-10 : 1.0);
    c.tangent_impulse[0] = k % 4 == 0 ? edge * (k % 8 == 0 ? 1.0 : -1.0) : 0.1 * unit(random);
    scene.contacts.push_back(c);
  };
  int k = 0;
  for (int b = 3; b < 80; ++b) add(b % 3, b, k++);            // on the static bodies
  for (int b = 4; b < 80; ++b) add(3, b, k++);                // the hub: 76 contacts, past 63 colours
  for (int i = 0; i < 300; ++i) {                             // the rest at random
    const int a = 4 + static_cast<int>(random() % (bodies - 4));
    const int b = 4 + static_cast<int>(random() % (bodies - 4));
    if (a != b) add(std::min(a, b), std::max(a, b), k++);
  }
  return scene;
}

// What the passes leave behind, to compare bit for bit.
struct Outcome {
  std::vector<BodyState> states;
  std::vector<Vec2> push;
  std::vector<LinearConstraint> constraints;
};

template <typename T>
bool SameBits(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0;
}

// The substep's passes in the solver's order: warm start, two velocity passes, a move, push-out.
// `lanes` 0: one at a time (substep_passes.cpp), else the wide passes of that width.
Outcome RunPasses(const Scene& scene, const engine::detail::ContactOrder& order, int lanes) {
  using namespace engine::detail;
  Outcome out{scene.states, std::vector<Vec2>(scene.states.size()), {}};
  PrepareSubstepConstraints<LinearConstraint>(scene.contacts, order.slot, scene.infos, scene.states,
                                              &out.constraints);
  const StepStart start{scene.start_positions, {}};
  const double inv_h = 240.0, rate = 9.0, max_speed = 3.0, slop = 0.005;
  const auto move = [&] {  // as MoveBodies would, between the velocity passes and the push-out
    for (BodyState& s : out.states) s.position += (1.0 / inv_h) * s.velocity;
  };
  if (lanes == 0) {
    const std::span<LinearConstraint> all = out.constraints;
    WarmStartAll(all, std::span<BodyState>(out.states));
    for (int pass = 0; pass < 2; ++pass) SolveContacts(all, std::span<BodyState>(out.states), start, inv_h, false);
    move();
    PushOut(all, std::span<const BodyState>(out.states), start, PushVelocities{out.push, {}}, rate, max_speed, slop);
    return out;
  }
  const WidePasses& passes = WidePassesFor(lanes);
  REQUIRE(passes.lanes == lanes);
  WideConstraints wide;
  wide.Pack(out.constraints, order);
  const std::size_t blocks = wide.blocks.size();
  passes.warm_start(wide.blocks.data(), blocks, out.states.data());
  for (int pass = 0; pass < 2; ++pass) {
    passes.solve(wide.blocks.data(), blocks, out.states.data(), scene.start_positions.data(), inv_h);
  }
  move();
  passes.push_out(wide.blocks.data(), blocks, out.states.data(), scene.start_positions.data(), out.push.data(),
                  rate, max_speed, slop);
  wide.UnpackImpulses(out.constraints);
  return out;
}

std::uint64_t PourHash(int lanes, int threads, bool boxes) {
  engine::WorldDef def;
  def.sleeping = false;
  def.threads = threads;
  def.substep_features.lanes = lanes;
  engine::World world(def);
  stress::AddBoxedPour(world, 1500);
  if (boxes) {
    for (int i = 0; i < 200; ++i) {
      world.CreateBody(testing::Box({-4.0 + 0.5 * (i % 16), 30.0 + 0.5 * (i / 16)}, {0.4, 0.3}));
    }
  }
  for (int s = 0; s < 240; ++s) world.Step();
  return world.StateHash();
}

}  // namespace

TEST_CASE("wide solver: each width's passes give the bits of the one-at-a-time passes") {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Scene scene = MakeScene(seed);
    engine::detail::ContactOrder order;
    order.ByColour(scene.contacts, scene.infos);
    // The hub's contacts ran out of colours: some share a body, and go one to a block.
    REQUIRE(order.group_ends.size() > order.parallel_groups);
    const Outcome reference = RunPasses(scene, order, 0);
    // The passes did something: velocities and impulses changed, and some pair was pushed.
    CHECK_FALSE(SameBits(reference.states, scene.states));
    bool pushed = false;
    for (const Vec2 v : reference.push) pushed = pushed || v.x != 0.0 || v.y != 0.0;
    CHECK(pushed);
    for (int lanes = 1; lanes <= engine::detail::WidestLanes(); lanes *= 2) {
      INFO("seed " << seed << ", " << lanes << " lanes");
      const Outcome wide = RunPasses(scene, order, lanes);
      CHECK(SameBits(wide.states, reference.states));
      CHECK(SameBits(wide.push, reference.push));
      CHECK(SameBits(wide.constraints, reference.constraints));
    }
  }
}

TEST_CASE("wide solver: a pour steps to the same hash at every width and thread count") {
  for (const bool boxes : {false, true}) {
    INFO((boxes ? "circles and boxes" : "circles"));
    const std::uint64_t one_at_a_time = PourHash(1, 1, boxes);
    for (int lanes = 2; lanes <= engine::detail::WidestLanes(); lanes *= 2) {
      INFO(lanes << " lanes");
      CHECK(PourHash(lanes, 1, boxes) == one_at_a_time);
    }
    CHECK(PourHash(0, 2, boxes) == one_at_a_time);
  }
}
