// The kernel over batches of pairs, two or four lanes at a time, and the wall's share of the
// kernel, integrated numerically once per kernel size.
#include "particles/sph_kernels.h"

#include <algorithm>

#include "particles/lanes.h"

#if defined(__x86_64__)
#include <immintrin.h>
#define BALLBOX_AVX_AT_RUN_TIME 1
#endif

namespace engine::detail {

namespace {
constexpr int kTableSize = WallShare::kTableSize;
constexpr int kLineSamples = 256;

// Two lanes: SSE2 on x86-64, NEON on arm64.
void PairTermsBy2(const SphKernels& k, double inv_clumping_w, double clumping_scale, bool with_gradients,
                  const PairBatch& batch, PairTerms* terms) {
  const double h = k.h, h2 = k.h2, scale = k.scale, minus_three_scale = -3.0 * k.scale;
  for (std::uint32_t q = 0; q < batch.count; q += 2) {
    const Double2 dx{batch.dx[q], batch.dx[q + 1]}, dy{batch.dy[q], batch.dy[q + 1]};
    const Double2 r2{batch.r2[q], batch.r2[q + 1]};
    const Double2 r = Sqrt2(r2);
    const Double2 f = Splat2(h) - r;
    const Double2 w = KeepWhere(reinterpret_cast<Mask2>(r2 < Splat2(h2)), Splat2(scale) * f * f * f);
    const bool second = q + 1 < batch.count;
    if (!with_gradients) {
      terms[q].weight = w[0];
      if (second) terms[q + 1].weight = w[1];
      continue;
    }
    const Mask2 slope = reinterpret_cast<Mask2>(r < Splat2(h)) & reinterpret_cast<Mask2>(r != Splat2(0.0));
    const Double2 c = Splat2(minus_three_scale) * f * f / r;
    const Double2 gx = KeepWhere(slope, c * dx), gy = KeepWhere(slope, c * dy);
    const Double2 ratio = w * Splat2(inv_clumping_w);
    const Double2 ratio2 = ratio * ratio;
    const Double2 clumping = Splat2(clumping_scale) * (ratio2 * ratio2);
    terms[q] = {w[0], {gx[0], gy[0]}, clumping[0]};
    if (second) terms[q + 1] = {w[1], {gx[1], gy[1]}, clumping[1]};
  }
}

#ifdef BALLBOX_AVX_AT_RUN_TIME
// Four lanes with AVX (not FMA: nothing is fused), where the processor has it: twice the
// square roots and divisions per cycle, which bound this loop.
__attribute__((target("avx"))) void PairTermsBy4(const SphKernels& k, double inv_clumping_w, double clumping_scale,
                                                 bool with_gradients, const PairBatch& batch, PairTerms* terms) {
  const __m256d h = _mm256_set1_pd(k.h), h2 = _mm256_set1_pd(k.h2), scale = _mm256_set1_pd(k.scale);
  const __m256d minus_three_scale = _mm256_set1_pd(-3.0 * k.scale), zero = _mm256_setzero_pd();
  const __m256d over_w = _mm256_set1_pd(inv_clumping_w), clumping_by = _mm256_set1_pd(clumping_scale);
  for (std::uint32_t q = 0; q < batch.count; q += 4) {
    const __m256d dx = _mm256_loadu_pd(batch.dx + q), dy = _mm256_loadu_pd(batch.dy + q);
    const __m256d r2 = _mm256_loadu_pd(batch.r2 + q);
    const __m256d r = _mm256_sqrt_pd(r2);
    const __m256d f = _mm256_sub_pd(h, r);
    const __m256d w = _mm256_and_pd(_mm256_cmp_pd(r2, h2, _CMP_LT_OQ),
                                    _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(scale, f), f), f));
    const std::uint32_t lanes = std::min(4u, batch.count - q);
    alignas(32) double ws[4], gxs[4], gys[4], cs[4];
    _mm256_store_pd(ws, w);
    if (!with_gradients) {
      for (std::uint32_t l = 0; l < lanes; ++l) terms[q + l].weight = ws[l];
      continue;
    }
    const __m256d slope = _mm256_and_pd(_mm256_cmp_pd(r, h, _CMP_LT_OQ), _mm256_cmp_pd(r, zero, _CMP_NEQ_UQ));
    const __m256d c = _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(minus_three_scale, f), f), r);
    _mm256_store_pd(gxs, _mm256_and_pd(slope, _mm256_mul_pd(c, dx)));
    _mm256_store_pd(gys, _mm256_and_pd(slope, _mm256_mul_pd(c, dy)));
    const __m256d ratio = _mm256_mul_pd(w, over_w);
    const __m256d ratio2 = _mm256_mul_pd(ratio, ratio);
    _mm256_store_pd(cs, _mm256_mul_pd(clumping_by, _mm256_mul_pd(ratio2, ratio2)));
    for (std::uint32_t l = 0; l < lanes; ++l) terms[q + l] = {ws[l], {gxs[l], gys[l]}, cs[l]};
  }
}
#endif

}  // namespace

void KernelTermsOfPairs(const SphKernels& k, double inv_clumping_w, double clumping_scale, bool with_gradients,
                        const PairBatch& batch, PairTerms* terms) {
#ifdef BALLBOX_AVX_AT_RUN_TIME
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx) return PairTermsBy4(k, inv_clumping_w, clumping_scale, with_gradients, batch, terms);
#endif
  PairTermsBy2(k, inv_clumping_w, clumping_scale, with_gradients, batch, terms);
}

WallShare::WallShare(const SphKernels& kernels) : h_(kernels.h) {
  line_.resize(kTableSize + 1);
  share_.resize(kTableSize + 1);
  // line(x) = ∫ W(√(x² + y²)) dy across the kernel (midpoint rule), share(d) = ∫_d^h line(x) dx
  // (trapezoids from the far end).
  for (int k = 0; k <= kTableSize; ++k) {
    const double x = h_ * k / kTableSize;
    const double half = std::sqrt(std::max(0.0, kernels.h2 - x * x));
    double sum = 0.0;
    for (int s = 0; s < kLineSamples; ++s) {
      const double y = -half + (s + 0.5) * (2.0 * half / kLineSamples);
      sum += kernels.W(x * x + y * y);
    }
    line_[k] = sum * (2.0 * half / kLineSamples);
  }
  share_[kTableSize] = 0.0;
  for (int k = kTableSize - 1; k >= 0; --k) {
    share_[k] = share_[k + 1] + 0.5 * (line_[k] + line_[k + 1]) * (h_ / kTableSize);
  }
}


}  // namespace engine::detail
