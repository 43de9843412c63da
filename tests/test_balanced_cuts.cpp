// BalancedCuts: even cuts until it has seen a call, then cuts that move half way to where each
// part would cost the same, were every stretch of the items to cost per item what it last did.
#include <catch2/catch.hpp>

#include <cstddef>
#include <vector>

#include "parallel/balanced_cuts.h"

using engine::detail::BalancedCuts;

TEST_CASE("BalancedCuts cuts evenly before it has seen a call", "[parallel]") {
  const BalancedCuts cuts;
  CHECK(cuts.Cut(0, 2, 100) == 0);
  CHECK(cuts.Cut(1, 2, 100) == 50);
  CHECK(cuts.Cut(2, 2, 100) == 100);
  CHECK(cuts.Cut(1, 3, 100) == 33);
  CHECK(cuts.Cut(2, 3, 100) == 66);
}

TEST_CASE("BalancedCuts moves a cut half way to where the parts would cost alike", "[parallel]") {
  BalancedCuts cuts;
  // Halves of 100 items: the first took 1 s, the second 3 s. Alike at 2 s each: the first half
  // (1 s) and then 1 s of the second, whose 50 items cost 3/50 s each, so 50/3 more items:
  // 66.67. Half way from 50: 58.33.
  const std::vector<std::size_t> halves{0, 50, 100};
  cuts.Learn(halves, std::vector<double>{1.0, 3.0});
  CHECK(cuts.Cut(1, 2, 100) == 58);
  CHECK(cuts.Cut(1, 2, 1000) == 583);  // a share of the items, whatever their count
  CHECK(cuts.Cut(2, 2, 100) == 100);
  // The same costs again from the new cut: 58 items for 1.16 s, 42 for 2.52 s, 3.68 in all.
  // Alike at 1.84: 58 + (1.84 - 1.16) / (2.52 / 42) = 69.33; half way from 58.33: 63.83.
  const std::vector<std::size_t> moved{0, 58, 100};
  cuts.Learn(moved, std::vector<double>{58.0 / 50.0, 42.0 * 3.0 / 50.0});
  CHECK(cuts.Cut(1, 2, 100) == 63);
}

TEST_CASE("BalancedCuts places several cuts by the cost walked part by part", "[parallel]") {
  BalancedCuts cuts;
  // Three parts of 30 items costing 1, 1 and 4 s: 6 s, 2 s a part. The first new cut at 2 s is
  // the end of the second part (60); the second at 4 s is half way into the third (75). Half
  // way from 30 and 60: 45 and 67.5.
  cuts.Learn(std::vector<std::size_t>{0, 30, 60, 90}, std::vector<double>{1.0, 1.0, 4.0});
  CHECK(cuts.Cut(1, 3, 90) == 45);
  CHECK(cuts.Cut(2, 3, 90) == 67);
  CHECK(cuts.Cut(3, 3, 90) == 90);
  // A call with another number of parts starts from even cuts again.
  CHECK(cuts.Cut(1, 2, 90) == 45);
}

TEST_CASE("BalancedCuts keeps its cuts when a call measured nothing", "[parallel]") {
  BalancedCuts cuts;
  cuts.Learn(std::vector<std::size_t>{0, 0}, std::vector<double>{1.0});  // no items
  cuts.Learn(std::vector<std::size_t>{0, 50, 100}, std::vector<double>{0.0, 0.0});  // no time
  CHECK(cuts.Cut(1, 2, 100) == 50);
}
