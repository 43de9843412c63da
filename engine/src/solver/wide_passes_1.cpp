// The wide passes one lane wide, in plain C++: for processors without SSE2 or AVX2 (arm64), the
// same arithmetic as the wider lanes, so the same bits.
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "solver/wide_passes.h"
#include "store_whole.h"

namespace engine::detail {

namespace {

struct Mask {
  bool lane;
};
inline Mask operator&(Mask a, Mask b) { return {a.lane && b.lane}; }
inline Mask operator|(Mask a, Mask b) { return {a.lane || b.lane}; }
inline Mask MaskOf(unsigned bits) { return {(bits & 1u) != 0}; }
inline unsigned Bits(Mask m) { return m.lane ? 1u : 0u; }

struct Lanes {
  static constexpr int kCount = 1;
  double v;
  Lanes() = default;
  explicit Lanes(double x) : v(x) {}
  static Lanes Load(const double* p) { return Lanes(*p); }
  void Store(double* p) const { *p = v; }
};
inline Lanes operator+(Lanes a, Lanes b) { return Lanes(a.v + b.v); }
inline Lanes operator-(Lanes a, Lanes b) { return Lanes(a.v - b.v); }
inline Lanes operator*(Lanes a, Lanes b) { return Lanes(a.v * b.v); }
inline Lanes operator/(Lanes a, Lanes b) { return Lanes(a.v / b.v); }
inline Lanes operator-(Lanes a) { return Lanes(-a.v); }
inline Mask operator<(Lanes a, Lanes b) { return {a.v < b.v}; }
inline Mask operator>(Lanes a, Lanes b) { return {a.v > b.v}; }
inline Mask operator>=(Lanes a, Lanes b) { return {a.v >= b.v}; }
inline Mask operator!=(Lanes a, Lanes b) { return {a.v != b.v}; }
inline Lanes Select(Mask m, Lanes if_set, Lanes if_clear) { return m.lane ? if_set : if_clear; }
inline Lanes Abs(Lanes a) { return Lanes(std::fabs(a.v)); }
// (a > b ? a : b) and (a < b ? a : b), as x86's max and min: b where either is NaN or both are 0.
inline Lanes MaxOf(Lanes a, Lanes b) { return a.v > b.v ? a : b; }
inline Lanes MinOf(Lanes a, Lanes b) { return a.v < b.v ? a : b; }

[[gnu::always_inline]] inline void Gather(const double* base, std::size_t stride, const std::int32_t* index, Lanes* x,
                                          Lanes* y) {
  const double* p = base + static_cast<std::size_t>(index[0]) * stride;
  *x = Lanes(p[0]);
  *y = Lanes(p[1]);
}
[[gnu::always_inline]] inline void Scatter(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                           Lanes y,
                    unsigned write) {
  if (!(write & 1u)) return;
  double* p = base + static_cast<std::size_t>(index[0]) * stride;
  p[0] = x.v;
  p[1] = y.v;
}

[[gnu::always_inline]] inline Lanes GatherOne(const double* base, std::size_t stride, const std::int32_t* index) {
  return Lanes(base[static_cast<std::size_t>(index[0]) * stride]);
}
[[gnu::always_inline]] inline void ScatterOne(double* base, std::size_t stride, const std::int32_t* index, Lanes x,
                                              unsigned write) {
  if (write & 1u) base[static_cast<std::size_t>(index[0]) * stride] = x.v;
}

#include "solver/wide_kernels.inl"
#include "solver/wide_twin.inl"
#include "solver/wide_turning_kernels.inl"
#include "joints/wide_joint_kernels.inl"
#include "solver/wide_cos_sin.inl"

constexpr WidePasses kPasses{1, WarmStartBlocks, SolveBlocks, PushOutBlocks,
                             TurningWarmStartBlocks, TurningSolveBlocks, TurningWarmStartTwin,
                             TurningSolveTwin,       TurningPushOutBlocks,   TurningPushOutTwin,
                             JointWarmStartBlocks,   JointSolveBlocks,   JointPushOutBlocks,
                             RotationsOf};

}  // namespace

const WidePasses& WidePasses1() { return kPasses; }

}  // namespace engine::detail
