// Determinism: the same scene and events give the same state hash, run after run.
#include <catch2/catch.hpp>

#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "game/commands.h"
#include "game/default_scene.h"
#include "game/session.h"
#include "world_builders.h"

namespace {

std::uint64_t RunDefaultScene(int steps, engine::BroadPhaseType broad_phase) {
  game::Expected<game::RunInput> input = game::LoadRunInput({});
  REQUIRE(input.HasValue());
  input.Value().scene.world.broad_phase = broad_phase;
  game::Session session(input.Value().scene, input.Value().events, 800, 600);
  for (int i = 0; i < steps; ++i) session.Step();
  return session.World().StateHash();
}

}  // namespace

TEST_CASE("the state hash is FNV-1a 64 over the state's little-endian bytes", "[determinism]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(testing::Circle({1.5, -2.0}, 0.5, {0.25, 3.0}));
  // Reference: FNV-1a written out over the bytes of the six doubles.
  std::uint64_t expected = 0xcbf29ce484222325ULL;
  for (double v : {1.5, -2.0, 0.25, 3.0, 0.0, 0.0}) {
    unsigned char bytes[8];
    std::memcpy(bytes, &v, 8);  // x86-64 and every target we build for are little-endian
    for (unsigned char b : bytes) expected = (expected ^ b) * 0x100000001b3ULL;
  }
  CHECK(world.StateHash() == expected);
}

TEST_CASE("the same run twice gives the same hash", "[determinism]") {
  const auto first = RunDefaultScene(600, engine::BroadPhaseType::kAuto);
  const auto second = RunDefaultScene(600, engine::BroadPhaseType::kAuto);
  CHECK(first == second);
  CHECK(first != RunDefaultScene(599, engine::BroadPhaseType::kAuto));
}

TEST_CASE("the broad phase chosen does not change the result", "[determinism]") {
  const auto all_pairs = RunDefaultScene(600, engine::BroadPhaseType::kAllPairs);
  CHECK(RunDefaultScene(600, engine::BroadPhaseType::kSweepAndPrune) == all_pairs);
}

TEST_CASE("golden hash of the default scene after 600 steps", "[determinism]") {
  // Pinned on purpose: a change to the physics, the default scene or its demo script changes
  // this value, and updating it must be a deliberate act (Box2D's determinism test does the same).
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016" PRIx64,
                RunDefaultScene(600, engine::BroadPhaseType::kAuto));
  CHECK(std::string(hash) == "d61735a3d7d61f19");
}
