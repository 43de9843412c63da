// Two bodies, lower id first: what the broad phase reports and the order every list of pairs or
// contacts is kept in. Internal to the engine.
#pragma once

#include <cstdint>

namespace engine {

struct BodyPair {
  std::uint32_t a;  ///< the smaller index
  std::uint32_t b;
  friend constexpr bool operator==(BodyPair, BodyPair) = default;
  /// By a, then b: the one order of pairs, contacts and constraints in the engine. Compared as
  /// one 64-bit key, which has no branch to mispredict (sorting, merging and checking lists of
  /// pairs spent most of their time in the two-part comparison's branches).
  friend constexpr bool operator<(BodyPair x, BodyPair y) { return Key(x) < Key(y); }
  static constexpr std::uint64_t Key(BodyPair p) { return std::uint64_t{p.a} << 32 | p.b; }
};

constexpr BodyPair MakePair(std::uint32_t i, std::uint32_t j) {
  return i < j ? BodyPair{i, j} : BodyPair{j, i};
}

}  // namespace engine
