// The pair loops of a fluid of one kind. Four lanes (AVX2), or eight for the density pass's
// kernel (AVX-512), do each pair's IEEE operations in the scalar code's order, one pair per
// lane, and add into the particles in pair order, so the bits are the one-at-a-time loop's.
#include "particles/fluid_pairs.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__)
#include <immintrin.h>
#define BALLBOX_AVX2_AT_RUN_TIME 1
#endif

namespace engine::detail {

static_assert(sizeof(DensitySums) == 4 * sizeof(double) && sizeof(Vec2) == 2 * sizeof(double));

namespace {

// The sums `fj` adds into: its own chunk's, or the next chunk's spill. (`own_end` is taken by
// value so that the stores into the sums cannot make it be read again.)
template <typename T>
T& Target(std::uint32_t own_end, std::uint32_t fj, T* own, T* spill) {
  return fj < own_end ? own[fj] : spill[fj];
}

void DensityBy1(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs, DensitySums* own,
                DensitySums* spill) {
  const std::uint32_t own_end = fluid.own_end;
  const SphKernels& k = fluid.kernel;
  const double a = fluid.mass * fluid.inv_rest;
  for (const auto& [i, j] : pairs) {
    const Vec2 d = x[i] - x[j];
    const double r2 = LengthSquared(d), r = std::sqrt(r2);
    const double mw = fluid.mass * k.W(r2, r);
    const Vec2 g = a * k.Gradient(d, r);
    const double denominator = fluid.inv_mass * LengthSquared(g);
    DensitySums& si = own[i];
    si.density += mw;
    si.gradient += g;
    si.denominator += denominator;
    DensitySums& sj = Target(own_end, j, own, spill);
    sj.density += mw;
    sj.gradient += -g;
    sj.denominator += denominator;
  }
}

void MovesBy1(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs, const double* lambda,
              Vec2* own, Vec2* spill) {
  const std::uint32_t own_end = fluid.own_end;
  const SphKernels& k = fluid.kernel;
  const double a = fluid.mass * fluid.inv_rest;
  for (const auto& [i, j] : pairs) {
    const std::uint32_t fi = i, fj = j;
    const Vec2 d = x[i] - x[j];
    const double r2 = LengthSquared(d), r = std::sqrt(r2);
    const double ratio = k.W(r2, r) * fluid.clumping_over_w;
    const double ratio2 = ratio * ratio;
    const double clumping = fluid.clumping_strength * (ratio2 * ratio2);
    const Vec2 gradient = k.Gradient(d, r);
    const double weight_i = (lambda[fi] + clumping) * a + fluid.mass * (lambda[fj] * fluid.inv_rest);
    const double weight_j = (lambda[fj] + clumping) * a + fluid.mass * (lambda[fi] * fluid.inv_rest);
    own[fi] += weight_i * gradient;
    Target(own_end, fj, own, spill) += weight_j * (-gradient);
  }
}

void PullsBy1(const UniformPairs& fluid, const Vec2* x, const Vec2* v, const double* mass_over_density,
              std::span<const ParticlePair> pairs, Vec2* own, Vec2* spill) {
  const std::uint32_t own_end = fluid.own_end;
  for (const auto& [i, j] : pairs) {
    const double r2 = LengthSquared(x[i] - x[j]);
    const double w = fluid.kernel.W(r2, std::sqrt(r2));
    own[i] += (mass_over_density[j] * w) * (v[j] - v[i]);
    Target(own_end, j, own, spill) += (mass_over_density[i] * w) * (v[i] - v[j]);
  }
}

void InitialSumsBy1(double self, double rest_density, const double* wall_share, const Vec2* wall_slope,
                    std::uint32_t begin, std::uint32_t end, DensitySums* sums) {
  for (std::uint32_t f = begin; f < end; ++f) sums[f] = {self + rest_density * wall_share[f], wall_slope[f], 0.0};
}

void MultipliersBy1(const UniformPairs& fluid, const DensitySums* sums, const double* wall_denominator,
                    double epsilon, std::uint32_t begin, std::uint32_t end, double* density, double* lambda) {
  for (std::uint32_t f = begin; f < end; ++f) {
    const DensitySums& sum = sums[f];
    const double denominator = sum.denominator + (fluid.inv_mass * LengthSquared(sum.gradient) + wall_denominator[f]);
    density[f] = sum.density;
    // Only compression is pushed apart: a free surface, below the rest density, is left alone
    // rather than pulled together.
    const double c = std::max(0.0, sum.density * fluid.inv_rest - 1.0);
    lambda[f] = -c / (denominator + epsilon);
  }
}

void MoveBy1(const UniformPairs& fluid, const Vec2* moves, const double* lambda, const Vec2* wall_slope,
             double wall_factor, double share, std::uint32_t begin, std::uint32_t end, Vec2* x) {
  for (std::uint32_t f = begin; f < end; ++f) {
    const Vec2 delta = fluid.inv_mass * (moves[f] + wall_factor * lambda[f] * wall_slope[f]);
    x[f] += share * delta;
  }
}

void PredictBy1(Vec2 gravity, double h, const double* inv_mass, std::uint32_t begin, std::uint32_t end, Vec2* x, Vec2* v,
                Vec2* previous) {
  for (std::uint32_t i = begin; i < end; ++i) {
    previous[i] = x[i];
    if (inv_mass[i] == 0.0) continue;
    v[i] += h * gravity;
    x[i] += h * v[i];
  }
}

void VelocitiesBy1(double h, const Vec2* x, const Vec2* previous, std::uint32_t begin, std::uint32_t end, Vec2* v) {
  for (std::uint32_t i = begin; i < end; ++i) v[i] = (x[i] - previous[i]) / h;
}

#ifdef BALLBOX_AVX2_AT_RUN_TIME
#define BALLBOX_AVX2 __attribute__((target("avx2")))

// The x and y of four Vec2s, lanes in the order given.
BALLBOX_AVX2 inline void Gather4(const Vec2* x, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d,
                                 __m256d* xs, __m256d* ys) {
  const __m256d ab = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[a].x)), _mm_loadu_pd(&x[b].x), 1);
  const __m256d cd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[c].x)), _mm_loadu_pd(&x[d].x), 1);
  // unpack gives (a, c, b, d); the permute puts them back in order.
  *xs = _mm256_permute4x64_pd(_mm256_unpacklo_pd(ab, cd), 0xd8);
  *ys = _mm256_permute4x64_pd(_mm256_unpackhi_pd(ab, cd), 0xd8);
}

// W, and ∇W's x and y, of four pairs, as SphKernels::W(r2, r) and Gradient(d, r).
struct Kernel4 {
  __m256d w, gx, gy;
};

BALLBOX_AVX2 inline Kernel4 KernelOf4(const SphKernels& k, __m256d dx, __m256d dy, __m256d r2) {
  const __m256d h = _mm256_set1_pd(k.h), scale = _mm256_set1_pd(k.scale);
  const __m256d r = _mm256_sqrt_pd(r2);
  const __m256d f = _mm256_sub_pd(h, r);
  const __m256d w = _mm256_and_pd(_mm256_cmp_pd(r2, _mm256_set1_pd(k.h2), _CMP_LT_OQ),
                                  _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(scale, f), f), f));
  const __m256d slope =
      _mm256_and_pd(_mm256_cmp_pd(r, h, _CMP_LT_OQ), _mm256_cmp_pd(r, _mm256_setzero_pd(), _CMP_NEQ_UQ));
  const __m256d c =
      _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(-3.0 * k.scale), f), f), r);
  return {w, _mm256_and_pd(slope, _mm256_mul_pd(c, dx)), _mm256_and_pd(slope, _mm256_mul_pd(c, dy))};
}

// The sums of a particle that is the lower one of a run of pairs (see DensityBy4).
struct LowerSums {
  std::uint32_t at;
  __m256d sums;
};

// Four pairs' density terms, from their W and ∇W (`t`), added into their particles in pair
// order, and the move pass's terms left at `stored`.
BALLBOX_AVX2 inline void AddDensityOf4(const UniformPairs& fluid, const ParticlePair* q, const Kernel4& t,
                                       double* stored, DensitySums* own, DensitySums* spill, LowerSums& lower) {
  const std::uint32_t own_end = fluid.own_end;
  const __m256d a = _mm256_set1_pd(fluid.mass * fluid.inv_rest);
  const __m256d mass = _mm256_set1_pd(fluid.mass), inv_mass = _mm256_set1_pd(fluid.inv_mass);
  const __m256d flip = _mm256_set_pd(0.0, -0.0, -0.0, 0.0);  // j's side: the gradient's sign
  // The move pass's terms, so that it need not work them out again.
  const __m256d ratio = _mm256_mul_pd(t.w, _mm256_set1_pd(fluid.clumping_over_w));
  const __m256d ratio2 = _mm256_mul_pd(ratio, ratio);
  _mm256_storeu_pd(stored, t.gx);
  _mm256_storeu_pd(stored + 4, t.gy);
  _mm256_storeu_pd(stored + 8, _mm256_mul_pd(_mm256_set1_pd(fluid.clumping_strength), _mm256_mul_pd(ratio2, ratio2)));
  const __m256d gx = _mm256_mul_pd(a, t.gx), gy = _mm256_mul_pd(a, t.gy);
  const __m256d mw = _mm256_mul_pd(mass, t.w);
  const __m256d denominator = _mm256_mul_pd(inv_mass, _mm256_add_pd(_mm256_mul_pd(gx, gx), _mm256_mul_pd(gy, gy)));
  // Each pair's (m·W, g, m⁻¹·|g|²) in one vector, laid out as DensitySums.
  const __m256d lo0 = _mm256_unpacklo_pd(mw, gx), hi0 = _mm256_unpackhi_pd(mw, gx);
  const __m256d lo1 = _mm256_unpacklo_pd(gy, denominator), hi1 = _mm256_unpackhi_pd(gy, denominator);
  const __m256d terms[4] = {_mm256_permute2f128_pd(lo0, lo1, 0x20), _mm256_permute2f128_pd(hi0, hi1, 0x20),
                            _mm256_permute2f128_pd(lo0, lo1, 0x31), _mm256_permute2f128_pd(hi0, hi1, 0x31)};
  for (int l = 0; l < 4; ++l) {
    const std::uint32_t fi = q[l].first;
    if (fi != lower.at) {
      _mm256_storeu_pd(&own[lower.at].density, lower.sums);
      lower.at = fi;
      lower.sums = _mm256_loadu_pd(&own[fi].density);
    }
    lower.sums = _mm256_add_pd(lower.sums, terms[l]);
    double* const sj = &Target(own_end, q[l].second, own, spill).density;
    _mm256_storeu_pd(sj, _mm256_add_pd(_mm256_loadu_pd(sj), _mm256_xor_pd(terms[l], flip)));
  }
}

BALLBOX_AVX2 void DensityBy4(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                             const PairOffsets& offsets, DensitySums* own, DensitySums* spill, double* stored) {
  // A particle's pairs as the lower one follow each other (and it is never a pair's higher
  // one): its sums wait in `lower` rather than go through memory after each pair, which made
  // the next pair wait for the store. The additions are the same, in the same order.
  if (pairs.size() < 4) return DensityBy1(fluid, x, pairs, own, spill);
  LowerSums lower{pairs[0].first, _mm256_loadu_pd(&own[pairs[0].first].density)};
  std::size_t p = 0;
  for (; p + 4 <= pairs.size(); p += 4) {
    const Kernel4 t = KernelOf4(fluid.kernel, _mm256_loadu_pd(offsets.dx + p), _mm256_loadu_pd(offsets.dy + p),
                                _mm256_loadu_pd(offsets.r2 + p));
    AddDensityOf4(fluid, pairs.data() + p, t, stored + 3 * p, own, spill, lower);
  }
  _mm256_storeu_pd(&own[lower.at].density, lower.sums);
  DensityBy1(fluid, x, pairs.subspan(p), own, spill);
}

#define BALLBOX_AVX512 __attribute__((target("avx512f,avx2")))

// KernelOf4 for eight pairs: on this machine (AMD Zen 5) the square roots and divisions of
// eight lanes take hardly longer than of four.
struct Kernel8 {
  __m512d w, gx, gy;
};

BALLBOX_AVX512 inline Kernel8 KernelOf8(const SphKernels& k, __m512d dx, __m512d dy, __m512d r2) {
  const __m512d h = _mm512_set1_pd(k.h), scale = _mm512_set1_pd(k.scale);
  const __m512d r = _mm512_maskz_sqrt_pd(0xff, r2);  // maskz: as in Half
  const __m512d f = _mm512_sub_pd(h, r);
  // Masked lanes are +0, as KernelOf4's `and` leaves them.
  const __mmask8 inside = _mm512_cmp_pd_mask(r2, _mm512_set1_pd(k.h2), _CMP_LT_OQ);
  const __m512d w = _mm512_maskz_mov_pd(inside, _mm512_mul_pd(_mm512_mul_pd(_mm512_mul_pd(scale, f), f), f));
  const __mmask8 slope =
      _mm512_cmp_pd_mask(r, h, _CMP_LT_OQ) & _mm512_cmp_pd_mask(r, _mm512_setzero_pd(), _CMP_NEQ_UQ);
  const __m512d c = _mm512_div_pd(_mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(-3.0 * k.scale), f), f), r);
  return {w, _mm512_maskz_mov_pd(slope, _mm512_mul_pd(c, dx)), _mm512_maskz_mov_pd(slope, _mm512_mul_pd(c, dy))};
}

// Half of eight lanes (maskz: GCC 12 warns of the undefined lanes the plain casts and
// extracts start from).
BALLBOX_AVX512 inline Kernel4 Half(const Kernel8& t, int half) {
  if (half == 0) {
    return {_mm512_maskz_extractf64x4_pd(0xf, t.w, 0), _mm512_maskz_extractf64x4_pd(0xf, t.gx, 0),
            _mm512_maskz_extractf64x4_pd(0xf, t.gy, 0)};
  }
  return {_mm512_maskz_extractf64x4_pd(0xf, t.w, 1), _mm512_maskz_extractf64x4_pd(0xf, t.gx, 1),
          _mm512_maskz_extractf64x4_pd(0xf, t.gy, 1)};
}

// DensityBy4 with the kernel worked out eight pairs at a time (AVX-512); the terms go into the
// particles four at a time as there, and the move pass finds them where DensityBy4 leaves them.
BALLBOX_AVX512 void DensityBy8(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                               const PairOffsets& offsets, DensitySums* own, DensitySums* spill, double* stored) {
  if (pairs.size() < 8) return DensityBy4(fluid, x, pairs, offsets, own, spill, stored);
  LowerSums lower{pairs[0].first, _mm256_loadu_pd(&own[pairs[0].first].density)};
  std::size_t p = 0;
  for (; p + 8 <= pairs.size(); p += 8) {
    const Kernel8 t = KernelOf8(fluid.kernel, _mm512_loadu_pd(offsets.dx + p), _mm512_loadu_pd(offsets.dy + p),
                                _mm512_loadu_pd(offsets.r2 + p));
    AddDensityOf4(fluid, pairs.data() + p, Half(t, 0), stored + 3 * p, own, spill, lower);
    AddDensityOf4(fluid, pairs.data() + p + 4, Half(t, 1), stored + 3 * p + 12, own, spill, lower);
  }
  _mm256_storeu_pd(&own[lower.at].density, lower.sums);
  DensityBy4(fluid, x, pairs.subspan(p), {offsets.dx + p, offsets.dy + p, offsets.r2 + p}, own, spill,
             stored + 3 * p);
}

BALLBOX_AVX2 void MovesBy4(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                           const double* lambda, const double* stored, Vec2* own, Vec2* spill) {
  const std::uint32_t own_end = fluid.own_end;
  const __m256d a = _mm256_set1_pd(fluid.mass * fluid.inv_rest), mass = _mm256_set1_pd(fluid.mass);
  const __m256d inv_rest = _mm256_set1_pd(fluid.inv_rest);
  const __m256d minus = _mm256_set1_pd(-0.0);
  if (pairs.size() < 4) return MovesBy1(fluid, x, pairs, lambda, own, spill);
  std::uint32_t lower_at = pairs[0].first;  // as in DensityBy4
  __m128d lower = _mm_loadu_pd(&own[lower_at].x);
  std::size_t p = 0;
  for (; p + 4 <= pairs.size(); p += 4) {
    const ParticlePair* const q = pairs.data() + p;
    const Kernel4 t{_mm256_setzero_pd(), _mm256_loadu_pd(stored + 3 * p), _mm256_loadu_pd(stored + 3 * p + 4)};
    const __m256d clumping = _mm256_loadu_pd(stored + 3 * p + 8);
    const std::uint32_t i0 = q[0].first, i1 = q[1].first, i2 = q[2].first,
                        i3 = q[3].first;
    const std::uint32_t j0 = q[0].second, j1 = q[1].second, j2 = q[2].second,
                        j3 = q[3].second;
    const __m256d lambda_i = _mm256_set_pd(lambda[i3], lambda[i2], lambda[i1], lambda[i0]);
    const __m256d lambda_j = _mm256_set_pd(lambda[j3], lambda[j2], lambda[j1], lambda[j0]);
    // λ/ρ0 in the lanes rather than gathered: the same product, four fewer loads a side.
    const __m256d over_i = _mm256_mul_pd(lambda_i, inv_rest), over_j = _mm256_mul_pd(lambda_j, inv_rest);
    const __m256d weight_i = _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(lambda_i, clumping), a), _mm256_mul_pd(mass, over_j));
    const __m256d weight_j = _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(lambda_j, clumping), a), _mm256_mul_pd(mass, over_i));
    const __m256d xi = _mm256_mul_pd(weight_i, t.gx), yi = _mm256_mul_pd(weight_i, t.gy);
    const __m256d xj = _mm256_mul_pd(weight_j, _mm256_xor_pd(t.gx, minus));
    const __m256d yj = _mm256_mul_pd(weight_j, _mm256_xor_pd(t.gy, minus));
    // Each pair's move as (x, y): lanes 0 and 1 in the low halves, 2 and 3 in the high.
    const __m256d lo_i = _mm256_unpacklo_pd(xi, yi), hi_i = _mm256_unpackhi_pd(xi, yi);
    const __m256d lo_j = _mm256_unpacklo_pd(xj, yj), hi_j = _mm256_unpackhi_pd(xj, yj);
    const __m128d moves_i[4] = {_mm256_castpd256_pd128(lo_i), _mm256_castpd256_pd128(hi_i),
                                _mm256_extractf128_pd(lo_i, 1), _mm256_extractf128_pd(hi_i, 1)};
    const __m128d moves_j[4] = {_mm256_castpd256_pd128(lo_j), _mm256_castpd256_pd128(hi_j),
                                _mm256_extractf128_pd(lo_j, 1), _mm256_extractf128_pd(hi_j, 1)};
    for (int l = 0; l < 4; ++l) {
      const std::uint32_t fi = q[l].first;
      if (fi != lower_at) {
        _mm_storeu_pd(&own[lower_at].x, lower);
        lower_at = fi;
        lower = _mm_loadu_pd(&own[fi].x);
      }
      lower = _mm_add_pd(lower, moves_i[l]);
      double* const mj = &Target(own_end, q[l].second, own, spill).x;
      _mm_storeu_pd(mj, _mm_add_pd(_mm_loadu_pd(mj), moves_j[l]));
    }
  }
  _mm_storeu_pd(&own[lower_at].x, lower);
  MovesBy1(fluid, x, pairs.subspan(p), lambda, own, spill);
}

BALLBOX_AVX2 void PullsBy4(const UniformPairs& fluid, const Vec2* x, const Vec2* v, const double* mass_over_density,
                           std::span<const ParticlePair> pairs, const PairOffsets& offsets, Vec2* own, Vec2* spill) {
  const std::uint32_t own_end = fluid.own_end;
  const SphKernels& k = fluid.kernel;
  const __m256d h = _mm256_set1_pd(k.h), h2 = _mm256_set1_pd(k.h2), scale = _mm256_set1_pd(k.scale);
  const double* const r2s = offsets.r2;
  const std::size_t full = pairs.size() / 4 * 4;
  if (full == 0) return PullsBy1(fluid, x, v, mass_over_density, pairs, own, spill);
  std::uint32_t lower_at = pairs[0].first;  // as in DensityBy4
  __m128d lower = _mm_loadu_pd(&own[lower_at].x);
  for (std::size_t p = 0; p < full; p += 4) {
    const ParticlePair* const q = pairs.data() + p;
    const __m256d r2 = _mm256_loadu_pd(r2s + p);
    const __m256d f = _mm256_sub_pd(h, _mm256_sqrt_pd(r2));
    const __m256d w = _mm256_and_pd(_mm256_cmp_pd(r2, h2, _CMP_LT_OQ),
                                    _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(scale, f), f), f));
    __m256d vxi, vyi, vxj, vyj;
    Gather4(v, q[0].first, q[1].first, q[2].first, q[3].first, &vxi, &vyi);
    Gather4(v, q[0].second, q[1].second, q[2].second, q[3].second, &vxj, &vyj);
    const __m256d over_i = _mm256_set_pd(mass_over_density[q[3].first], mass_over_density[q[2].first],
                                         mass_over_density[q[1].first], mass_over_density[q[0].first]);
    const __m256d over_j = _mm256_set_pd(mass_over_density[q[3].second], mass_over_density[q[2].second],
                                         mass_over_density[q[1].second], mass_over_density[q[0].second]);
    const __m256d wi = _mm256_mul_pd(over_j, w), wj = _mm256_mul_pd(over_i, w);
    const __m256d xi = _mm256_mul_pd(wi, _mm256_sub_pd(vxj, vxi)), yi = _mm256_mul_pd(wi, _mm256_sub_pd(vyj, vyi));
    const __m256d xj = _mm256_mul_pd(wj, _mm256_sub_pd(vxi, vxj)), yj = _mm256_mul_pd(wj, _mm256_sub_pd(vyi, vyj));
    const __m256d lo_i = _mm256_unpacklo_pd(xi, yi), hi_i = _mm256_unpackhi_pd(xi, yi);
    const __m256d lo_j = _mm256_unpacklo_pd(xj, yj), hi_j = _mm256_unpackhi_pd(xj, yj);
    const __m128d pulls_i[4] = {_mm256_castpd256_pd128(lo_i), _mm256_castpd256_pd128(hi_i),
                                _mm256_extractf128_pd(lo_i, 1), _mm256_extractf128_pd(hi_i, 1)};
    const __m128d pulls_j[4] = {_mm256_castpd256_pd128(lo_j), _mm256_castpd256_pd128(hi_j),
                                _mm256_extractf128_pd(lo_j, 1), _mm256_extractf128_pd(hi_j, 1)};
    for (int l = 0; l < 4; ++l) {
      const std::uint32_t fi = q[l].first;
      if (fi != lower_at) {
        _mm_storeu_pd(&own[lower_at].x, lower);
        lower_at = fi;
        lower = _mm_loadu_pd(&own[fi].x);
      }
      lower = _mm_add_pd(lower, pulls_i[l]);
      double* const pj = &Target(own_end, q[l].second, own, spill).x;
      _mm_storeu_pd(pj, _mm_add_pd(_mm_loadu_pd(pj), pulls_j[l]));
    }
  }
  _mm_storeu_pd(&own[lower_at].x, lower);
  PullsBy1(fluid, x, v, mass_over_density, pairs.subspan(full), own, spill);
}

// InitialSumsBy1 eight particles at a time: each particle's (ρ, slope, 0) put together from
// the lanes of ρ and the slopes as they lie (x, y).
BALLBOX_AVX512 void InitialSumsBy8(double self, double rest_density, const double* wall_share, const Vec2* wall_slope,
                                   std::uint32_t begin, std::uint32_t end, DensitySums* sums) {
  const __m512d own = _mm512_set1_pd(self), rest = _mm512_set1_pd(rest_density);
  // Indices into (ρ of eight, then four slopes): two particles' sums a vector, lane 3 and 7
  // left +0.
  const __m512i pair01 = _mm512_setr_epi64(0, 8, 9, 0, 1, 10, 11, 0), pair23 = _mm512_setr_epi64(2, 12, 13, 0, 3, 14, 15, 0);
  const __m512i pair45 = _mm512_setr_epi64(4, 8, 9, 0, 5, 10, 11, 0), pair67 = _mm512_setr_epi64(6, 12, 13, 0, 7, 14, 15, 0);
  std::uint32_t f = begin;
  for (; f + 8 <= end; f += 8) {
    const __m512d rho = _mm512_add_pd(own, _mm512_mul_pd(rest, _mm512_loadu_pd(wall_share + f)));
    const __m512d slopes03 = _mm512_loadu_pd(&wall_slope[f].x), slopes47 = _mm512_loadu_pd(&wall_slope[f + 4].x);
    double* const out = &sums[f].density;
    _mm512_storeu_pd(out, _mm512_maskz_permutex2var_pd(0x77, rho, pair01, slopes03));
    _mm512_storeu_pd(out + 8, _mm512_maskz_permutex2var_pd(0x77, rho, pair23, slopes03));
    _mm512_storeu_pd(out + 16, _mm512_maskz_permutex2var_pd(0x77, rho, pair45, slopes47));
    _mm512_storeu_pd(out + 24, _mm512_maskz_permutex2var_pd(0x77, rho, pair67, slopes47));
  }
  InitialSumsBy1(self, rest_density, wall_share, wall_slope, f, end, sums);
}

// MultipliersBy1 eight particles at a time: the sums of eight particles turned into lanes of
// each quantity, then each lane does the scalar code's IEEE operations (max with +0 as
// std::max(0.0, e) takes it, −c by its sign bit).
BALLBOX_AVX512 void MultipliersBy8(const UniformPairs& fluid, const DensitySums* sums, const double* wall_denominator,
                                   double epsilon, std::uint32_t begin, std::uint32_t end, double* density,
                                   double* lambda) {
  const __m512i low = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13), high = _mm512_setr_epi64(2, 6, 10, 14, 3, 7, 11, 15);
  const __m512i firsts = _mm512_setr_epi64(0, 1, 2, 3, 8, 9, 10, 11), seconds = _mm512_setr_epi64(4, 5, 6, 7, 12, 13, 14, 15);
  const __m512d inv_mass = _mm512_set1_pd(fluid.inv_mass), inv_rest = _mm512_set1_pd(fluid.inv_rest);
  const __m512d one = _mm512_set1_pd(1.0), eps = _mm512_set1_pd(epsilon);
  const __m512i sign = _mm512_set1_epi64(static_cast<std::int64_t>(0x8000000000000000ull));
  std::uint32_t f = begin;
  for (; f + 8 <= end; f += 8) {
    const double* const s = &sums[f].density;
    const __m512d z0 = _mm512_loadu_pd(s), z1 = _mm512_loadu_pd(s + 8);
    const __m512d z2 = _mm512_loadu_pd(s + 16), z3 = _mm512_loadu_pd(s + 24);
    // (ρ, gx) and (gy, d) of particles 0-3, then of 4-7; then each quantity's eight.
    const __m512d a = _mm512_permutex2var_pd(z0, low, z1), b = _mm512_permutex2var_pd(z0, high, z1);
    const __m512d c = _mm512_permutex2var_pd(z2, low, z3), e = _mm512_permutex2var_pd(z2, high, z3);
    const __m512d rho = _mm512_permutex2var_pd(a, firsts, c), gx = _mm512_permutex2var_pd(a, seconds, c);
    const __m512d gy = _mm512_permutex2var_pd(b, firsts, e), d = _mm512_permutex2var_pd(b, seconds, e);
    const __m512d g2 = _mm512_add_pd(_mm512_mul_pd(gx, gx), _mm512_mul_pd(gy, gy));
    const __m512d denominator =
        _mm512_add_pd(d, _mm512_add_pd(_mm512_mul_pd(inv_mass, g2), _mm512_loadu_pd(wall_denominator + f)));
    _mm512_storeu_pd(density + f, rho);
    // maskz here and below: GCC 12 warns of the undefined lanes the plain forms start from.
    const __m512d squeeze =
        _mm512_maskz_max_pd(0xff, _mm512_sub_pd(_mm512_mul_pd(rho, inv_rest), one), _mm512_setzero_pd());
    const __m512d minus = _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(squeeze), sign));
    _mm512_storeu_pd(lambda + f, _mm512_div_pd(minus, _mm512_add_pd(denominator, eps)));
  }
  MultipliersBy1(fluid, sums, wall_denominator, epsilon, f, end, density, lambda);
}

// MoveBy1 four particles (eight doubles) at a time.
BALLBOX_AVX512 void MoveBy4(const UniformPairs& fluid, const Vec2* moves, const double* lambda, const Vec2* wall_slope,
                            double wall_factor, double share, std::uint32_t begin, std::uint32_t end, Vec2* x) {
  const __m512i twice = _mm512_setr_epi64(0, 0, 1, 1, 2, 2, 3, 3);
  const __m512d factor = _mm512_set1_pd(wall_factor), inv_mass = _mm512_set1_pd(fluid.inv_mass);
  const __m512d half = _mm512_set1_pd(share);
  std::uint32_t f = begin;
  for (; f + 4 <= end; f += 4) {
    // Each particle's λ in both its lanes (x and y).
    const __m512d l = _mm512_maskz_permutexvar_pd(0xff, twice, _mm512_maskz_loadu_pd(0x0f, lambda + f));
    const __m512d pull = _mm512_mul_pd(_mm512_mul_pd(factor, l), _mm512_loadu_pd(&wall_slope[f].x));
    const __m512d delta = _mm512_mul_pd(inv_mass, _mm512_add_pd(_mm512_loadu_pd(&moves[f].x), pull));
    _mm512_storeu_pd(&x[f].x, _mm512_add_pd(_mm512_loadu_pd(&x[f].x), _mm512_mul_pd(half, delta)));
  }
  MoveBy1(fluid, moves, lambda, wall_slope, wall_factor, share, f, end, x);
}

// PredictBy1 four particles (eight doubles) at a time; a particle of no inverse mass keeps its
// velocity and position (masked lanes).
BALLBOX_AVX512 void PredictBy4(Vec2 gravity, double h, const double* inv_mass, std::uint32_t begin, std::uint32_t end,
                               Vec2* x, Vec2* v, Vec2* previous) {
  const __m512d hs = _mm512_set1_pd(h);
  const __m512i twice = _mm512_setr_epi64(0, 0, 1, 1, 2, 2, 3, 3);
  const __m512d fall = _mm512_setr_pd(h * gravity.x, h * gravity.y, h * gravity.x, h * gravity.y, h * gravity.x,
                                      h * gravity.y, h * gravity.x, h * gravity.y);
  std::uint32_t i = begin;
  for (; i + 4 <= end; i += 4) {
    const __m512d xi = _mm512_loadu_pd(&x[i].x);
    _mm512_storeu_pd(&previous[i].x, xi);
    // Each particle's two lanes where its inverse mass is not 0 (maskz: as in Half).
    const __m512d masses = _mm512_maskz_permutexvar_pd(0xff, twice, _mm512_maskz_loadu_pd(0x0f, inv_mass + i));
    const __mmask8 moving = _mm512_cmp_pd_mask(masses, _mm512_setzero_pd(), _CMP_NEQ_UQ);
    const __m512d vi = _mm512_add_pd(_mm512_loadu_pd(&v[i].x), fall);
    _mm512_mask_storeu_pd(&v[i].x, moving, vi);
    _mm512_mask_storeu_pd(&x[i].x, moving, _mm512_add_pd(xi, _mm512_mul_pd(hs, vi)));
  }
  PredictBy1(gravity, h, inv_mass, i, end, x, v, previous);
}

// VelocitiesBy1 four particles at a time.
BALLBOX_AVX512 void VelocitiesBy4(double h, const Vec2* x, const Vec2* previous, std::uint32_t begin, std::uint32_t end,
                                  Vec2* v) {
  const __m512d hs = _mm512_set1_pd(h);
  std::uint32_t i = begin;
  for (; i + 4 <= end; i += 4) {
    _mm512_storeu_pd(&v[i].x, _mm512_div_pd(_mm512_sub_pd(_mm512_loadu_pd(&x[i].x), _mm512_loadu_pd(&previous[i].x)), hs));
  }
  VelocitiesBy1(h, x, previous, i, end, v);
}

bool HasAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

bool HasAvx512() {
  static const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx2");
  return avx512;
}
#endif

}  // namespace

void AddDensityOfPairs(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                       [[maybe_unused]] const PairOffsets& offsets, DensitySums* own, DensitySums* spill,
                       [[maybe_unused]] double* terms, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return DensityBy8(fluid, x, pairs, offsets, own, spill, terms);
  if (lanes != 1 && HasAvx2()) return DensityBy4(fluid, x, pairs, offsets, own, spill, terms);
#endif
  DensityBy1(fluid, x, pairs, own, spill);
}

void AddMovesOfPairs(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                     const double* lambda, [[maybe_unused]] const double* terms,
                     Vec2* own, Vec2* spill, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes != 1 && HasAvx2()) return MovesBy4(fluid, x, pairs, lambda, terms, own, spill);
#endif
  MovesBy1(fluid, x, pairs, lambda, own, spill);
}


void AddPullsOfPairs(const UniformPairs& fluid, const Vec2* x, const Vec2* v, const double* mass_over_density,
                     std::span<const ParticlePair> pairs, [[maybe_unused]] const PairOffsets& offsets, Vec2* own,
                     Vec2* spill, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes != 1 && HasAvx2()) return PullsBy4(fluid, x, v, mass_over_density, pairs, offsets, own, spill);
#endif
  PullsBy1(fluid, x, v, mass_over_density, pairs, own, spill);
}

void MultipliersOf(const UniformPairs& fluid, const DensitySums* sums, const double* wall_denominator, double epsilon,
                   std::uint32_t begin, std::uint32_t end, double* density, double* lambda, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return MultipliersBy8(fluid, sums, wall_denominator, epsilon, begin, end, density, lambda);
#endif
  MultipliersBy1(fluid, sums, wall_denominator, epsilon, begin, end, density, lambda);
}

void MoveParticles(const UniformPairs& fluid, const Vec2* moves, const double* lambda, const Vec2* wall_slope,
                   double wall_factor, double share, std::uint32_t begin, std::uint32_t end, Vec2* x,
                   [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return MoveBy4(fluid, moves, lambda, wall_slope, wall_factor, share, begin, end, x);
#endif
  MoveBy1(fluid, moves, lambda, wall_slope, wall_factor, share, begin, end, x);
}

void PredictParticles(Vec2 gravity, double h, const double* inv_mass, std::uint32_t begin, std::uint32_t end, Vec2* x,
                      Vec2* v, Vec2* previous, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return PredictBy4(gravity, h, inv_mass, begin, end, x, v, previous);
#endif
  PredictBy1(gravity, h, inv_mass, begin, end, x, v, previous);
}

void VelocitiesOfMoves(double h, const Vec2* x, const Vec2* previous, std::uint32_t begin, std::uint32_t end, Vec2* v,
                       [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return VelocitiesBy4(h, x, previous, begin, end, v);
#endif
  VelocitiesBy1(h, x, previous, begin, end, v);
}

void InitialSums([[maybe_unused]] const UniformPairs& fluid, double self, double rest_density, const double* wall_share,
                 const Vec2* wall_slope, std::uint32_t begin, std::uint32_t end, DensitySums* sums,
                 [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  if (lanes == 0 && HasAvx512()) return InitialSumsBy8(self, rest_density, wall_share, wall_slope, begin, end, sums);
#endif
  InitialSumsBy1(self, rest_density, wall_share, wall_slope, begin, end, sums);
}

}  // namespace engine::detail
