// The wide passes two lanes wide in SSE2, which every x86-64 processor has.
#include <emmintrin.h>

#include <cstdint>
#include <type_traits>

#include "solver/wide_passes.h"
#include "store_whole.h"

namespace engine::detail {

namespace {

struct Mask {
  __m128d bits;
};
inline Mask operator&(Mask a, Mask b) { return {_mm_and_pd(a.bits, b.bits)}; }
inline Mask operator|(Mask a, Mask b) { return {_mm_or_pd(a.bits, b.bits)}; }
inline Mask MaskOf(unsigned bits) {
  return {_mm_castsi128_pd(_mm_set_epi64x(bits & 2u ? -1 : 0, bits & 1u ? -1 : 0))};
}
inline unsigned Bits(Mask m) { return static_cast<unsigned>(_mm_movemask_pd(m.bits)); }

struct Lanes {
  static constexpr int kCount = 2;
  __m128d v;
  Lanes() = default;
  explicit Lanes(__m128d x) : v(x) {}
  explicit Lanes(double x) : v(_mm_set1_pd(x)) {}
  static Lanes Load(const double* p) { return Lanes(_mm_load_pd(p)); }
  void Store(double* p) const { _mm_store_pd(p, v); }
};
inline Lanes operator+(Lanes a, Lanes b) { return Lanes(_mm_add_pd(a.v, b.v)); }
inline Lanes operator-(Lanes a, Lanes b) { return Lanes(_mm_sub_pd(a.v, b.v)); }
inline Lanes operator*(Lanes a, Lanes b) { return Lanes(_mm_mul_pd(a.v, b.v)); }
inline Lanes operator/(Lanes a, Lanes b) { return Lanes(_mm_div_pd(a.v, b.v)); }
inline Lanes operator-(Lanes a) { return Lanes(_mm_xor_pd(a.v, _mm_set1_pd(-0.0))); }
// The comparisons are false where either side is NaN, as C++'s are; != is true there.
inline Mask operator<(Lanes a, Lanes b) { return {_mm_cmplt_pd(a.v, b.v)}; }
inline Mask operator>(Lanes a, Lanes b) { return {_mm_cmpgt_pd(a.v, b.v)}; }
inline Mask operator>=(Lanes a, Lanes b) { return {_mm_cmpge_pd(a.v, b.v)}; }
inline Mask operator!=(Lanes a, Lanes b) { return {_mm_cmpneq_pd(a.v, b.v)}; }
inline Lanes Select(Mask m, Lanes if_set, Lanes if_clear) {
  return Lanes(_mm_or_pd(_mm_and_pd(m.bits, if_set.v), _mm_andnot_pd(m.bits, if_clear.v)));
}
inline Lanes Abs(Lanes a) { return Lanes(_mm_andnot_pd(_mm_set1_pd(-0.0), a.v)); }
// (a > b ? a : b) and (a < b ? a : b): b where either is NaN or both are 0.
inline Lanes MaxOf(Lanes a, Lanes b) { return Lanes(_mm_max_pd(a.v, b.v)); }
inline Lanes MinOf(Lanes a, Lanes b) { return Lanes(_mm_min_pd(a.v, b.v)); }

// Two bodies' Vec2s (x, y at base + index·stride) into lanes of x and of y.
[[gnu::always_inline]] inline void Gather(const double* base, std::size_t stride, const std::int32_t* index, Lanes* x,
                                          Lanes* y) {
  const __m128d v0 = _mm_loadu_pd(base + static_cast<std::size_t>(index[0]) * stride);
  const __m128d v1 = _mm_loadu_pd(base + static_cast<std::size_t>(index[1]) * stride);
  *x = Lanes(_mm_unpacklo_pd(v0, v1));
  *y = Lanes(_mm_unpackhi_pd(v0, v1));
}
// Back, for the lanes whose bit is set in `write`.
[[gnu::always_inline]] inline void Scatter(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                           Lanes y,
                    unsigned write) {
  if (write & 1u) _mm_storeu_pd(base + static_cast<std::size_t>(index[0]) * stride, _mm_unpacklo_pd(x.v, y.v));
  if (write & 2u) _mm_storeu_pd(base + static_cast<std::size_t>(index[1]) * stride, _mm_unpackhi_pd(x.v, y.v));
}

[[gnu::always_inline]] inline Lanes GatherOne(const double* base, std::size_t stride, const std::int32_t* index) {
  return Lanes(_mm_set_pd(base[static_cast<std::size_t>(index[1]) * stride], base[static_cast<std::size_t>(index[0]) * stride]));
}
[[gnu::always_inline]] inline void ScatterOne(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                              unsigned write) {
  if (write & 1u) _mm_storel_pd(base + static_cast<std::size_t>(index[0]) * stride, x.v);
  if (write & 2u) _mm_storeh_pd(base + static_cast<std::size_t>(index[1]) * stride, x.v);
}

#include "solver/wide_kernels.inl"
#include "solver/wide_twin.inl"
#include "solver/wide_turning_kernels.inl"
#include "joints/wide_joint_kernels.inl"
#include "solver/wide_cos_sin.inl"

constexpr WidePasses kPasses{2, WarmStartBlocks, SolveBlocks, PushOutBlocks,
                             TurningWarmStartBlocks, TurningSolveBlocks, TurningWarmStartTwin,
                             TurningSolveTwin,       TurningPushOutBlocks,   TurningPushOutTwin,
                             JointWarmStartBlocks,   JointSolveBlocks,   JointPushOutBlocks,
                             RotationsOf};

}  // namespace

const WidePasses& WidePasses2() { return kPasses; }

}  // namespace engine::detail
