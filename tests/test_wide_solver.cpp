// The wide solver (SubstepFeatures::lanes): its passes at every width (and build) the processor has give the
// bits of the one-at-a-time passes, on hand-made contacts with the awkward cases in them, and a
// world steps to the same state hash at every width and thread count.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "bench/stress_scenes.h"
#include "contact_bodies.h"
#include "engine/world.h"
#include "move_measure.h"
#include "solver/contact_order.h"
#include "solver/substep_passes.h"
#include "solver/substep_solver.h"
#include "solver/wide_passes.h"
#include "world_builders.h"

namespace {

using engine::BodyInfo;
using engine::BodyState;
using engine::Contact;
using engine::Vec2;
using engine::LinearConstraint;
using engine::SubstepConstraint;
using engine::SubstepPoint;
using testing::MeasureMoves;

// Bodies and contacts with what the passes must get right: static bodies shared by many
// contacts of a colour (never written), a hub with more contacts than there are colours (the
// colour whose contacts share a body, one to a block), gaps and overlaps, separations of -0.0,
// friction 0, tangent impulses at the cone's edge (dropped when sliding along them).
struct Scene {
  std::vector<BodyInfo> infos;
  std::vector<BodyState> states;
  std::vector<Vec2> start_positions;
  std::vector<engine::Rot> turned;  ///< each body's turn since the step's start (turning scenes)
  std::vector<Contact> contacts;
};

// A body near `position` with a random mass (none where `fixed`), velocity, start a little
// away, and where it `turns` a moment of inertia, spin and turn since the start.
void AddBody(Scene* scene, std::mt19937_64& random, bool fixed, bool turns, Vec2 position) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BodyInfo info;
  info.mass = fixed ? 0.0 : 1.0 + 0.5 * (unit(random) + 1.0);
  info.inv_mass = fixed ? 0.0 : 1.0 / info.mass;
  info.inertia = fixed || !turns ? 0.0 : 0.2 + 0.1 * unit(random);
  info.inv_inertia = fixed || !turns ? 0.0 : 1.0 / info.inertia;
  scene->infos.push_back(info);
  BodyState state;
  state.position = position + Vec2{0.02 * unit(random), 0.02 * unit(random)};
  state.velocity = {3.0 * unit(random), 3.0 * unit(random)};
  state.angular_velocity = turns ? 4.0 * unit(random) : 0.0;
  scene->states.push_back(state);
  scene->start_positions.push_back(state.position + Vec2{0.01 * unit(random), 0.01 * unit(random)});
  scene->turned.push_back(engine::MakeRot(turns ? 0.05 * unit(random) : 0.0));
}

Scene MakeScene(unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Scene scene;
  const int bodies = 150;
  for (int i = 0; i < bodies; ++i) {
    AddBody(&scene, random, i < 3, false, {10.0 * unit(random), 10.0 * unit(random)});  // three static
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
  std::vector<engine::SubstepConstraint> turning;
  std::vector<double> push_angular;
  std::vector<Contact> contacts;  ///< the scene's, with the impulses the passes stored in them
};

// Every impulse the contacts hold, both points (a contact of one point stores none in its second).
std::vector<double> Impulses(const std::vector<Contact>& contacts) {
  std::vector<double> impulses;
  for (const Contact& c : contacts) {
    for (int k = 0; k < 2; ++k) {
      impulses.push_back(c.normal_impulse[k]);
      impulses.push_back(c.tangent_impulse[k]);
    }
  }
  return impulses;
}

template <typename T>
bool SameBits(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0;
}

// The substep's passes in the solver's order: warm start, two velocity passes, a move, push-out.
// `wide_passes` null: one at a time (substep_passes.cpp), else those wide passes.
Outcome RunPasses(const Scene& scene, const engine::detail::ContactOrder& order,
                  const engine::detail::WidePasses* wide_passes) {
  using namespace engine::detail;
  Outcome out{scene.states, std::vector<Vec2>(scene.states.size()), {}, {}, {}, scene.contacts};
  PrepareSubstepConstraints<LinearConstraint>(scene.contacts, order.slot, scene.infos, scene.states,
                                              &out.constraints);
  const StepStart start{scene.start_positions, {}};
  const double inv_h = 240.0, rate = 9.0, max_speed = 3.0, slop = 0.005;
  const auto move = [&] {  // as MoveBodies would, between the velocity passes and the push-out
    for (BodyState& s : out.states) s.position += (1.0 / inv_h) * s.velocity;
  };
  if (wide_passes == nullptr) {
    const std::span<LinearConstraint> all = out.constraints;
    WarmStartAll(all, std::span<BodyState>(out.states));
    for (int pass = 0; pass < 2; ++pass) SolveContacts(all, std::span<BodyState>(out.states), start, inv_h, false);
    move();
    PushOut(all, std::span<const BodyState>(out.states), start, PushVelocities{out.push, {}}, rate, max_speed, slop);
    StoreImpulses<LinearConstraint>(all, order.slot, out.contacts, nullptr);
    return out;
  }
  const WidePasses& passes = *wide_passes;
  WideConstraints wide;
  wide.Pack(out.constraints, order);
  const std::size_t blocks = wide.blocks.size();
  passes.warm_start(wide.blocks.data(), blocks, out.states.data());
  std::vector<Vec2> moved(out.states.size());  // the lanes read the moves since the start, as the solver makes them
  MeasureMoves(out.states, scene.start_positions, moved);
  for (int pass = 0; pass < 2; ++pass) passes.solve(wide.blocks.data(), blocks, out.states.data(), moved.data(), inv_h);
  move();
  MeasureMoves(out.states, scene.start_positions, moved);
  passes.push_out(wide.blocks.data(), blocks, moved.data(), out.push.data(), rate, max_speed, slop);
  wide.StoreImpulses(order.slot, out.contacts);
  return out;
}

// Turning bodies in a row across eight strips, touching their neighbours (most contacts inside a
// strip, some across an edge, a few far apart), with one and two points, and pairs whose two
// points coincide (the block solver gives up and they go one at a time), on static bodies too.
Scene MakeTurningScene(unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Scene scene;
  const int bodies = 400;
  for (int i = 0; i < bodies; ++i) AddBody(&scene, random, i % 50 == 0, true, {-20.0 + 0.1 * i, 2.0 * unit(random)});
  int k = 0;
  const auto add = [&](int a, int b) {
    Contact c;
    c.a = static_cast<engine::BodyIndex>(a);
    c.b = static_cast<engine::BodyIndex>(b);
    const double turn = 3.2 * unit(random);
    c.manifold.normal = {std::cos(turn), std::sin(turn)};
    c.manifold.point_count = 1 + (k % 3 != 0);
    const Vec2 middle = 0.5 * (scene.states[a].position + scene.states[b].position);
    const Vec2 along = engine::LeftPerp(c.manifold.normal);
    const double half = k % 7 == 0 ? 0.0 : 0.05 + 0.1 * (unit(random) + 1.0);  // 0: the points coincide
    c.manifold.points[0] = {middle - half * along, k % 11 == 0 ? 0.0 : 0.02 * unit(random), 0};
    c.manifold.points[1] = {middle + half * along, 0.02 * unit(random), 1};
    c.restitution = 0.2;
    c.friction = k % 5 == 0 ? 0.0 : 0.6;
    for (int p = 0; p < 2; ++p) {
      c.normal_impulse[p] = k % 4 == 1 ? 0.0 : 0.5 * (unit(random) + 1.0);
      const double edge = c.friction * c.normal_impulse[p] * (k % 12 == 4 ? 1.0 - 5e-10 : 1.0);
      c.tangent_impulse[p] = k % 4 == 0 ? edge * (k % 8 == 0 ? 1.0 : -1.0) : 0.1 * unit(random);
    }
    scene.contacts.push_back(c);
    ++k;
  };
  for (int a = 0; a + 1 < bodies; ++a) {
    add(a, a + 1);
    if (a + 3 < bodies && a % 2 == 0) add(a, a + 3);
  }
  for (int i = 0; i < 12; ++i) add(i, bodies - 1 - i);  // far apart
  for (int i = 0; i < 70; ++i) add(5, 100 + 3 * i);  // a hub: past the colours, one to a block
  return scene;
}

// RunPasses for turning contacts in strip or colour order, block-solved; without `turns`, as where
// no body's turn moves its points (the anchors fixed, no turns passed). `twins` (strip order):
// the warm start, the velocity passes and the push-out take the even and the odd strips side by
// side (the passes' twins), then the even and the odd edges, then the rest, as the solver does on
// one thread; kOddFirst hands the twins the odd strips first (either run may be the longer).
// kColourHalves (colour order): each colour's blocks cut in two halves side by side, as the
// solver does (ColourHalves).
enum class Twins { kNone, kEvenFirst, kOddFirst, kColourHalves };
Outcome RunTurningPasses(const Scene& scene, const engine::detail::ContactOrder& order,
                         const engine::detail::WidePasses* wide_passes, bool turns, Twins twins = Twins::kNone) {
  using namespace engine::detail;
  Outcome out{scene.states, std::vector<Vec2>(scene.states.size()), {}, {}, std::vector<double>(scene.states.size()),
              scene.contacts};
  PrepareSubstepConstraints<SubstepConstraint>(scene.contacts, order.slot, scene.infos, scene.states,
                                               &out.turning);
  const StepStart start{scene.start_positions, turns ? std::span<const engine::Rot>(scene.turned)
                                                     : std::span<const engine::Rot>()};
  const engine::Rot* turned = turns ? scene.turned.data() : nullptr;
  const double inv_h = 480.0, rate = 9.0, max_speed = 3.0, slop = 0.005;
  const auto move = [&] {
    for (BodyState& s : out.states) s.position += (1.0 / inv_h) * s.velocity;
  };
  if (wide_passes == nullptr) {
    const std::span<SubstepConstraint> all = out.turning;
    WarmStartAll(all, std::span<BodyState>(out.states));
    for (int pass = 0; pass < 2; ++pass) SolveContacts(all, std::span<BodyState>(out.states), start, inv_h, true);
    move();
    PushOut(all, std::span<const BodyState>(out.states), start, PushVelocities{out.push, out.push_angular}, rate,
            max_speed, slop);
    StoreImpulses<SubstepConstraint>(all, order.slot, out.contacts, nullptr);
    return out;
  }
  const WidePasses& passes = *wide_passes;
  REQUIRE(WideTurningConstraints::Fits(out.turning, order));
  WideTurningConstraints wide;
  wide.Pack(out.turning, order);
  const std::size_t blocks = wide.blocks.size();
  REQUIRE(wide.second_points.size() == blocks);
  // A block whose lanes all have one point is packed without its second points, which the passes
  // must not keep anything of (WideTurningConstraints::second_points): NaN there, the bits below
  // still match the one-at-a-time passes'.
  std::size_t unwritten = 0;
  for (std::size_t k = 0; k < blocks; ++k) {
    if (std::ranges::any_of(wide.blocks[k].two_points, [](double two) { return two != 0.0; })) continue;
    ++unwritten;
    engine::detail::TurningSecondLanes& second = wide.second_points[k];
    for (double* field : {second.base_separation, second.normal_mass, second.tangent_mass, second.normal_impulse,
                          second.tangent_impulse, second.anchor_a_x, second.anchor_a_y, second.anchor_b_x,
                          second.anchor_b_y, second.min_normal_speed, second.k11, second.k12, second.k22,
                          second.det, second.inv_det, second.inv_k11, second.inv_k22}) {
      std::fill(field, field + engine::detail::kBlockLanes, std::numeric_limits<double>::quiet_NaN());
    }
  }
  CHECK(unwritten > 0);
  const auto run = [&](std::size_t begin, std::size_t end) {
    return TurningRun{wide.blocks.data() + begin, wide.second_points.data() + begin, end - begin};
  };
  if (twins == Twins::kColourHalves) {
    REQUIRE(wide.order.strips == 0);
    // Some colour is cut: at least two blocks in one group among the colours.
    bool cut = false;
    for (std::size_t g = 0, begin = 0; g < wide.order.parallel_groups; begin = wide.order.group_ends[g++]) {
      cut = cut || wide.order.group_ends[g] - begin >= 2;
    }
    CHECK(cut);
    const auto halves = [&](auto&& twin_pass, auto&& pass) {
      ColourHalves(wide, 0, blocks, twin_pass, [&](std::uint32_t first, std::size_t count) {
        pass(wide.blocks.data() + first, wide.second_points.data() + first, count);
      });
    };
    halves([&](TurningRun one, TurningRun two) { passes.turning_warm_start_twin(one, two, out.states.data()); },
           [&](TurningBlock* b, TurningSecondLanes* s, std::size_t n) {
             passes.turning_warm_start(b, s, n, out.states.data());
           });
    std::vector<Vec2> moved(out.states.size());
    MeasureMoves(out.states, scene.start_positions, moved);
    for (int pass = 0; pass < 2; ++pass) {
      halves(
          [&](TurningRun one, TurningRun two) {
            passes.turning_solve_twin(one, two, out.states.data(), moved.data(), turned, inv_h, true, pass == 0);
          },
          [&](TurningBlock* b, TurningSecondLanes* s, std::size_t n) {
            passes.turning_solve(b, s, n, out.states.data(), moved.data(), turned, inv_h, true, pass == 0);
          });
    }
    move();
    MeasureMoves(out.states, scene.start_positions, moved);
    halves(
        [&](TurningRun one, TurningRun two) {
          passes.turning_push_out_twin(one, two, moved.data(), turned, out.push.data(), out.push_angular.data(),
                                       rate, max_speed, slop);
        },
        [&](TurningBlock* b, TurningSecondLanes* s, std::size_t n) {
          passes.turning_push_out(b, s, n, moved.data(), turned, out.push.data(), out.push_angular.data(), rate,
                                  max_speed, slop);
        });
    wide.StoreImpulses(order.slot, out.contacts);
    return out;
  }
  // The even strips end where the odd ones start, and those where the rest start.
  const bool twin = twins != Twins::kNone;
  const std::size_t odd = twin ? wide.order.group_ends.at(0) : 0, rest = twin ? wide.order.group_ends.at(1) : 0;
  const TurningRun one = twins == Twins::kOddFirst ? run(odd, rest) : run(0, odd);
  const TurningRun two = twins == Twins::kOddFirst ? run(0, odd) : run(odd, rest);
  // Where the even edges and the odd ones share no moving body, they go side by side too: so
  // they do in these scenes, whose strips are many bodies wide.
  if (twin) CHECK(wide.edges_apart);
  const bool twin_edges = twin && wide.edges_apart;
  const std::size_t far = twin_edges ? wide.order.group_ends.at(2) : rest;
  const TurningRun even_edges = run(rest, wide.odd_edges_begin), odd_edges = run(wide.odd_edges_begin, far);
  if (twin) {
    REQUIRE(wide.order.strips == 2);
    passes.turning_warm_start_twin(one, two, out.states.data());
  }
  if (twin_edges) passes.turning_warm_start_twin(even_edges, odd_edges, out.states.data());
  passes.turning_warm_start(wide.blocks.data() + far, wide.second_points.data() + far, blocks - far,
                            out.states.data());
  std::vector<Vec2> moved(out.states.size());  // the lanes read the moves since the start, as the solver makes them
  MeasureMoves(out.states, scene.start_positions, moved);
  for (int pass = 0; pass < 2; ++pass) {
    if (twin) {
      passes.turning_solve_twin(one, two, out.states.data(), moved.data(), turned, inv_h, true, pass == 0);
    }
    if (twin_edges) {
      passes.turning_solve_twin(even_edges, odd_edges, out.states.data(), moved.data(), turned, inv_h, true,
                                pass == 0);
    }
    passes.turning_solve(wide.blocks.data() + far, wide.second_points.data() + far, blocks - far,
                         out.states.data(), moved.data(), turned, inv_h, true, pass == 0);
  }
  move();
  MeasureMoves(out.states, scene.start_positions, moved);
  const auto push_out_twin = [&](TurningRun a, TurningRun b) {
    passes.turning_push_out_twin(a, b, moved.data(), turned, out.push.data(), out.push_angular.data(), rate,
                                 max_speed, slop);
  };
  if (twin) push_out_twin(one, two);
  if (twin_edges) push_out_twin(even_edges, odd_edges);
  passes.turning_push_out(wide.blocks.data() + far, wide.second_points.data() + far, blocks - far, moved.data(),
                          turned, out.push.data(), out.push_angular.data(), rate, max_speed, slop);
  wide.StoreImpulses(order.slot, out.contacts);
  return out;
}

// A pour of `count` circles (and 200 boxes) stepped 240 times; `contacts` gets how many touch then.
std::uint64_t PourHash(int lanes, int threads, bool boxes, bool rotation = false, int count = 1500,
                       std::size_t* contacts = nullptr) {
  engine::WorldDef def;
  def.rotation = rotation;
  def.sleeping = false;
  def.threads = threads;
  def.adapt_threads = false;  // the shared paths, even on a busy machine
  def.substep_features.lanes = lanes;
  engine::World world(def);
  stress::AddBoxedPour(world, count);
  if (boxes) {
    for (int i = 0; i < 200; ++i) {
      world.CreateBody(testing::Box({-4.0 + 0.5 * (i % 16), 30.0 + 0.5 * (i / 16)}, {0.4, 0.3}));
    }
  }
  for (int s = 0; s < 240; ++s) world.Step();
  if (contacts) *contacts = world.Contacts().size();
  return world.StateHash();
}

}  // namespace

TEST_CASE("wide solver: each width's passes give the bits of the one-at-a-time passes") {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Scene scene = MakeScene(seed);
    engine::detail::ContactOrder order;
    order.ByColour(testing::BodiesOf(scene.contacts), scene.infos);
    // The hub's contacts ran out of colours: some share a body, and go one to a block.
    REQUIRE(order.group_ends.size() > order.parallel_groups);
    const Outcome reference = RunPasses(scene, order, nullptr);
    // The passes did something: velocities and impulses changed, and some pair was pushed.
    CHECK_FALSE(SameBits(reference.states, scene.states));
    CHECK_FALSE(SameBits(Impulses(reference.contacts), Impulses(scene.contacts)));  // impulses stored
    bool pushed = false;
    for (const Vec2 v : reference.push) pushed = pushed || v.x != 0.0 || v.y != 0.0;
    CHECK(pushed);
    for (const engine::detail::WidePasses* passes : engine::detail::RunnableWidePasses()) {
      INFO("seed " << seed << ", " << passes->lanes << " lanes");
      const Outcome wide = RunPasses(scene, order, passes);
      CHECK(SameBits(wide.states, reference.states));
      CHECK(SameBits(wide.push, reference.push));
      CHECK(SameBits(Impulses(wide.contacts), Impulses(reference.contacts)));
    }
  }
}

TEST_CASE("wide solver: blocks packed in parts, in any order, over stale blocks, hold each constraint in its lane") {
  using engine::detail::kBlockLanes;
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Scene scene = MakeScene(seed);
    engine::detail::ContactOrder order;
    order.ByColour(testing::BodiesOf(scene.contacts), scene.infos);
    std::vector<LinearConstraint> constraints;
    engine::detail::PrepareSubstepConstraints<LinearConstraint>(scene.contacts, order.slot, scene.infos, scene.states,
                                                                &constraints);
    // A larger scene packed first: the blocks PackBlocks fills hold its numbers.
    const Scene big = MakeScene(seed + 10);
    std::vector<Contact> more = big.contacts;
    more.insert(more.end(), big.contacts.begin(), big.contacts.end());
    engine::detail::ContactOrder big_order;
    big_order.ByColour(testing::BodiesOf(more), big.infos);
    std::vector<LinearConstraint> big_constraints;
    engine::detail::PrepareSubstepConstraints<LinearConstraint>(more, big_order.slot, big.infos, big.states,
                                                                &big_constraints);
    engine::detail::WideConstraints parts;
    parts.Pack(big_constraints, big_order);
    REQUIRE(parts.blocks.size() > constraints.size() / kBlockLanes);

    parts.Layout(order);
    const auto blocks = static_cast<std::uint32_t>(parts.blocks.size());
    std::vector<std::uint32_t> starts;  // runs of 5 blocks, filled last first
    for (std::uint32_t b = 0; b < blocks; b += 5) starts.push_back(b);
    std::reverse(starts.begin(), starts.end());
    for (const std::uint32_t b : starts) parts.PackBlocks(constraints, order, b, std::min(blocks, b + 5));

    engine::detail::WideConstraints whole;
    whole.Pack(constraints, order);
    INFO("seed " << seed);
    REQUIRE(SameBits(parts.blocks, whole.blocks));
    REQUIRE(parts.lane_of == whole.lane_of);
    REQUIRE(parts.lead_body == whole.lead_body);
    REQUIRE(parts.lead_fixed == whole.lead_fixed);
    REQUIRE(parts.order.group_ends == whole.order.group_ends);

    // Each constraint in its lane, the parallel colours four to a block in order, the rest one
    // to a block; every other lane zero on body 0; each block's lead the body its first lane's
    // constraint moves (b where a is fixed).
    std::vector<int> filled(blocks * kBlockLanes, 0);
    std::uint32_t begin = 0;
    for (std::size_t g = 0; g < order.group_ends.size(); ++g) {
      const std::uint32_t lanes = g < order.parallel_groups ? kBlockLanes : 1;
      const std::uint32_t first_block = g == 0 ? 0 : parts.order.group_ends[g - 1];
      for (std::uint32_t j = begin; j < order.group_ends[g]; ++j) {
        const std::uint32_t expected = (first_block + (j - begin) / lanes) * kBlockLanes + (j - begin) % lanes;
        REQUIRE(parts.lane_of[j] == expected);
        const engine::detail::LinearBlock& block = parts.blocks[expected / kBlockLanes];
        const std::uint32_t lane = expected % kBlockLanes;
        const LinearConstraint& c = constraints[j];
        REQUIRE(block.a[lane] == static_cast<std::int32_t>(c.a));
        REQUIRE(block.b[lane] == static_cast<std::int32_t>(c.b));
        REQUIRE(block.normal_x[lane] == c.normal.x);
        REQUIRE(block.normal_y[lane] == c.normal.y);
        REQUIRE(block.inv_mass_a[lane] == c.inv_mass_a);
        REQUIRE(block.inv_mass_b[lane] == c.inv_mass_b);
        REQUIRE(block.normal_mass[lane] == c.normal_mass);
        REQUIRE(block.base_separation[lane] == c.base_separation);
        REQUIRE(block.normal_impulse[lane] == c.normal_impulse);
        REQUIRE(block.tangent_impulse[lane] == c.tangent_impulse);
        REQUIRE(block.friction[lane] == c.friction);
        if (lane == 0) {
          const bool fixed = c.inv_mass_a == 0.0;
          REQUIRE(parts.lead_body[expected / kBlockLanes] == (fixed ? c.b : c.a));
          REQUIRE(parts.lead_fixed[expected / kBlockLanes] == (fixed ? c.a : engine::kNoBody));
        }
        filled[expected] = 1;
      }
      begin = order.group_ends[g];
    }
    for (std::uint32_t k = 0; k < blocks; ++k) {
      const engine::detail::LinearBlock& block = parts.blocks[k];
      REQUIRE(filled[k * kBlockLanes] == 1);  // lane 0 is never padding
      for (std::uint32_t lane = 0; lane < kBlockLanes; ++lane) {
        if (filled[k * kBlockLanes + lane]) continue;
        for (const double x : {block.normal_x[lane], block.normal_y[lane], block.inv_mass_a[lane],
                               block.inv_mass_b[lane], block.normal_mass[lane], block.base_separation[lane],
                               block.normal_impulse[lane], block.tangent_impulse[lane], block.friction[lane]}) {
          REQUIRE(std::signbit(x) == false);
          REQUIRE(x == 0.0);
        }
        REQUIRE(block.a[lane] == 0);
        REQUIRE(block.b[lane] == 0);
      }
    }
    // The scene has contacts with a fixed body (leads by b) and between moving ones.
    CHECK(std::count(parts.lead_fixed.begin(), parts.lead_fixed.end(), engine::kNoBody) > 0);
    CHECK(std::count(parts.lead_fixed.begin(), parts.lead_fixed.end(), engine::kNoBody) <
          static_cast<long>(blocks));
  }
}

TEST_CASE("wide solver: the blocks from b to e hold the constraints from FirstConstraint(b) to FirstConstraint(e)") {
  using engine::detail::kBlockLanes;
  for (const unsigned seed : {1u, 2u, 3u}) {
    const Scene scene = MakeScene(seed);
    engine::detail::ContactOrder order;
    order.ByColour(testing::BodiesOf(scene.contacts), scene.infos);
    REQUIRE(order.group_ends.size() > order.parallel_groups);  // blocks of one constraint too
    std::vector<LinearConstraint> constraints;
    engine::detail::PrepareSubstepConstraints<LinearConstraint>(scene.contacts, order.slot, scene.infos, scene.states,
                                                                &constraints);
    engine::detail::WideConstraints wide;
    wide.Pack(constraints, order);
    const auto blocks = static_cast<std::uint32_t>(wide.blocks.size());
    INFO("seed " << seed);
    CHECK(wide.FirstConstraint(0, order) == 0);
    CHECK(wide.FirstConstraint(blocks, order) == constraints.size());
    // Where Pack put each constraint (lane_of) says which block holds it.
    for (std::uint32_t k = 0; k < blocks; ++k) {
      const std::uint32_t first = wide.FirstConstraint(k, order), end = wide.FirstConstraint(k + 1, order);
      REQUIRE(first < end);  // every block holds at least one constraint
      for (std::uint32_t j = first; j < end; ++j) REQUIRE(wide.lane_of[j] / kBlockLanes == k);
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

TEST_CASE("wide solver: each width's turning passes give the bits of the one-at-a-time passes") {
  for (const auto& [seed, by_colour] : {std::pair{1u, false}, {2u, false}, {3u, false}, {1u, true}, {2u, true}}) {
    INFO((by_colour ? "colour order" : "strip order"));
    const Scene scene = MakeTurningScene(seed);
    engine::detail::ContactOrder order;
    if (by_colour) {
      order.ByColour(testing::BodiesOf(scene.contacts), scene.infos);
    } else {
      order.InStrips(scene.contacts, scene.infos, scene.states, {0.0, -9.8});
    }
    const Outcome turning = RunTurningPasses(scene, order, nullptr, true);
    for (const bool turns : {true, false}) {
      INFO((turns ? "with turns" : "without turns"));
      const Outcome reference = turns ? turning : RunTurningPasses(scene, order, nullptr, false);
      CHECK_FALSE(SameBits(reference.states, scene.states));
      CHECK_FALSE(SameBits(Impulses(reference.contacts), Impulses(scene.contacts)));  // impulses stored
      bool pushed = false;
      for (const double w : reference.push_angular) pushed = pushed || w != 0.0;
      CHECK(pushed);
      // The scene's bodies have turned: the separations, so the answers, differ with the turns.
      if (!turns) CHECK_FALSE(SameBits(reference.push, turning.push));
      for (const engine::detail::WidePasses* passes : engine::detail::RunnableWidePasses()) {
        // In strip order, also with the even and the odd strips side by side (twins), either
        // first; in colour order, also with each colour's halves side by side.
        for (const Twins twins : {Twins::kNone, Twins::kEvenFirst, Twins::kOddFirst, Twins::kColourHalves}) {
          if (by_colour != (twins == Twins::kNone || twins == Twins::kColourHalves)) continue;
          INFO("seed " << seed << ", " << passes->lanes << " lanes, twins " << static_cast<int>(twins));
          const Outcome wide = RunTurningPasses(scene, order, passes, turns, twins);
          CHECK(SameBits(wide.states, reference.states));
          CHECK(SameBits(wide.push, reference.push));
          CHECK(SameBits(wide.push_angular, reference.push_angular));
          CHECK(SameBits(Impulses(wide.contacts), Impulses(reference.contacts)));
        }
      }
    }
  }
}

TEST_CASE("wide solver: runs of constraints share a body only where it moves in both") {
  using engine::detail::ShareMovingBody;
  std::vector<engine::SubstepConstraint> constraints(4);
  const auto set = [&](std::size_t j, engine::BodyIndex a, engine::BodyIndex b, bool b_moves) {
    constraints[j].a = a;
    constraints[j].b = b;
    constraints[j].inv_mass_a = 1.0;
    constraints[j].inv_mass_b = b_moves ? 0.5 : 0.0;
  };
  set(0, 1, 2, true);
  set(1, 3, 0, false);  // body 0 is static: held fixed wherever it appears
  set(2, 4, 0, false);
  set(3, 5, 2, true);
  using Run = std::pair<std::uint32_t, std::uint32_t>;
  const Run first_two[] = {{0, 2}}, third[] = {{2, 3}}, fourth[] = {{3, 4}}, third_and_fourth[] = {{2, 3}, {3, 4}};
  std::vector<engine::BodyIndex> scratch;
  CHECK_FALSE(ShareMovingBody(constraints, first_two, third, &scratch));  // only the static body
  CHECK(ShareMovingBody(constraints, first_two, fourth, &scratch));       // body 2 moves in both
  CHECK(ShareMovingBody(constraints, first_two, third_and_fourth, &scratch));
  CHECK(ShareMovingBody(constraints, fourth, first_two, &scratch));
  CHECK_FALSE(ShareMovingBody(constraints, third, fourth, &scratch));
}

TEST_CASE("wide solver: turning contacts go by colour only where every moving body in them is a circle") {
  std::vector<BodyInfo> infos(4);
  infos[0].is_static = true;
  infos[0].shape.type = engine::ShapeType::kBox;  // static: it takes no impulse
  infos[1].shape.type = engine::ShapeType::kCircle;
  infos[2].shape.type = engine::ShapeType::kCircle;
  infos[3].shape.type = engine::ShapeType::kBox;
  std::vector<Contact> contacts(2);
  contacts[0].a = 0, contacts[0].b = 1;
  contacts[1].a = 1, contacts[1].b = 2;
  using engine::detail::SubstepSolver;
  using testing::BodiesOf;
  CHECK(SubstepSolver::AllRound(BodiesOf(contacts), infos));
  contacts.emplace_back();
  contacts[2].a = 2, contacts[2].b = 3;
  CHECK_FALSE(SubstepSolver::AllRound(BodiesOf(contacts), infos));
  infos[3].is_kinematic = true;  // a kinematic box takes no impulse either
  CHECK(SubstepSolver::AllRound(BodiesOf(contacts), infos));
}

TEST_CASE("wide solver: a turning pour steps to the same hash in lanes and on two threads") {
  // Circles alone go by colour; with boxes among them, in strips (SubstepSolver::AllRound).
  for (const bool boxes : {false, true}) {
    INFO((boxes ? "circles and boxes, in strips" : "circles, by colour"));
    std::size_t contacts = 0;
    const std::uint64_t one_at_a_time = PourHash(1, 1, boxes, true, 2200, &contacts);
    // Enough contacts for either order, which the turning lanes take.
    REQUIRE(contacts >= engine::detail::SubstepSolver::kMinStripContacts);
    // The widest lanes here (each width is checked pass by pass above), on one thread and on two.
    CHECK(PourHash(0, 1, boxes, true, 2200) == one_at_a_time);
    CHECK(PourHash(0, 2, boxes, true, 2200) == one_at_a_time);
  }
}
