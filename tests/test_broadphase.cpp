// Sweep and prune must report exactly the pairs an all-pairs AABB test reports.
#include <catch2/catch.hpp>

#include <random>

#include "engine/broadphase.h"
#include "engine/world.h"

namespace {

// Boxes on a coarse grid of integer sizes and positions, so that exactly touching edges (equal
// endpoint values, the case insertion sort must order right) happen often.
std::vector<engine::AABB> RandomBoxes(std::mt19937_64& rng, int n, double extent) {
  std::uniform_int_distribution<int> cell(0, static_cast<int>(extent));
  std::uniform_int_distribution<int> size(1, 3);
  std::vector<engine::AABB> boxes(n);
  for (auto& b : boxes) {
    b.lower = {static_cast<double>(cell(rng)), static_cast<double>(cell(rng))};
    b.upper = b.lower + engine::Vec2{static_cast<double>(size(rng)), static_cast<double>(size(rng))};
  }
  return boxes;
}

// Every box takes a small random step (sometimes none, sometimes a jump), as bodies do.
void Move(std::mt19937_64& rng, std::vector<engine::AABB>& boxes) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<double> nudge(-0.3, 0.3);
  std::uniform_int_distribution<int> jump(-5, 5);
  for (auto& b : boxes) {
    const int k = kind(rng);
    engine::Vec2 d;
    if (k < 6) d = {nudge(rng), nudge(rng)};
    if (k == 9) d = {static_cast<double>(jump(rng)), static_cast<double>(jump(rng))};
    b.lower += d;
    b.upper += d;
  }
}

}  // namespace

TEST_CASE("sweep and prune equals all pairs on random moving scenes", "[broadphase]") {
  std::mt19937_64 rng(12345);
  for (int n : {2, 3, 10, 100, 500, 2000}) {
    auto boxes = RandomBoxes(rng, n, 2.0 * std::sqrt(static_cast<double>(n)) + 2.0);
    engine::SweepAndPrune sap;
    std::vector<engine::BodyPair> expected, actual;
    const int steps = n >= 2000 ? 20 : 60;
    std::size_t pairs_seen = 0;
    for (int step = 0; step < steps; ++step) {
      engine::FindPairsAllPairs(boxes, &expected);
      sap.FindPairs(boxes, &actual);
      INFO("n = " << n << ", step " << step);
      REQUIRE(actual == expected);
      pairs_seen += expected.size();
      Move(rng, boxes);
    }
    CHECK(pairs_seen > 0);  // the scenes are dense enough to test something
  }
}

TEST_CASE("sweep and prune: exactly touching boxes are a pair, a hair apart are not", "[broadphase]") {
  std::vector<engine::AABB> boxes = {{{0, 0}, {1, 1}}, {{1, 0}, {2, 1}}, {{2.0000001, 0}, {3, 1}}};
  engine::SweepAndPrune sap;
  std::vector<engine::BodyPair> pairs;
  sap.FindPairs(boxes, &pairs);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == engine::BodyPair{0, 1});
}

TEST_CASE("sweep and prune follows bodies added between steps", "[broadphase]") {
  std::vector<engine::AABB> boxes = {{{0, 0}, {1, 1}}};
  engine::SweepAndPrune sap;
  std::vector<engine::BodyPair> pairs;
  sap.FindPairs(boxes, &pairs);
  CHECK(pairs.empty());
  boxes.push_back({{0.5, 0.5}, {2, 2}});
  sap.FindPairs(boxes, &pairs);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == engine::BodyPair{0, 1});
}

TEST_CASE("sweep and prune: a coherent step costs few swaps", "[broadphase]") {
  std::mt19937_64 rng(7);
  auto boxes = RandomBoxes(rng, 1000, 60);
  engine::SweepAndPrune sap;
  std::vector<engine::BodyPair> pairs;
  sap.FindPairs(boxes, &pairs);  // the first sort pays for the random order
  const auto first = sap.LastSwapCount();
  for (auto& b : boxes) {
    b.lower.x += 1e-3;
    b.upper.x += 1e-3;
  }
  sap.FindPairs(boxes, &pairs);
  CHECK(first > 10000);
  CHECK(sap.LastSwapCount() == 0);  // everything moved alike: the order is unchanged
}
