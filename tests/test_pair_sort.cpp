// The pair sort every broad phase's list goes through (engine::detail::SortPairs): it must give
// std::sort's order, by a then b, whatever order the pairs come in and however many a body leads.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "broad_phase/pair_sort.h"

namespace {

using engine::BodyPair;

// Distinct pairs over `bodies` bodies, body a leading (a + 1) % 9 of them: every group size from
// none to eight, in a shuffled order.
std::vector<BodyPair> ShuffledPairs(std::uint32_t bodies, std::mt19937& random) {
  std::vector<BodyPair> pairs;
  for (std::uint32_t a = 0; a + 1 < bodies; ++a) {
    std::vector<std::uint32_t> partners;
    for (std::uint32_t b = a + 1; b < bodies; ++b) partners.push_back(b);
    std::shuffle(partners.begin(), partners.end(), random);
    const std::uint32_t led = std::min<std::uint32_t>((a + 1) % 9, static_cast<std::uint32_t>(partners.size()));
    for (std::uint32_t k = 0; k < led; ++k) pairs.push_back({a, partners[k]});
  }
  std::shuffle(pairs.begin(), pairs.end(), random);
  return pairs;
}

}  // namespace

TEST_CASE("pair sort: shuffled pairs come out as std::sort orders them, a body leading none to eight") {
  std::mt19937 random(7);
  std::vector<BodyPair> scratch;
  std::vector<std::uint32_t> counts;
  for (const std::uint32_t bodies : {2u, 5u, 40u, 300u}) {
    std::vector<BodyPair> pairs = ShuffledPairs(bodies, random);
    std::vector<BodyPair> expected = pairs;
    std::sort(expected.begin(), expected.end());
    REQUIRE_FALSE(pairs.empty());
    engine::detail::SortPairs(bodies, &pairs, &scratch, &counts);
    REQUIRE(pairs == expected);
    // Sorted already, it stays as it is (the buffers are reused from the last call).
    engine::detail::SortPairs(bodies, &pairs, &scratch, &counts);
    REQUIRE(pairs == expected);
  }
}
