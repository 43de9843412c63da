// The wide passes four lanes wide in AVX2, included by the two files that compile them: for
// AVX2 alone (wide_passes_4.cpp, -mavx2, not FMA) and for AVX2 with AVX-512VL's 32 vector
// registers (wide_passes_4_evex.cpp). Everything here has internal linkage; each file names its
// own passes. WidePassesFor hands each out only where the processor has what it was built for.
#include <immintrin.h>

#include <cstdint>
#include <type_traits>

#include "solver/wide_passes.h"
#include "store_whole.h"

namespace engine::detail {

namespace {

struct Mask {
  __m256d bits;
};
inline Mask operator&(Mask a, Mask b) { return {_mm256_and_pd(a.bits, b.bits)}; }
inline Mask operator|(Mask a, Mask b) { return {_mm256_or_pd(a.bits, b.bits)}; }
inline Mask MaskOf(unsigned bits) {
  return {_mm256_castsi256_pd(_mm256_set_epi64x(bits & 8u ? -1 : 0, bits & 4u ? -1 : 0, bits & 2u ? -1 : 0,
                                                bits & 1u ? -1 : 0))};
}
inline unsigned Bits(Mask m) { return static_cast<unsigned>(_mm256_movemask_pd(m.bits)); }

struct Lanes {
  static constexpr int kCount = 4;
  __m256d v;
  Lanes() = default;
  explicit Lanes(__m256d x) : v(x) {}
  explicit Lanes(double x) : v(_mm256_set1_pd(x)) {}
  static Lanes Load(const double* p) { return Lanes(_mm256_load_pd(p)); }
  void Store(double* p) const { _mm256_store_pd(p, v); }
};
inline Lanes operator+(Lanes a, Lanes b) { return Lanes(_mm256_add_pd(a.v, b.v)); }
inline Lanes operator-(Lanes a, Lanes b) { return Lanes(_mm256_sub_pd(a.v, b.v)); }
inline Lanes operator*(Lanes a, Lanes b) { return Lanes(_mm256_mul_pd(a.v, b.v)); }
inline Lanes operator/(Lanes a, Lanes b) { return Lanes(_mm256_div_pd(a.v, b.v)); }
inline Lanes operator-(Lanes a) { return Lanes(_mm256_xor_pd(a.v, _mm256_set1_pd(-0.0))); }
// Ordered, quiet comparisons: false where either side is NaN, as C++'s are; != is unordered,
// true there.
inline Mask operator<(Lanes a, Lanes b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)}; }
inline Mask operator>(Lanes a, Lanes b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)}; }
inline Mask operator>=(Lanes a, Lanes b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GE_OQ)}; }
inline Mask operator!=(Lanes a, Lanes b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_NEQ_UQ)}; }
inline Lanes Select(Mask m, Lanes if_set, Lanes if_clear) {
  return Lanes(_mm256_blendv_pd(if_clear.v, if_set.v, m.bits));
}
inline Lanes Abs(Lanes a) { return Lanes(_mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v)); }
// (a > b ? a : b) and (a < b ? a : b): b where either is NaN or both are 0.
inline Lanes MaxOf(Lanes a, Lanes b) { return Lanes(_mm256_max_pd(a.v, b.v)); }
inline Lanes MinOf(Lanes a, Lanes b) { return Lanes(_mm256_min_pd(a.v, b.v)); }

// Four bodies' Vec2s (x, y at base + index·stride) into lanes of x and of y.
[[gnu::always_inline]] inline void Gather(const double* base, std::size_t stride, const std::int32_t* index, Lanes* x,
                                          Lanes* y) {
  const __m128d v0 = _mm_loadu_pd(base + static_cast<std::size_t>(index[0]) * stride);
  const __m128d v1 = _mm_loadu_pd(base + static_cast<std::size_t>(index[1]) * stride);
  const __m128d v2 = _mm_loadu_pd(base + static_cast<std::size_t>(index[2]) * stride);
  const __m128d v3 = _mm_loadu_pd(base + static_cast<std::size_t>(index[3]) * stride);
  const __m256d even = _mm256_insertf128_pd(_mm256_castpd128_pd256(v0), v2, 1);  // x0 y0 x2 y2
  const __m256d odd = _mm256_insertf128_pd(_mm256_castpd128_pd256(v1), v3, 1);   // x1 y1 x3 y3
  *x = Lanes(_mm256_unpacklo_pd(even, odd));
  *y = Lanes(_mm256_unpackhi_pd(even, odd));
}
// Back, for the lanes whose bit is set in `write`.
[[gnu::always_inline]] inline void Scatter(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                           Lanes y,
                    unsigned write) {
  const __m256d even = _mm256_unpacklo_pd(x.v, y.v);  // x0 y0 x2 y2
  const __m256d odd = _mm256_unpackhi_pd(x.v, y.v);   // x1 y1 x3 y3
  if (write & 1u) _mm_storeu_pd(base + static_cast<std::size_t>(index[0]) * stride, _mm256_castpd256_pd128(even));
  if (write & 2u) _mm_storeu_pd(base + static_cast<std::size_t>(index[1]) * stride, _mm256_castpd256_pd128(odd));
  if (write & 4u) _mm_storeu_pd(base + static_cast<std::size_t>(index[2]) * stride, _mm256_extractf128_pd(even, 1));
  if (write & 8u) _mm_storeu_pd(base + static_cast<std::size_t>(index[3]) * stride, _mm256_extractf128_pd(odd, 1));
}

[[gnu::always_inline]] inline Lanes GatherOne(const double* base, std::size_t stride, const std::int32_t* index) {
  return Lanes(_mm256_set_pd(base[static_cast<std::size_t>(index[3]) * stride], base[static_cast<std::size_t>(index[2]) * stride],
                             base[static_cast<std::size_t>(index[1]) * stride], base[static_cast<std::size_t>(index[0]) * stride]));
}
[[gnu::always_inline]] inline void ScatterOne(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                              unsigned write) {
  const __m128d low = _mm256_castpd256_pd128(x.v), high = _mm256_extractf128_pd(x.v, 1);
  if (write & 1u) _mm_storel_pd(base + static_cast<std::size_t>(index[0]) * stride, low);
  if (write & 2u) _mm_storeh_pd(base + static_cast<std::size_t>(index[1]) * stride, low);
  if (write & 4u) _mm_storel_pd(base + static_cast<std::size_t>(index[2]) * stride, high);
  if (write & 8u) _mm_storeh_pd(base + static_cast<std::size_t>(index[3]) * stride, high);
}

#include "solver/wide_kernels.inl"
#include "solver/wide_twin.inl"
#include "solver/wide_turning_kernels.inl"
#include "joints/wide_joint_kernels.inl"
#include "solver/wide_cos_sin.inl"

constexpr WidePasses kPasses{4, WarmStartBlocks, SolveBlocks, PushOutBlocks,
                             TurningWarmStartBlocks, TurningSolveBlocks, TurningWarmStartTwin,
                             TurningSolveTwin,       TurningPushOutBlocks,   TurningPushOutTwin,
                             JointWarmStartBlocks,   JointSolveBlocks,   JointPushOutBlocks,
                             RotationsOf};

}  // namespace

}  // namespace engine::detail
