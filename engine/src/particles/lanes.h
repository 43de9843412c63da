// Two doubles worked on at once, lane by lane (SSE2 on x86-64, NEON on arm64, two scalars
// elsewhere). Each lane's add, multiply, divide and square root is the one IEEE operation the
// scalar code does, and nothing is summed across lanes, so the results are the scalar code's
// bits on every machine. Internal.
#pragma once

#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif

namespace engine::detail {

using Double2 = double __attribute__((vector_size(16)));
/// A lane-wise comparison's result: all bits set where it holds.
using Mask2 = std::int64_t __attribute__((vector_size(16)));

inline Double2 Splat2(double a) { return Double2{a, a}; }

inline Double2 Sqrt2(Double2 a) {
#if defined(__SSE2__)
  return _mm_sqrt_pd(a);
#elif defined(__aarch64__)
  return reinterpret_cast<Double2>(vsqrtq_f64(reinterpret_cast<float64x2_t>(a)));
#else
  return Double2{std::sqrt(a[0]), std::sqrt(a[1])};
#endif
}

/// `a` in the lanes where `keep` holds, +0 in the others.
inline Double2 KeepWhere(Mask2 keep, Double2 a) {
  return reinterpret_cast<Double2>(keep & reinterpret_cast<Mask2>(a));
}

}  // namespace engine::detail
