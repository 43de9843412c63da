// A thread's own object on cache lines of its own. Objects of neighbouring threads side by side
// (the headers of a vector of vectors) share a line, and every write by one thread then takes
// the line from the other: two threads colliding half the pairs each into their own lists took
// 85 % of the time one thread took for all of them. Internal.
#pragma once

#include <cstddef>

namespace engine::detail {

inline constexpr std::size_t kCacheLine = 64;

template <typename T>
struct alignas(kCacheLine) PerThread {
  T value;
};

}  // namespace engine::detail
