// Pairs sorted by (a, b) with two counting sorts: linear in pairs plus bodies.
#include "broad_phase/pair_sort.h"

#include <cassert>

namespace engine::detail {

void SortPairs(std::size_t body_count, std::vector<BodyPair>* pairs, std::vector<BodyPair>* scratch,
               std::vector<std::uint32_t>* counts) {
  const std::span<const BodyPair> all(*pairs);
  SortPairsInto({&all, 1}, 0, static_cast<std::uint32_t>(body_count), body_count, pairs->data(), scratch, counts);
}

void SortPairsInto(std::span<const std::span<const BodyPair>> parts, std::uint32_t a_begin, std::uint32_t a_end,
                   std::size_t body_count, BodyPair* out, std::vector<BodyPair>* scratch,
                   std::vector<std::uint32_t>* counts) {
  assert(a_begin <= a_end && a_end <= body_count);
  std::size_t total = 0;
  for (const std::span<const BodyPair> part : parts) total += part.size();
  scratch->resize(total);
  // Two stable counting sorts: by b into `scratch`, then by a (keys in [a_begin, a_end)) into
  // `out`, which keeps each a's pairs in b's order.
  counts->assign(body_count + 1, 0);
  for (const std::span<const BodyPair> part : parts) {
    for (const BodyPair& p : part) ++(*counts)[p.b + 1];
  }
  for (std::size_t i = 1; i <= body_count; ++i) (*counts)[i] += (*counts)[i - 1];
  for (const std::span<const BodyPair> part : parts) {
    for (const BodyPair& p : part) (*scratch)[(*counts)[p.b]++] = p;
  }
  const std::size_t keys = a_end - a_begin;
  counts->assign(keys + 1, 0);
  for (const BodyPair& p : *scratch) ++(*counts)[p.a - a_begin + 1];
  for (std::size_t i = 1; i <= keys; ++i) (*counts)[i] += (*counts)[i - 1];
  for (const BodyPair& p : *scratch) out[(*counts)[p.a - a_begin]++] = p;
}

}  // namespace engine::detail
