// Every broad phase (sweep and prune, uniform grid, quadtree, AABB tree, the automatic choice) must
// report exactly the pairs an all-pairs AABB test reports, in the same order, and the world's
// result must not depend on which one runs.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>

#include "bench/stress_scenes.h"
#include "broad_phase/broad_phase.h"
#include "engine/world.h"
#include "parallel/worker_pool.h"
#include "game/scene.h"

namespace {

using engine::AABB;
using engine::BodyPair;
using engine::Vec2;

// Boxes on a coarse grid of integer sizes and positions, so that exactly touching edges (equal
// endpoint values, equal cell boundaries) happen often.
std::vector<AABB> RandomBoxes(std::mt19937_64& rng, int n, double extent) {
  std::uniform_int_distribution<int> cell(0, static_cast<int>(extent));
  std::uniform_int_distribution<int> size(1, 3);
  std::vector<AABB> boxes(n);
  for (auto& b : boxes) {
    b.lower = {static_cast<double>(cell(rng)), static_cast<double>(cell(rng))};
    b.upper = b.lower + Vec2{static_cast<double>(size(rng)), static_cast<double>(size(rng))};
  }
  return boxes;
}

// Every box takes a small random step (sometimes none, sometimes a jump), as bodies do.
void Move(std::mt19937_64& rng, std::vector<AABB>& boxes) {
  std::uniform_int_distribution<int> kind(0, 9);
  std::uniform_real_distribution<double> nudge(-0.3, 0.3);
  std::uniform_int_distribution<int> jump(-5, 5);
  for (auto& b : boxes) {
    const int k = kind(rng);
    Vec2 d;
    if (k < 6) d = {nudge(rng), nudge(rng)};
    if (k == 9) d = {static_cast<double>(jump(rng)), static_cast<double>(jump(rng))};
    b.lower += d;
    b.upper += d;
  }
}

// Integer moves keep the boxes on the grid, so touching stays common over all the steps.
void MoveOnGrid(std::mt19937_64& rng, std::vector<AABB>& boxes) {
  std::uniform_int_distribution<int> step(-1, 1);
  for (auto& b : boxes) {
    const Vec2 d{static_cast<double>(step(rng)), static_cast<double>(step(rng))};
    b.lower += d;
    b.upper += d;
  }
}

bool Touching(const AABB& a, const AABB& b) {
  return engine::Overlaps(a, b) && (a.upper.x == b.lower.x || b.upper.x == a.lower.x ||
                                    a.upper.y == b.lower.y || b.upper.y == a.lower.y);
}

// Runs the broad phase on `boxes` and requires exactly the all-pairs answer; returns the pair count.
template <class BroadPhase>
std::size_t RequireAllPairs(BroadPhase& broad_phase, const std::vector<AABB>& boxes) {
  std::vector<BodyPair> expected, actual;
  engine::FindPairsAllPairs(boxes, &expected);
  broad_phase.FindPairs(boxes, &actual);
  REQUIRE(actual.size() == expected.size());
  REQUIRE(actual == expected);
  if constexpr (std::is_same_v<BroadPhase, engine::AabbTree>) REQUIRE(broad_phase.IsValid());
  return expected.size();
}

// The automatic choice behind the same call as the structures.
struct AutoBroadPhase {
  engine::BroadPhase chooser;
  void FindPairs(std::span<const AABB> boxes, std::vector<BodyPair>* pairs,
                 std::span<const engine::PairQuota> quotas = {}) {
    chooser.FindPairs(engine::BroadPhaseType::kAuto, boxes, pairs, quotas);
  }
};

// The pair budget's rule written out plainly (engine::PairCollector): every overlapping pair is
// charged to its narrower body (the higher id between equal widths); a body charged with more
// pairs than its quota, grown by its box's area over its own (at most 256), keeps its 4 best:
// static partners first, then the deepest overlap (the lesser of the two axes), then the partner
// nearest in id, then the lower id.
std::vector<BodyPair> BudgetedPairs(const std::vector<AABB>& boxes, const std::vector<engine::PairQuota>& quotas,
                                    std::size_t* crowded) {
  std::vector<BodyPair> all;
  engine::FindPairsAllPairs(boxes, &all);
  std::vector<std::vector<BodyPair>> charged(boxes.size());
  for (const BodyPair& p : all) charged[quotas[p.a].width < quotas[p.b].width ? p.a : p.b].push_back(p);
  std::vector<BodyPair> kept;
  *crowded = 0;
  for (std::uint32_t c = 0; c < boxes.size(); ++c) {
    std::vector<BodyPair>& mine = charged[c];
    const AABB& box = boxes[c];
    const double grown =
        std::ceil(quotas[c].quota * (box.upper.x - box.lower.x) * (box.upper.y - box.lower.y) / quotas[c].area);
    if (mine.size() > std::min(grown, 256.0)) {
      ++*crowded;
      auto rank = [&](const BodyPair& p) {
        const std::uint32_t o = p.a == c ? p.b : p.a;
        const AABB& b = boxes[c];
        const AABB& q = boxes[o];
        const double depth = std::min(std::min(b.upper.x, q.upper.x) - std::max(b.lower.x, q.lower.x),
                                      std::min(b.upper.y, q.upper.y) - std::max(b.lower.y, q.lower.y));
        return std::make_tuple(!std::isinf(quotas[o].width), -depth, o < c ? c - o : o - c, o);
      };
      std::sort(mine.begin(), mine.end(), [&](const BodyPair& p, const BodyPair& q) { return rank(p) < rank(q); });
      mine.resize(engine::PairCollector::kCrowdPairs);
    }
    kept.insert(kept.end(), mine.begin(), mine.end());
  }
  std::sort(kept.begin(), kept.end(), [](BodyPair p, BodyPair q) { return p.a < q.a || (p.a == q.a && p.b < q.b); });
  return kept;
}

}  // namespace

#define BROAD_PHASES engine::SweepAndPrune, engine::UniformGrid, engine::Quadtree, engine::AabbTree, AutoBroadPhase

TEMPLATE_TEST_CASE("broad phase equals all pairs on random moving scenes", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(12345);
  for (int n : {2, 3, 10, 100, 500, 2000}) {
    auto boxes = RandomBoxes(rng, n, 2.0 * std::sqrt(static_cast<double>(n)) + 2.0);
    TestType broad_phase;
    const int steps = n >= 2000 ? 20 : 60;
    std::size_t pairs_seen = 0;
    for (int step = 0; step < steps; ++step) {
      INFO("n = " << n << ", step " << step);
      pairs_seen += RequireAllPairs(broad_phase, boxes);
      Move(rng, boxes);
    }
    CHECK(pairs_seen > 0);  // the scenes are dense enough to test something
  }
}

TEMPLATE_TEST_CASE("broad phase equals all pairs with boxes touching on an integer grid", "[broadphase]",
                   BROAD_PHASES) {
  std::mt19937_64 rng(99);
  for (int n : {50, 400, 2000}) {
    auto boxes = RandomBoxes(rng, n, std::sqrt(static_cast<double>(n)) + 2.0);
    TestType broad_phase;
    std::size_t touching = 0;
    for (int step = 0; step < 30; ++step) {
      INFO("n = " << n << ", step " << step);
      RequireAllPairs(broad_phase, boxes);
      for (int i = 0; i + 1 < n; ++i) touching += Touching(boxes[i], boxes[i + 1]);
      MoveOnGrid(rng, boxes);
    }
    CHECK(touching > 10);  // touching is common, not a lucky case
  }
}

TEMPLATE_TEST_CASE("broad phase: exactly touching boxes are a pair, a hair apart are not", "[broadphase]",
                   BROAD_PHASES) {
  // Edges, corners, and each of them on either side; the hair is one unit in the last place.
  const double hair = std::nextafter(2.0, 3.0);
  std::vector<AABB> boxes = {{{0, 0}, {1, 1}}, {{1, 0}, {2, 1}},     {{hair, 0}, {3, 1}},
                             {{1, 1}, {2, 2}}, {{0, -1}, {1, 0}},    {{-1, -1}, {0, 0}},
                             {{2, 2}, {2, 2}}, {{hair, hair}, {4, 4}}};
  TestType broad_phase;
  std::vector<BodyPair> pairs;
  broad_phase.FindPairs(boxes, &pairs);
  const std::vector<BodyPair> expected = {{0, 1}, {0, 3}, {0, 4}, {0, 5}, {1, 3}, {1, 4},
                                          {3, 6}, {4, 5}};
  CHECK(pairs == expected);
  RequireAllPairs(broad_phase, boxes);
}

TEMPLATE_TEST_CASE("broad phase follows bodies added and removed between calls", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(4);
  std::vector<AABB> boxes = {{{0, 0}, {1, 1}}};
  TestType broad_phase;
  std::vector<BodyPair> pairs;
  broad_phase.FindPairs(boxes, &pairs);
  CHECK(pairs.empty());
  boxes.push_back({{0.5, 0.5}, {2, 2}});
  broad_phase.FindPairs(boxes, &pairs);
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == BodyPair{0, 1});

  // Grow to 600 bodies a few at a time while everything moves, then shrink, then grow again.
  for (int step = 0; step < 120; ++step) {
    INFO("step " << step << ", " << boxes.size() << " bodies");
    auto more = RandomBoxes(rng, step % 7, 30);
    boxes.insert(boxes.end(), more.begin(), more.end());
    if (step == 80) boxes.resize(boxes.size() / 2);
    RequireAllPairs(broad_phase, boxes);
    Move(rng, boxes);
  }
}

TEMPLATE_TEST_CASE("broad phase: bodies teleporting far away and back", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(5);
  auto boxes = RandomBoxes(rng, 800, 60);
  const auto home = boxes;
  std::uniform_int_distribution<int> pick(0, 799);
  std::uniform_int_distribution<int> direction(0, 3);
  TestType broad_phase;
  for (int step = 0; step < 40; ++step) {
    INFO("step " << step);
    RequireAllPairs(broad_phase, boxes);
    Move(rng, boxes);
    for (int k = 0; k < 20; ++k) {
      const int i = pick(rng);
      const double far = step % 2 == 0 ? 1e6 : 1e12;
      const Vec2 jumps[4] = {{far, 0}, {-far, 0}, {0, far}, {far, -far}};
      const Vec2 d = jumps[direction(rng)];
      boxes[i].lower += d;
      boxes[i].upper += d;
      boxes[pick(rng)] = home[pick(rng)];  // and some land back among the others, on someone
    }
  }
}

TEMPLATE_TEST_CASE("broad phase: huge boxes among small ones", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(6);
  auto boxes = RandomBoxes(rng, 1000, 60);
  // A floor across the whole world, walls, a box covering everything, and one far bigger still.
  boxes.push_back({{-1e4, -2}, {1e4, 0.5}});
  boxes.push_back({{-2, -2}, {0.5, 1e3}});
  boxes.push_back({{60, -2}, {61, 1e3}});
  boxes.push_back({{-100, -100}, {200, 200}});
  boxes.push_back({{-1e9, -1e9}, {1e9, 1e9}});
  TestType broad_phase;
  for (int step = 0; step < 30; ++step) {
    INFO("step " << step);
    RequireAllPairs(broad_phase, boxes);
    Move(rng, boxes);
  }
  // Half of the boxes huge: no size is "typical".
  std::uniform_real_distribution<double> size(100, 1000);
  for (std::size_t i = 0; i < boxes.size(); i += 2) boxes[i].upper = boxes[i].lower + Vec2{size(rng), size(rng)};
  for (int step = 0; step < 10; ++step) {
    INFO("half huge, step " << step);
    RequireAllPairs(broad_phase, boxes);
    Move(rng, boxes);
  }
}

TEMPLATE_TEST_CASE("broad phase: tiny and zero-size boxes", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> cell(0, 20);
  std::uniform_int_distribution<int> kind(0, 2);
  std::vector<AABB> boxes(1500);
  for (auto& b : boxes) {
    // Points on a grid (coincident points touch), 1e-9 boxes at the same spots, unit boxes.
    b.lower = {static_cast<double>(cell(rng)), static_cast<double>(cell(rng))};
    const int k = kind(rng);
    b.upper = b.lower + (k == 0 ? Vec2{} : k == 1 ? Vec2{1e-9, 1e-9} : Vec2{1, 1});
  }
  TestType broad_phase;
  std::size_t pairs_seen = 0;
  for (int step = 0; step < 10; ++step) {
    INFO("step " << step);
    pairs_seen += RequireAllPairs(broad_phase, boxes);
    MoveOnGrid(rng, boxes);
  }
  CHECK(pairs_seen > 0);

  // Only points: every box has zero size.
  for (auto& b : boxes) b.upper = b.lower;
  for (int step = 0; step < 10; ++step) {
    INFO("points, step " << step);
    RequireAllPairs(broad_phase, boxes);
    MoveOnGrid(rng, boxes);
  }
}

TEMPLATE_TEST_CASE("broad phase: identical boxes all pair with each other", "[broadphase]", BROAD_PHASES) {
  TestType broad_phase;
  std::vector<AABB> boxes(300, AABB{{1, 2}, {3, 4}});
  CHECK(RequireAllPairs(broad_phase, boxes) == 300 * 299 / 2);
  for (auto& b : boxes) b = {{-5, -5}, {-5, -5}};  // all moved to one point
  CHECK(RequireAllPairs(broad_phase, boxes) == 300 * 299 / 2);
  // Two coincident stacks far apart.
  for (std::size_t i = 0; i < boxes.size(); i += 2) boxes[i] = {{100, 100}, {101, 101}};
  CHECK(RequireAllPairs(broad_phase, boxes) == 2 * (150 * 149 / 2));
}

TEMPLATE_TEST_CASE("pair budget: every broad phase keeps what the rule keeps, piles and all", "[broadphase]",
                   BROAD_PHASES) {
  // Boxes scattered about, and a pile of 300 around one spot (some exactly on top of each
  // other), of three widths and some static, with small quotas so that crowds form outside the
  // pile too. Whatever order a structure finds pairs in, the kept set must be the rule's.
  std::mt19937_64 rng(21);
  auto boxes = RandomBoxes(rng, 500, 40);
  std::uniform_real_distribution<double> near(-0.5, 0.5);
  for (int i = 0; i < 300; ++i) {
    const Vec2 at = i % 5 == 0 ? Vec2{20, 20} : Vec2{20 + near(rng), 20 + near(rng)};
    boxes.push_back({at, at + Vec2{1.0 + i % 3, 1.0 + i % 2}});
  }
  std::shuffle(boxes.begin(), boxes.end(), rng);
  // Some boxes grown to two or four times the body's own area: their quota grows alike.
  std::uniform_int_distribution<int> width(1, 3), quota(3, 40), kind(0, 19), growth(0, 2);
  std::vector<engine::PairQuota> quotas(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    engine::PairQuota& q = quotas[i];
    q.width = kind(rng) == 0 ? std::numeric_limits<double>::infinity() : width(rng);
    q.quota = static_cast<std::uint32_t>(quota(rng));
    const AABB& b = boxes[i];
    q.area = (b.upper.x - b.lower.x) * (b.upper.y - b.lower.y) / (1 << growth(rng));
  }
  TestType broad_phase;
  std::vector<BodyPair> pairs;
  for (int step = 0; step < 25; ++step) {
    INFO("step " << step);
    std::size_t crowded = 0;
    const std::vector<BodyPair> expected = BudgetedPairs(boxes, quotas, &crowded);
    broad_phase.FindPairs(boxes, &pairs, quotas);
    REQUIRE(pairs.size() == expected.size());
    REQUIRE(pairs == expected);
    CHECK(crowded > (step == 0 ? 250u : 0u));  // the pile, and more, while the moves scatter it
    Move(rng, boxes);
  }
}

TEMPLATE_TEST_CASE("grid and tree shared among threads: all pairs, and the budget's, as on one", "[broadphase][parallel]",
                   engine::UniformGrid, engine::AabbTree) {
  // Enough boxes that the grid shares its buckets out (past its 4 096 entries) and the tree its
  // kept candidates, moving, and a pile with small quotas so the budget crowds bodies: the pairs
  // found by two and three threads must be the rule's. A floor, a wall and a long bar, first and
  // last among the ids, are too large for the grid's cells: their pairs join the binned ones.
  std::mt19937_64 rng(5);
  auto boxes = RandomBoxes(rng, 9000, 160);
  std::uniform_real_distribution<double> near(-0.5, 0.5);
  for (int i = 0; i < 600; ++i) {
    const Vec2 at{80 + near(rng), 80 + near(rng)};
    boxes.push_back({at, at + Vec2{1.0 + i % 3, 1.0 + i % 2}});
  }
  boxes.insert(boxes.begin(), AABB{{-1, -1}, {161, 2}});
  boxes.push_back({{-1, -1}, {2, 161}});
  boxes.push_back({{40, 70}, {120, 72}});
  std::vector<engine::PairQuota> quotas(boxes.size(), engine::PairQuota{1.0, 12, 1.0});
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    quotas[i].area = (boxes[i].upper.x - boxes[i].lower.x) * (boxes[i].upper.y - boxes[i].lower.y);
  }
  for (const int threads : {2, 3}) {
    engine::detail::WorkerPool pool(threads);
    TestType grid;
    std::vector<BodyPair> all, pairs;
    for (int step = 0; step < 6; ++step) {
      INFO("threads " << threads << ", step " << step);
      engine::FindPairsAllPairs(boxes, &all);
      grid.FindPairs(boxes, &pairs, {}, &pool);
      REQUIRE(pairs == all);
      std::size_t crowded = 0;
      const std::vector<BodyPair> expected = BudgetedPairs(boxes, quotas, &crowded);
      grid.FindPairs(boxes, &pairs, quotas, &pool);
      REQUIRE(pairs == expected);
      CHECK(grid.Collector().CrowdedCount() == crowded);
      CHECK(crowded > 100);  // the pile
      Move(rng, boxes);
    }
  }
}

TEMPLATE_TEST_CASE("grid and tree shared among threads: with no crowd, the budget counts the pairs as on one",
                   "[broadphase][parallel]", engine::UniformGrid, engine::AabbTree) {
  // Quotas no body reaches: the threads hand their pairs to the budget together (past 4 096 of
  // them), and its counts must be the rule's: nothing dropped, and the most pairs charged to one
  // body counted here from all the pairs (each to its narrower body, the higher id between equals).
  std::mt19937_64 rng(11);
  auto boxes = RandomBoxes(rng, 9000, 160);
  std::vector<engine::PairQuota> quotas(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const double area = (boxes[i].upper.x - boxes[i].lower.x) * (boxes[i].upper.y - boxes[i].lower.y);
    quotas[i] = {1.0 + static_cast<double>(i % 3), engine::PairQuota::kMaxQuota, area};
  }
  for (const int threads : {2, 3}) {
    engine::detail::WorkerPool pool(threads);
    TestType structure;
    std::vector<BodyPair> all, pairs;
    for (int step = 0; step < 6; ++step) {
      INFO("threads " << threads << ", step " << step);
      engine::FindPairsAllPairs(boxes, &all);
      REQUIRE(all.size() > 4096);
      std::vector<std::uint32_t> charged(boxes.size(), 0);
      for (const BodyPair& p : all) ++charged[quotas[p.a].width < quotas[p.b].width ? p.a : p.b];
      structure.FindPairs(boxes, &pairs, quotas, &pool);
      REQUIRE(pairs == all);
      CHECK(structure.Collector().CrowdedCount() == 0);
      CHECK(structure.Collector().DroppedCount() == 0);
      CHECK(structure.Collector().MostCharged() == *std::max_element(charged.begin(), charged.end()));
      Move(rng, boxes);
    }
  }
}

TEST_CASE("grid shared among threads: a cell piled past the pair limit is scanned again on one thread, the "
          "budget's pairs", "[broadphase][parallel]") {
  // 2 000 equal boxes at one point put 2 million pairs in one cell, past what a thread may hold
  // (16 an entry): the shared scan stops and one thread scans again, handing pairs to the budget
  // as it goes. The pairs must be the budget's, as on one thread.
  std::mt19937_64 rng(17);
  auto boxes = RandomBoxes(rng, 3000, 120);
  for (int i = 0; i < 2000; ++i) boxes.push_back({{60.25, 60.25}, {61.25, 61.25}});
  std::shuffle(boxes.begin(), boxes.end(), rng);
  std::vector<engine::PairQuota> quotas(boxes.size(), engine::PairQuota{1.0, 12, 1.0});
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    quotas[i].area = (boxes[i].upper.x - boxes[i].lower.x) * (boxes[i].upper.y - boxes[i].lower.y);
  }
  std::size_t crowded = 0;
  const std::vector<BodyPair> expected = BudgetedPairs(boxes, quotas, &crowded);
  CHECK(crowded > 1900);
  for (const int threads : {1, 2, 3}) {
    INFO("threads " << threads);
    engine::detail::WorkerPool pool(threads);
    engine::UniformGrid grid;
    std::vector<BodyPair> pairs;
    grid.FindPairs(boxes, &pairs, quotas, &pool);
    REQUIRE(pairs == expected);
    CHECK(grid.Collector().CrowdedCount() == crowded);
  }
}

// Eight calls of a tree on `threads` threads, moving the boxes with move(rng, boxes, step) after
// each: every call's pairs must be all the overlapping ones and the tree valid; check(tree, all,
// step) adds the test's own expectations (`all`: the call's overlapping pairs).
template <typename Check, typename MoveBoxes>
void RequireTreeFindsAllPairs(std::mt19937_64& rng, std::vector<AABB> boxes, int threads, Check&& check,
                              MoveBoxes&& move) {
  engine::detail::WorkerPool pool(threads);
  engine::AabbTree tree;
  std::vector<BodyPair> all, pairs;
  for (int step = 0; step < 8; ++step) {
    INFO("threads " << threads << ", step " << step);
    engine::FindPairsAllPairs(boxes, &all);
    tree.FindPairs(boxes, &pairs, {}, &pool);
    REQUIRE(pairs == all);
    CHECK(tree.IsValid());
    check(tree, all, step);
    move(rng, boxes, step);
  }
}

TEST_CASE("AABB tree shared among threads: a few bodies moving, their fresh pairs as on one",
          "[broadphase][parallel]") {
  // Each call moves one box in twenty by a jump: past the 64 that the tree reinserts and queries
  // on several threads, short of the quarter past which it is built anew and traversed whole,
  // with candidates enough that their merge with the fresh pairs is shared out in runs. The
  // moved leaves go back into the branches of the tree's top on the pool's threads (a floor and
  // a wall sit above them: the tree's rotations lift wide boxes). The pairs found by one, two and
  // three threads must be all the overlapping ones, and the tree valid.
  for (const int threads : {1, 2, 3}) {
    std::mt19937_64 rng(11);
    auto boxes = RandomBoxes(rng, 4000, 130);
    boxes.insert(boxes.begin(), {AABB{{-1, -2}, {131, -1}}, AABB{{-2, -1}, {-1, 131}}});
    const auto check = [&](const engine::AabbTree& tree, const std::vector<BodyPair>& all, int step) {
      CHECK(all.size() > 4096);  // candidates enough to be merged in runs shared out
      if (step > 0) {
        CHECK(tree.LastReinsertCount() >= 64);
        CHECK(4 * tree.LastReinsertCount() <= boxes.size());
      }
    };
    RequireTreeFindsAllPairs(rng, boxes, threads, check, [](std::mt19937_64& r, std::vector<AABB>& b, int step) {
      std::uniform_int_distribution<int> jump(-4, 4);
      for (std::size_t i = static_cast<std::size_t>(step) % 20; i < b.size(); i += 20) {
        const Vec2 d{static_cast<double>(jump(r)), static_cast<double>(jump(r)) + 5.0};
        b[i].lower += d;
        b[i].upper += d;
      }
    });
  }
}

TEST_CASE("AABB tree: a handful or a tenth of the bodies moving, their fresh pairs sorted either way",
          "[broadphase][parallel]") {
  // The moved leaves' fresh pairs are sorted before they are merged into the kept candidates: by
  // comparisons when they are few, by counting (over every body) when there are one or more for
  // each 16 bodies. Three jumping boxes give a few dozen pairs, one box in ten a thousand or so
  // (2 000 boxes, each overlapping several). On two threads the merge is cut into runs where
  // the fresh pairs are looked up by binary search, which takes them sorted: the pairs must be
  // all the overlapping ones either way, with only jumping boxes reinserted.
  for (const int threads : {1, 2}) {
    for (const std::size_t every : {std::size_t{667}, std::size_t{10}}) {
      CAPTURE(every);
      std::mt19937_64 rng(17);
      const auto boxes = RandomBoxes(rng, 2000, 80);
      const auto check = [&](const engine::AabbTree& tree, const std::vector<BodyPair>& all, int step) {
        CHECK(all.size() > 4096);  // each box in six pairs or more: candidates enough to merge in runs
        if (step > 0) {  // a box jumping as it did before can stay in the box stretched ahead of it
          const std::size_t jumping = (boxes.size() + every - 1) / every;
          CHECK(tree.LastReinsertCount() <= jumping);
          CHECK(2 * tree.LastReinsertCount() >= jumping);
        }
      };
      RequireTreeFindsAllPairs(rng, boxes, threads, check, [every](std::mt19937_64& r, std::vector<AABB>& b, int) {
        std::uniform_int_distribution<int> jump(1, 4);
        for (std::size_t i = 0; i < b.size(); i += every) {
          const Vec2 d{static_cast<double>(jump(r)), static_cast<double>(jump(r)) + 5.0};
          b[i].lower += d;
          b[i].upper += d;
        }
      });
    }
  }
}

TEST_CASE("AABB tree: most bodies moving, the tree built anew, balanced, its pairs as all pairs on 1-3 threads",
          "[broadphase][parallel]") {
  // Every box jumps each call, so more than a quarter leave their fat boxes and the tree is built
  // anew by median splits: of height ceil(log2 n) exactly. The traversal of the new tree, shared
  // out on two and three threads, must find exactly the overlapping pairs.
  for (const int threads : {1, 2, 3}) {
    std::mt19937_64 rng(13);
    const auto boxes = RandomBoxes(rng, 3000, 110);
    const auto check = [&](const engine::AabbTree& tree, const std::vector<BodyPair>&, int) {
      CHECK(4 * tree.LastReinsertCount() > boxes.size());
      CHECK(tree.Height() == 12);  // 2^11 < 3000 <= 2^12
    };
    RequireTreeFindsAllPairs(rng, boxes, threads, check, [](std::mt19937_64& r, std::vector<AABB>& b, int) {
      std::uniform_int_distribution<int> jump(-3, 3);
      for (auto& box : b) {
        const Vec2 d{static_cast<double>(jump(r)), static_cast<double>(jump(r)) + 4.0};
        box.lower += d;
        box.upper += d;
      }
    });
  }
}

TEST_CASE("pair budget: the collector's account of a pile", "[broadphase]") {
  // 100 equal boxes at one point: body i is charged with the i pairs to lower ids, so bodies 33
  // and up (quota 32) are crowded and keep 4 each.
  std::vector<AABB> boxes(100, AABB{{0, 0}, {1, 1}});
  std::vector<engine::PairQuota> quotas(boxes.size(), engine::PairQuota{1.0, 32, 1.0});
  engine::BroadPhase broad_phase;
  std::vector<BodyPair> pairs;
  broad_phase.FindPairs(engine::BroadPhaseType::kSweepAndPrune, boxes, &pairs, quotas);
  const engine::PairCollector& budget = broad_phase.LastCollector();
  CHECK(budget.CrowdedCount() == 100 - 33);
  CHECK(budget.MostCharged() == 99);
  const std::size_t kept = 33 * 32 / 2 + (100 - 33) * 4;
  CHECK(pairs.size() == kept);
  CHECK(budget.DroppedCount() == 100 * 99 / 2 - kept);
  // With every box in the same place the nearest ids win: body 50 keeps 49, 48, 47, 46.
  for (std::uint32_t a : {46u, 47u, 48u, 49u}) {
    CHECK(std::find(pairs.begin(), pairs.end(), BodyPair{a, 50}) != pairs.end());
  }
  // A static partner comes first, however shallow: put body 0 (static) at the corner.
  boxes[0] = {{0.99, 0.99}, {2, 2}};
  quotas[0].width = std::numeric_limits<double>::infinity();
  broad_phase.FindPairs(engine::BroadPhaseType::kSweepAndPrune, boxes, &pairs, quotas);
  for (std::uint32_t b = 1; b < 100; ++b) {
    CHECK(std::find(pairs.begin(), pairs.end(), BodyPair{0, b}) != pairs.end());
  }
  // Without quotas, every pair.
  broad_phase.FindPairs(engine::BroadPhaseType::kSweepAndPrune, boxes, &pairs);
  CHECK(pairs.size() == 100 * 99 / 2);
  CHECK(broad_phase.LastCollector().CrowdedCount() == 0);
}

TEMPLATE_TEST_CASE("broad phase: sizes over six orders of magnitude", "[broadphase]", BROAD_PHASES) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> log_size(-3, 3);
  std::uniform_real_distribution<double> position(0, 200);
  std::vector<AABB> boxes(1200);
  for (auto& b : boxes) {
    b.lower = {position(rng), position(rng)};
    b.upper = b.lower + Vec2{std::pow(10.0, log_size(rng)), std::pow(10.0, log_size(rng))};
  }
  TestType broad_phase;
  for (int step = 0; step < 20; ++step) {
    INFO("step " << step);
    RequireAllPairs(broad_phase, boxes);
    Move(rng, boxes);
  }
}

TEST_CASE("sweep and prune: a coherent step costs few swaps", "[broadphase]") {
  std::mt19937_64 rng(7);
  auto boxes = RandomBoxes(rng, 1000, 60);
  engine::SweepAndPrune sap;
  std::vector<BodyPair> pairs;
  sap.FindPairs(boxes, &pairs);  // the first call sorts the random order in O(n log n)
  CHECK(sap.LastSwapCount() == 0);  // nothing left for insertion sort to do
  for (auto& b : boxes) {
    b.lower.x += 1e-3;
    b.upper.x += 1e-3;
  }
  sap.FindPairs(boxes, &pairs);
  CHECK(sap.LastSwapCount() == 0);  // everything moved alike: the order is unchanged
  // One box jumping across the others does cost swaps, and the pairs stay exact.
  boxes[0].lower.x += 30;
  boxes[0].upper.x += 30;
  sap.FindPairs(boxes, &pairs);
  CHECK(sap.LastSwapCount() > 0);
  std::vector<BodyPair> expected;
  engine::FindPairsAllPairs(boxes, &expected);
  CHECK(pairs == expected);
}

TEST_CASE("sweep and prune: a reshuffle past the swap budget ends in a full sort, same order", "[broadphase]") {
  std::mt19937_64 rng(17);
  auto boxes = RandomBoxes(rng, 2000, 90);
  engine::SweepAndPrune sap;
  std::vector<BodyPair> pairs, expected;
  sap.FindPairs(boxes, &pairs);
  // Mirror every box in x: insertion sort would need about n² / 2 swaps.
  for (auto& b : boxes) b = {{-b.upper.x, b.lower.y}, {-b.lower.x, b.upper.y}};
  sap.FindPairs(boxes, &pairs);
  const auto budget = static_cast<std::int64_t>(8 * 2 * boxes.size() + 1024);
  CHECK(sap.LastSwapCount() > budget);
  CHECK(sap.LastSwapCount() <= budget + static_cast<std::int64_t>(2 * boxes.size()));
  engine::FindPairsAllPairs(boxes, &expected);
  CHECK(pairs == expected);
  // And back to small steps: the order is the one insertion sort keeps.
  for (int step = 0; step < 5; ++step) {
    Move(rng, boxes);
    RequireAllPairs(sap, boxes);
  }
}

TEST_CASE("AABB tree: a pile past the candidate limit keeps no candidates, the pairs stay exact",
          "[broadphase]") {
  std::mt19937_64 rng(19);
  auto boxes = RandomBoxes(rng, 400, 40);
  engine::AabbTree tree;
  RequireAllPairs(tree, boxes);
  CHECK_FALSE(tree.Crowded());
  // 200 of them onto one spot: 19 900 pairs, past 16 a body (and 1024).
  const auto home = boxes;
  for (int i = 0; i < 200; ++i) boxes[2 * i] = {{5, 5}, {6, 6}};
  RequireAllPairs(tree, boxes);
  CHECK(tree.Crowded());
  Move(rng, boxes);
  RequireAllPairs(tree, boxes);
  CHECK(tree.Crowded());
  // Back where they were: the tree keeps its candidates again.
  boxes = home;
  RequireAllPairs(tree, boxes);
  CHECK_FALSE(tree.Crowded());
  for (int step = 0; step < 5; ++step) {
    Move(rng, boxes);
    RequireAllPairs(tree, boxes);
  }
}

TEST_CASE("uniform grid: cells follow the typical box, a floor stays out of them", "[broadphase]") {
  std::mt19937_64 rng(9);
  auto boxes = RandomBoxes(rng, 1000, 60);  // sides 1 to 3: median extent 2 or 3
  boxes.push_back({{-1e4, -2}, {1e4, 0}});
  engine::UniformGrid grid;
  std::vector<BodyPair> pairs;
  grid.FindPairs(boxes, &pairs);
  CHECK(grid.CellSize() >= 4.0);
  CHECK(grid.CellSize() <= 6.0);
  CHECK(grid.LargeCount() == 1);
  const double first = grid.CellSize();
  // Small changes keep the cell size; boxes ten times bigger get cells to match.
  Move(rng, boxes);
  grid.FindPairs(boxes, &pairs);
  CHECK(grid.CellSize() == first);
  for (auto& b : boxes) b.upper = b.lower + 10.0 * (b.upper - b.lower);
  grid.FindPairs(boxes, &pairs);
  CHECK(grid.CellSize() >= 40.0);
}

TEST_CASE("quadtree: depth stays bounded for coincident boxes and modest for spread ones", "[broadphase]") {
  engine::Quadtree tree;
  std::vector<BodyPair> pairs;
  std::vector<AABB> boxes(100, AABB{{1, 1}, {1, 1}});
  tree.FindPairs(boxes, &pairs);
  CHECK(tree.LastDepth() <= engine::Quadtree::kMaxDepth);
  std::mt19937_64 rng(10);
  boxes = RandomBoxes(rng, 4000, 200);
  tree.FindPairs(boxes, &pairs);
  CHECK(tree.LastDepth() >= 3);
  CHECK(tree.LastDepth() <= 12);
}

TEST_CASE("aabb tree: still bodies cost no reinsertion and the tree stays balanced", "[broadphase]") {
  std::mt19937_64 rng(11);
  auto boxes = RandomBoxes(rng, 2000, 90);
  engine::AabbTree tree;
  std::vector<BodyPair> pairs;
  tree.FindPairs(boxes, &pairs);
  CHECK(tree.LastReinsertCount() == 2000);
  tree.FindPairs(boxes, &pairs);
  CHECK(tree.LastReinsertCount() == 0);
  // Moves smaller than the fat margin stay inside the leaves.
  for (auto& b : boxes) {
    b.lower.x += 0.01;
    b.upper.x += 0.01;
  }
  tree.FindPairs(boxes, &pairs);
  CHECK(tree.LastReinsertCount() == 0);
  for (int step = 0; step < 30; ++step) {
    Move(rng, boxes);
    tree.FindPairs(boxes, &pairs);
  }
  CHECK(tree.IsValid());
  CHECK(tree.Height() <= 2 * 11 + 2);  // log2(2000) ≈ 11
  // Inserted in sorted order along a line, the worst case for an unbalanced tree.
  engine::AabbTree line;
  std::vector<AABB> row;
  for (int i = 0; i < 1024; ++i) row.push_back({{1.0 * i, 0}, {i + 0.5, 1}});
  for (std::size_t n = 1; n <= row.size(); n *= 2) {
    line.FindPairs(std::span(row).first(n), &pairs);
  }
  CHECK(line.IsValid());
  CHECK(line.Height() <= 2 * 10 + 2);
}

TEST_CASE("automatic broad phase: the tree while bodies rest, the grid while many move", "[broadphase]") {
  using engine::BroadPhaseType;
  std::mt19937_64 rng(12);
  auto boxes = RandomBoxes(rng, 500, 40);
  engine::BroadPhase broad_phase;
  std::vector<BodyPair> pairs;
  auto step = [&] {
    broad_phase.FindPairs(BroadPhaseType::kAuto, boxes, &pairs);
    std::vector<BodyPair> expected;
    engine::FindPairsAllPairs(boxes, &expected);
    REQUIRE(pairs == expected);
    return broad_phase.LastUsed();
  };
  CHECK(step() == BroadPhaseType::kAabbTree);  // the first call builds the tree: not motion
  CHECK(step() == BroadPhaseType::kAabbTree);
  // Everything moves by more than its fat margin every call: the tree would reinsert it all.
  auto drift = [&] {
    for (auto& b : boxes) {
      b.lower.x += 1.5;
      b.upper.x += 1.5;
    }
  };
  drift();
  CHECK(step() == BroadPhaseType::kAabbTree);  // this call reinserts them and hands over
  for (int k = 0; k < 5; ++k) {
    drift();
    CHECK(step() == BroadPhaseType::kUniformGrid);
  }
  // Most rest, a few still move: the grid keeps the choice for a second of calls (60), then the
  // tree is back, and stays.
  int grid_calls = 5;
  for (int k = 0; k < 100; ++k) {
    boxes[k % 30].lower.y += 0.5;
    boxes[k % 30].upper.y += 0.5;
    if (step() != BroadPhaseType::kUniformGrid) break;
    ++grid_calls;
  }
  CHECK(grid_calls == 60);
  CHECK(broad_phase.LastUsed() == BroadPhaseType::kAabbTree);
  CHECK(step() == BroadPhaseType::kAabbTree);
  CHECK(step() == BroadPhaseType::kAabbTree);
  // A handful of boxes: all pairs.
  boxes.resize(engine::BroadPhase::kAllPairsMaxBodies);
  CHECK(step() == BroadPhaseType::kAllPairs);
  boxes.resize(engine::BroadPhase::kAllPairsMaxBodies + 1);
  CHECK(step() == BroadPhaseType::kAabbTree);
}

TEST_CASE("automatic broad phase: back to the tree once no more than an eighth of the bodies move",
          "[broadphase]") {
  using engine::BroadPhaseType;
  std::mt19937_64 rng(13);
  auto boxes = RandomBoxes(rng, 500, 40);  // an eighth: 62.5, so 63 moving keep the grid
  engine::BroadPhase broad_phase;
  std::vector<BodyPair> pairs;
  auto step = [&] {
    broad_phase.FindPairs(BroadPhaseType::kAuto, boxes, &pairs);
    return broad_phase.LastUsed();
  };
  step();
  for (int k = 0; k < 3; ++k) {  // all of them drift: onto the grid
    for (auto& b : boxes) {
      b.lower.x += 1.5;
      b.upper.x += 1.5;
    }
    step();
  }
  REQUIRE(broad_phase.LastUsed() == BroadPhaseType::kUniformGrid);
  // `count` boxes spread over all of them (the count is looked at in blocks) move half a unit,
  // more than 2 % of any box's size.
  auto move = [&](int count, int call) {
    for (int j = 0; j < count; ++j) {
      engine::AABB& b = boxes[static_cast<std::size_t>(7 * j + 3)];
      const double dy = call % 2 == 0 ? 0.5 : -0.5;
      b.lower.y += dy;
      b.upper.y += dy;
    }
  };
  for (int call = 0; call < 80; ++call) {  // past the grid's first 60 calls, looked at each call
    move(63, call);
    CHECK(step() == BroadPhaseType::kUniformGrid);
  }
  move(62, 80);
  CHECK(step() == BroadPhaseType::kAabbTree);
}

namespace {

// Builds the world with each broad phase, steps it, and requires the same state hash from all.
void RequireSameHashWithEveryBroadPhase(const std::function<engine::World(engine::BroadPhaseType)>& make,
                                        int steps) {
  using engine::BroadPhaseType;
  const std::pair<BroadPhaseType, const char*> choices[] = {
      {BroadPhaseType::kAuto, "auto"},
      {BroadPhaseType::kAllPairs, "all_pairs"},
      {BroadPhaseType::kSweepAndPrune, "sweep_and_prune"},
      {BroadPhaseType::kUniformGrid, "uniform_grid"},
      {BroadPhaseType::kQuadtree, "quadtree"},
      {BroadPhaseType::kAabbTree, "aabb_tree"},
  };
  std::uint64_t reference = 0;
  for (const auto& [type, name] : choices) {
    engine::World world = make(type);
    for (int s = 0; s < steps; ++s) world.Step();
    INFO(name);
    if (type == BroadPhaseType::kAuto) {
      reference = world.StateHash();
    } else {
      CHECK(world.StateHash() == reference);
    }
  }
}

}  // namespace

TEST_CASE("world: the same state hash with every broad phase", "[broadphase]") {
  for (const char* file : {"box_pile.json", "ball_pour.json"}) {
    INFO(file);
    const game::Expected<game::Scene> loaded = game::LoadScene(std::string(BALLBOX_ASSETS) + "/scenes/" + file);
    REQUIRE(loaded.HasValue());
    RequireSameHashWithEveryBroadPhase(
        [&loaded](engine::BroadPhaseType type) {
          game::Scene scene = loaded.Value();
          scene.world.broad_phase = type;
          return game::BuildWorld(scene);
        },
        300);
  }
  // Enough bodies that the automatic choice uses a structure, not all pairs.
  RequireSameHashWithEveryBroadPhase(
      [](engine::BroadPhaseType type) {
        engine::WorldDef def;
        def.broad_phase = type;
        engine::World world(def);
        stress::AddContainer(world, 30, 30);
        stress::AddCirclePour(world, 600, 0.25, 30);
        return world;
      },
      120);
}
