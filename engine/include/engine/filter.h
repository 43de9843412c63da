// Collision filtering, as Box2D has it: categories and masks, and groups that override them.
#pragma once

#include <cstdint>

namespace engine {

/// Which bodies a body collides with. Two bodies in the same non-zero group always collide
/// (positive group) or never (negative group); otherwise each one's category must be in the
/// other's mask.
struct Filter {
  std::uint64_t category_bits = 1;     ///< what this body is
  std::uint64_t mask_bits = ~0ull;     ///< what it collides with
  std::int32_t group_index = 0;
  friend constexpr bool operator==(const Filter&, const Filter&) = default;
};

constexpr bool ShouldCollide(const Filter& a, const Filter& b) {
  if (a.group_index == b.group_index && a.group_index != 0) return a.group_index > 0;
  return (a.category_bits & b.mask_bits) != 0 && (b.category_bits & a.mask_bits) != 0;
}

}  // namespace engine
