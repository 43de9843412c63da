// WorldDef::threads: the rigid step (narrow phase, the contact passes group by group) gives the
// same bits on one, two and three threads, in the axis-aligned game, with rotation, and with
// bodies made of parts; and a group's constraints never share a moving body.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <vector>

#include "bench/stress_scenes.h"
#include "engine/world.h"
#include "solver/contact_order.h"
#include "world_builders.h"

namespace {

// A pour of `count` circles into a box, stepped `steps` times: about 2.3 contacts a circle once
// it lies, enough that the narrow phase and every colour of the solve are shared out.
std::uint64_t PourHash(int count, bool rotation, int threads, int steps) {
  engine::WorldDef def;
  def.rotation = rotation;
  def.sleeping = false;
  def.threads = threads;
  engine::World world(def);
  stress::AddBoxedPour(world, count);
  for (int s = 0; s < steps; ++s) world.Step();
  return world.StateHash();
}

// Turning hexagons and boxes (bodies made of parts, the narrow phase's other loop) on a floor.
std::uint64_t PartsPileHash(int threads) {
  engine::WorldDef def;
  def.rotation = true;
  def.sleeping = false;
  def.threads = threads;
  engine::World world(def);
  world.CreateBody(testing::Floor(40.0));
  for (int i = 0; i < 900; ++i) {
    const double x = -14.0 + 0.9 * (i % 30) + 0.1 * ((i / 30) % 2);
    const double y = 0.6 + 0.9 * (i / 30);
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
  return world.StateHash();
}

}  // namespace

TEST_CASE("a pour steps to the same bits on one, two and three threads", "[parallel][solver]") {
  for (const bool rotation : {false, true}) {
    INFO((rotation ? "with rotation" : "axis-aligned"));
    const std::uint64_t one = PourHash(2000, rotation, 1, 90);
    CHECK(PourHash(2000, rotation, 2, 90) == one);
    CHECK(PourHash(2000, rotation, 3, 90) == one);
  }
}

TEST_CASE("a pile of bodies made of parts steps to the same bits on one and two threads", "[parallel][solver]") {
  const std::uint64_t one = PartsPileHash(1);
  CHECK(PartsPileHash(2) == one);
  CHECK(PartsPileHash(3) == one);
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
  order.ByColour(contacts, infos);
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
