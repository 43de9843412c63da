// WorldDef::threads: the rigid step (narrow phase, the contact passes group by group) gives the
// same bits on one, two and three threads, in the axis-aligned game, with rotation, and with
// bodies made of parts; and a group's constraints never share a moving body.
#include <catch2/catch.hpp>
#include <algorithm>
#include <bit>
#include <memory>
#include <cmath>
#include <string>
#include <set>
#include <vector>

#include "bench/stress_scenes.h"
#include "contact_bodies.h"
#include "engine/world.h"
#include "narrow_phase/narrow_phase.h"
#include "parallel/worker_pool.h"
#include "solver/constraint_groups.h"
#include "solver/contact_order.h"
#include "solver/substep_solver.h"
#include "world_builders.h"

namespace {

// Every body's info and state, in slot order, as the engine's internal passes take them.
struct BodyLists {
  std::vector<engine::BodyInfo> infos;
  std::vector<engine::BodyState> states;
};

BodyLists BodiesOf(const engine::World& world) {
  BodyLists bodies;
  for (std::size_t i = 0; i < world.BodyCount(); ++i) {
    const engine::BodyId id{static_cast<engine::BodyIndex>(i)};
    bodies.infos.push_back(world.Info(id));
    bodies.states.push_back(world.State(id));
  }
  return bodies;
}

// A world on `threads` threads that always shares its steps among them (the shared paths are
// what these tests check, even on a busy machine), sleeping off, turning or not.
engine::WorldDef SharedDef(int threads, bool rotation) {
  engine::WorldDef def;
  def.rotation = rotation;
  def.sleeping = false;
  def.threads = threads;
  def.adapt_threads = false;
  return def;
}

// A pour of `count` circles into a box, stepped `steps` times: about 2.3 contacts a circle once
// it lies, enough that the narrow phase and every colour of the solve are shared out.
std::uint64_t PourHash(int count, bool rotation, int threads, int steps) {
  const engine::WorldDef def = SharedDef(threads, rotation);
  engine::World world(def);
  stress::AddBoxedPour(world, count);
  for (int s = 0; s < steps; ++s) world.Step();
  return world.StateHash();
}

// Turning hexagons and boxes (bodies made of parts, the narrow phase's other loop) on a floor.
std::uint64_t PartsPileHash(int threads) {
  const engine::WorldDef def = SharedDef(threads, true);
  engine::World world(def);
  world.CreateBody(testing::Floor(100.0));
  // 3 600 bodies in rows of 90: past NarrowPhase's 4 096 pairs (and the strip order's 4 096
  // contacts) once they touch.
  for (int i = 0; i < 3600; ++i) {
    const double x = -40.5 + 0.9 * (i % 90) + 0.1 * ((i / 90) % 2);
    const double y = 0.6 + 0.82 * (i / 90);
    if (i % 2 == 0) {
      world.CreateBody(testing::Box({x, y}, {0.7, 0.5}));
      continue;
    }
    engine::BodyDef hexagon;
    hexagon.position = {x, y};
    engine::ShapePart outline;
    for (int k = 0; k < 6; ++k) {
      const double a = k * std::acos(-1.0) / 3.0;
      outline.points.push_back({0.4 * std::cos(a), 0.4 * std::sin(a)});
    }
    hexagon.parts.push_back(outline);
    world.CreateBody(hexagon);
  }
  for (int s = 0; s < 40; ++s) world.Step();
  REQUIRE(world.Contacts().size() > 4096);
  return world.StateHash();
}

}  // namespace

TEST_CASE("the narrow phase writes each contact's bodies beside it, on one thread and shared out",
          "[parallel][narrow]") {
  // Rows of circles of radius 0.5 whose centres lie 0.9 apart along a row (they overlap) and 2 apart
  // across (they do not touch): every pair of row neighbours touches, no pair across rows does.
  constexpr int kColumns = 100, kRows = 60;
  std::vector<engine::BodyState> states(kColumns * kRows);
  std::vector<engine::BodyInfo> infos(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    states[i].position = {0.9 * static_cast<double>(i % kColumns), 2.0 * static_cast<double>(i / kColumns)};
    infos[i].shape.type = engine::ShapeType::kCircle;
    infos[i].shape.radius = 0.5;
  }
  const auto index = [](int row, int column) { return static_cast<engine::BodyIndex>(row * kColumns + column); };
  std::vector<engine::BodyPair> pairs, touching;
  for (int row = 0; row < kRows; ++row) {
    for (int column = 0; column < kColumns; ++column) {
      if (column + 1 < kColumns) {
        pairs.push_back({index(row, column), index(row, column + 1)});
        touching.push_back(pairs.back());
      }
      if (row + 1 < kRows) pairs.push_back({index(row, column), index(row + 1, column)});
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::sort(touching.begin(), touching.end());
  REQUIRE(pairs.size() > 4096);  // past the narrow phase's least to share out
  const std::vector<std::shared_ptr<const engine::detail::BodyGeometry>> geometries(states.size());
  const std::vector<double> margins(states.size(), 0.0);
  const std::vector<engine::Rot> box_turns(states.size());  // no boxes: not read
  for (const int threads : {1, 2, 3}) {
    INFO(threads << " threads");
    engine::detail::WorkerPool pool(threads);
    engine::detail::NarrowPhase narrow_phase;
    // Several steps: from the second on, each contact carries the impulse its pair had the step
    // before, in every thread's part (each starts its walk through the last step's contacts at
    // its own first pair).
    for (int step = 0; step < 6; ++step) {
      INFO("step " << step);
      narrow_phase.Update(pairs, states, infos, geometries, margins, box_turns, false, pool);
      std::vector<engine::Contact>& contacts = narrow_phase.Contacts();
      const std::span<const engine::BodyPair> bodies = narrow_phase.ContactPairs();
      REQUIRE(contacts.size() == touching.size());
      REQUIRE(bodies.size() == contacts.size());
      for (std::size_t i = 0; i < contacts.size(); ++i) {
        REQUIRE(contacts[i].a == touching[i].a);
        REQUIRE(contacts[i].b == touching[i].b);
        REQUIRE(bodies[i] == touching[i]);
        // Last step's, as written below (none at the first step).
        REQUIRE(contacts[i].normal_impulse[0] == (step == 0 ? 0.0 : 1000.0 * (step - 1) + static_cast<double>(i)));
        contacts[i].normal_impulse[0] = 1000.0 * step + static_cast<double>(i);
      }
    }
  }
}

TEST_CASE("a pour steps to the same bits on one, two and three threads", "[parallel][solver]") {
  for (const bool rotation : {false, true}) {
    INFO((rotation ? "with rotation" : "axis-aligned"));
    // 2 500 circles: with rotation, past SubstepSolver::kMinStripContacts (the strip order).
    const std::uint64_t one = PourHash(2500, rotation, 1, 90);
    CHECK(PourHash(2500, rotation, 2, 90) == one);
    CHECK(PourHash(2500, rotation, 3, 90) == one);
  }
}

// The contact events of a pour, step by step, as text: who began and ended touching, where, and
// how fast (every bit of the numbers).
std::string PourEvents(int threads, std::size_t* most_contacts) {
  const engine::WorldDef def = SharedDef(threads, false);
  engine::World world(def);
  stress::AddBoxedPour(world, 2500);
  std::string log;
  *most_contacts = 0;
  const auto id = [](engine::BodyId b) { return std::to_string(b.index) + "." + std::to_string(b.generation); };
  const auto bits = [](double x) { return std::to_string(std::bit_cast<std::uint64_t>(x)); };
  for (int s = 0; s < 90; ++s) {
    world.Step();
    *most_contacts = std::max(*most_contacts, world.Contacts().size());
    const engine::StepEvents& events = world.Events();
    for (const engine::ContactBeginEvent& e : events.contact_begin) {
      log += "begin " + id(e.a) + " " + id(e.b) + " " + bits(e.point.x) + " " + bits(e.point.y) + " " +
             bits(e.approach_speed) + "\n";
    }
    for (const engine::ContactEndEvent& e : events.contact_end) log += "end " + id(e.a) + " " + id(e.b) + "\n";
    log += "hits " + std::to_string(events.hits.size()) + "\n";
  }
  return log;
}

TEST_CASE("a pour's contact events are the same on one, two and three threads", "[parallel][events]") {
  std::size_t contacts = 0;
  const std::string one = PourEvents(1, &contacts);
  CHECK(contacts > 4096);  // the touch test is shared out past 4 096 contacts
  CHECK(std::count(one.begin(), one.end(), '\n') > 5000);  // thousands of circles landed
  for (const int threads : {2, 3}) {
    CAPTURE(threads);
    CHECK(PourEvents(threads, &contacts) == one);
  }
}

// A pour of circles that cannot turn, in a world with rotation on, until a circle that can turn
// drops in: the solver switches from the axis-aligned constraints to the turning ones mid-run.
std::uint64_t StartsTurningHash(int threads, std::size_t* contacts_before) {
  const engine::WorldDef def = SharedDef(threads, true);
  engine::World world(def);
  stress::AddContainer(world, 12.0, 24.0);
  for (int i = 0; i < 2500; ++i) {
    engine::BodyDef circle;
    circle.shape.radius = 0.1;
    circle.position = {-5.5 + 0.22 * (i % 50) + 0.01 * ((i / 50) % 2), 0.2 + 0.22 * (i / 50)};
    circle.fixed_rotation = true;
    world.CreateBody(circle);
  }
  for (int s = 0; s < 60; ++s) world.Step();
  *contacts_before = world.Contacts().size();
  engine::BodyDef turning;
  turning.shape.radius = 0.1;
  turning.position = {0.0, 12.0};  // just above the pile: it lands and the pile shifts under it
  world.CreateBody(turning);
  for (int s = 0; s < 60; ++s) world.Step();
  return world.StateHash();
}

TEST_CASE("a world that starts turning mid-run steps to the same bits on one and two threads",
          "[parallel][solver]") {
  // On two threads the axis-aligned steps find shock propagation's levels beside the colouring,
  // the turning steps after from their constraints: the switch must not change the bits. (A stale
  // "levels found" flag carried into the turning steps did not change them here either: the
  // settled pile's levels stay the same step to step.)
  std::size_t contacts = 0;
  const std::uint64_t one = StartsTurningHash(1, &contacts);
  CHECK(contacts >= engine::detail::SubstepSolver::kMinSideBySideConstraints);
  CHECK(StartsTurningHash(2, &contacts) == one);
}

TEST_CASE("a pile of bodies made of parts steps to the same bits on one and two threads", "[parallel][solver]") {
  const std::uint64_t one = PartsPileHash(1);
  CHECK(PartsPileHash(2) == one);
  CHECK(PartsPileHash(3) == one);
}

TEST_CASE("a turning pyramid of boxes steps to the same bits on one, two and three threads", "[parallel][solver]") {
  // Boxes that turn go in strips (StripContacts), each strip whole to one thread, from
  // kMinSharedConstraints contacts: a pyramid of base 60 has about 5 400.
  const auto hash = [](int threads, std::size_t* contacts) {
    const engine::WorldDef def = SharedDef(threads, true);
    engine::World world(def);
    stress::AddPyramid(world, 60);
    for (int s = 0; s < 30; ++s) world.Step();
    *contacts = world.Contacts().size();
    return world.StateHash();
  };
  std::size_t contacts = 0;
  const std::uint64_t one = hash(1, &contacts);
  CHECK(contacts >= engine::detail::kMinSharedConstraints);
  CHECK(hash(2, &contacts) == one);
  CHECK(hash(3, &contacts) == one);
}

TEST_CASE("no two contacts of a colour share a moving body, and the groups cover every contact once",
          "[parallel][solver]") {
  engine::WorldDef def;
  def.sleeping = false;
  engine::World world(def);
  stress::AddBoxedPour(world, 1500);
  for (int s = 0; s < 90; ++s) world.Step();
  const std::vector<engine::Contact>& contacts = world.Contacts();
  REQUIRE(contacts.size() > 2000);
  std::vector<engine::BodyInfo> infos;
  for (std::size_t i = 0; i < world.BodyCount(); ++i) {
    infos.push_back(world.Info(engine::BodyId{static_cast<engine::BodyIndex>(i)}));
  }
  engine::detail::ContactOrder order;
  order.ByColour(testing::BodiesOf(contacts), infos);
  REQUIRE(order.group_ends.back() == contacts.size());
  // Each slot taken once.
  std::vector<int> taken(contacts.size(), 0);
  for (const std::uint32_t s : order.slot) ++taken[s];
  CHECK(std::count(taken.begin(), taken.end(), 1) == static_cast<long>(contacts.size()));
  std::vector<std::uint32_t> contact_at(contacts.size());
  for (std::uint32_t i = 0; i < contacts.size(); ++i) contact_at[order.slot[i]] = i;
  std::uint32_t begin = 0;
  for (std::size_t g = 0; g < order.group_ends.size(); ++g) {
    std::set<engine::BodyIndex> bodies;
    bool shared = false;
    for (std::uint32_t s = begin; s < order.group_ends[g]; ++s) {
      const engine::Contact& c = contacts[contact_at[s]];
      for (const engine::BodyIndex b : {c.a, c.b}) {
        if (engine::HasInfiniteMass(infos[b])) continue;
        shared = shared || !bodies.insert(b).second;
      }
    }
    if (g < order.parallel_groups) CHECK_FALSE(shared);
    begin = order.group_ends[g];
  }
}

TEST_CASE("strip order: the groups solved side by side share no moving body, and every contact is in one",
          "[parallel][solver]") {
  engine::WorldDef def;
  def.rotation = true;
  def.sleeping = false;
  engine::World world(def);
  stress::AddBoxedPour(world, 2500);
  for (int s = 0; s < 90; ++s) world.Step();
  const std::vector<engine::Contact>& contacts = world.Contacts();
  REQUIRE(contacts.size() >= engine::detail::SubstepSolver::kMinStripContacts);
  const auto [infos, states] = BodiesOf(world);
  engine::detail::ContactOrder order;
  order.InStrips(contacts, infos, states, def.gravity);
  const engine::detail::StripGroups groups(engine::detail::ContactOrder::kStrips);
  REQUIRE(order.group_ends.size() == groups.far + 1);
  REQUIRE(order.group_ends.back() == contacts.size());
  std::vector<std::uint32_t> contact_at(contacts.size(), 0);
  std::vector<int> taken(contacts.size(), 0);
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    ++taken[order.slot[i]];
    contact_at[order.slot[i]] = i;
  }
  CHECK(std::count(taken.begin(), taken.end(), 1) == static_cast<long>(contacts.size()));
  // Within the slots [begin, end), every contact comes in contact order.
  const auto group_range = [&](std::uint32_t g) {
    return std::pair{g == 0 ? 0u : order.group_ends[g - 1], order.group_ends[g]};
  };
  // Which group of the phase each moving body was touched by: none may be touched by two.
  const std::uint32_t phases[] = {0, groups.strips, groups.strips + groups.even_edges, groups.far};
  std::size_t inside_strips = 0;
  for (int phase = 0; phase < 3; ++phase) {
    std::vector<int> toucher(infos.size(), -1);
    bool shared = false;
    for (std::uint32_t g = phases[phase]; g < phases[phase + 1]; ++g) {
      const auto [begin, end] = group_range(g);
      if (phase == 0) inside_strips += end - begin;
      for (std::uint32_t s = begin; s < end; ++s) {
        if (s > begin) CHECK(contact_at[s - 1] < contact_at[s]);
        const engine::Contact& c = contacts[contact_at[s]];
        for (const engine::BodyIndex b : {c.a, c.b}) {
          if (engine::HasInfiniteMass(infos[b])) continue;
          shared = shared || (toucher[b] != -1 && toucher[b] != static_cast<int>(g));
          toucher[b] = static_cast<int>(g);
        }
      }
    }
    INFO("phase " << phase);
    CHECK_FALSE(shared);
  }
  // Upright strips of a pile: most contacts lie inside one.
  CHECK(inside_strips > contacts.size() * 8 / 10);
}

TEST_CASE("strip order: the strips of a pyramid hold about as many contacts each, cut alike on any number of threads",
          "[parallel][solver]") {
  // A pyramid is tall in its middle and low at its sides. Strips of equal width gave the outer
  // strips of a pyramid of base 40 70 contacts each and the middle ones 460, and the lanes that
  // solve four strips side by side waited on the longest (three lanes in five busy). Cut where
  // they hold about as many contacts each (the ends weighed by how many of their strip's stay
  // inside it), only the contacts across the edges between strips keep them apart. The cut
  // counts in integers: the same with any number of threads.
  for (const int base : {40, 100}) {
    engine::WorldDef def;
    def.rotation = true;
    def.sleeping = false;
    engine::World world(def);
    stress::AddPyramid(world, base);
    world.Step();
    const std::vector<engine::Contact>& contacts = world.Contacts();
    const auto [infos, states] = BodiesOf(world);
    engine::detail::ContactOrder one;
    one.InStrips(contacts, infos, states, def.gravity);
    std::uint32_t fewest = ~0u, most = 0;
    for (int g = 0; g < engine::detail::ContactOrder::kStrips; ++g) {
      const std::uint32_t size = one.group_ends[g] - (g == 0 ? 0 : one.group_ends[g - 1]);
      fewest = std::min(fewest, size);
      most = std::max(most, size);
    }
    const std::uint32_t inside = one.group_ends[engine::detail::ContactOrder::kStrips - 1];
    INFO("base " << base << ": " << contacts.size() << " contacts, " << inside << " inside strips of "
                 << fewest << " to " << most);
    CHECK(most <= 3 * fewest / 2);
    CHECK(inside >= contacts.size() * 3 / 4);
    // Past kMinSharedContacts the threads count their parts of the contacts apart.
    if (base == 100) REQUIRE(contacts.size() >= engine::detail::kMinSharedContacts);
    for (const int threads : {2, 3}) {
      engine::detail::WorkerPool pool(threads);
      engine::detail::ContactOrder shared;
      shared.InStrips(contacts, infos, states, def.gravity, &pool);
      CHECK(shared.slot == one.slot);
      CHECK(shared.group_ends == one.group_ends);
    }
  }
}

TEST_CASE("a pile that sleeps, then is woken by a falling ball, steps to the same bits on one and two threads",
          "[parallel][sleep]") {
  // 3 000 circles at rest on a floor between walls that overlap it (static pairs): past 4 096
  // pairs, the threads share the look for sleepers to wake and drop the pairs where nothing
  // moves; once the pile sleeps, a ball dropped on it wakes it, on one thread. Step by step, the
  // bits and who is awake must be the same on one and two threads.
  const auto run = [](int threads, std::vector<std::size_t>* awake_counts) {
    engine::WorldDef def;
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
    engine::World world(def);
    world.CreateBody(testing::Floor(70.0));
    world.CreateBody(testing::Static(testing::Box({-30.5, 2.0}, {1.0, 6.0})));
    world.CreateBody(testing::Static(testing::Box({30.5, 2.0}, {1.0, 6.0})));
    std::vector<engine::BodyId> ids;
    for (int i = 0; i < 3000; ++i) {
      const int row = i / 300, column = i % 300;
      const double x = -29.9 + 0.2 * column + 0.1 * (row % 2);
      ids.push_back(world.CreateBody(testing::Circle({x, 0.1 + 0.1733 * row}, 0.1)));
    }
    std::vector<std::uint64_t> hashes;
    for (int s = 0; s < 200; ++s) {
      if (s == 120) world.CreateBody(testing::Circle({0.05, 7.0}, 0.3, {0, -5}));
      world.Step();
      hashes.push_back(world.StateHash());
      std::size_t awake = 0;
      for (const engine::BodyId id : ids) awake += world.IsAwake(id) ? 1 : 0;
      awake_counts->push_back(awake);
    }
    return hashes;
  };
  std::vector<std::size_t> one_awake, two_awake;
  const std::vector<std::uint64_t> one = run(1, &one_awake);
  const std::vector<std::uint64_t> two = run(2, &two_awake);
  CHECK(two == one);
  CHECK(two_awake == one_awake);
  CHECK(one_awake[119] == 0);     // the pile slept before the ball
  CHECK(one_awake.back() > 100);  // and the ball woke it
}
