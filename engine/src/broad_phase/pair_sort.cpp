// Pairs sorted by (a, b) with two counting sorts: linear in pairs plus bodies.
#include "broad_phase/pair_sort.h"

namespace engine::detail {

void SortPairs(std::size_t body_count, std::vector<BodyPair>* pairs, std::vector<BodyPair>* scratch,
               std::vector<std::uint32_t>* counts) {
  scratch->resize(pairs->size());
  auto pass = [&](const std::vector<BodyPair>& from, std::vector<BodyPair>& to, bool by_a) {
    counts->assign(body_count + 1, 0);
    for (const BodyPair& p : from) ++(*counts)[(by_a ? p.a : p.b) + 1];
    for (std::size_t i = 1; i <= body_count; ++i) (*counts)[i] += (*counts)[i - 1];
    for (const BodyPair& p : from) to[(*counts)[by_a ? p.a : p.b]++] = p;
  };
  pass(*pairs, *scratch, false);
  pass(*scratch, *pairs, true);
}

}  // namespace engine::detail
