// SplitMix64 (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number generators";
// the constants of Vigna's public-domain splitmix64.c): a 64-bit state stepped by a fixed odd
// increment and mixed on the way out. Written here rather than taken from <random>, whose
// distributions give different numbers under different standard libraries. Internal.
#pragma once

#include <cstdint>

namespace engine::detail {

/// The next 64 random bits; advances `state`.
constexpr std::uint64_t SplitMix64(std::uint64_t* state) {
  std::uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Uniform in [0, 1): the top 53 bits, so every value is a double exactly.
constexpr double UniformUnit(std::uint64_t* state) {
  return static_cast<double>(SplitMix64(state) >> 11) * 0x1.0p-53;
}

/// Uniform in [mean − spread, mean + spread).
constexpr double UniformAround(double mean, double spread, std::uint64_t* state) {
  return mean + spread * (2.0 * UniformUnit(state) - 1.0);
}

}  // namespace engine::detail
