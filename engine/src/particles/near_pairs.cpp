// Pairs within a distance: eight at a time with AVX-512 or four with AVX2 where the processor
// has them (chosen at run time), else one at a time. All keep the same pairs, in the same order.
#include "particles/near_pairs.h"

#if defined(__x86_64__)
#include <immintrin.h>

#include "particles/keep_table.h"
#define BALLBOX_AVX2_AT_RUN_TIME 1
#endif

namespace engine::detail {

namespace {

std::uint32_t PairsWithinBy1(const Vec2* x, std::span<const ParticlePair> pairs, double r2, ParticlePair* out,
                             const PairOffsets& offsets) {
  // Every pair is written and kept or overwritten by the next: whether a pair is near is a
  // coin toss a branch would mispredict.
  double* const dxs = offsets.dx;
  double* const dys = offsets.dy;
  double* const r2s = offsets.r2;
  std::uint32_t m = 0;
  for (const ParticlePair& p : pairs) {
    const Vec2 d = x[p.first] - x[p.second];
    const double d2 = LengthSquared(d);
    out[m] = p;
    dxs[m] = d.x, dys[m] = d.y, r2s[m] = d2;
    m += d2 < r2;
  }
  return m;
}

#ifdef BALLBOX_AVX2_AT_RUN_TIME

// The x and y of particles a, b, c, d as two vectors (lanes in that order).
__attribute__((target("avx2"))) inline void Gather4(const Vec2* x, std::uint32_t a, std::uint32_t b,
                                                    std::uint32_t c, std::uint32_t d, __m256d* xs, __m256d* ys) {
  const __m256d ab = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[a].x)), _mm_loadu_pd(&x[b].x), 1);
  const __m256d cd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[c].x)), _mm_loadu_pd(&x[d].x), 1);
  // unpack gives (a, c, b, d); the permute puts them back in order.
  *xs = _mm256_permute4x64_pd(_mm256_unpacklo_pd(ab, cd), 0xd8);
  *ys = _mm256_permute4x64_pd(_mm256_unpackhi_pd(ab, cd), 0xd8);
}

// The kept doubles moved to the front by the same 32-bit lanes (two halves each).
__attribute__((target("avx2"))) inline __m256d KeepLanes(__m256d v, __m256i lanes) {
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), lanes));
}

__attribute__((target("avx2"))) std::uint32_t PairsWithinBy4(const Vec2* x, std::span<const ParticlePair> pairs,
                                                             double r2, ParticlePair* out,
                                                             const PairOffsets& offsets) {
  static_assert(sizeof(ParticlePair) == 8);
  const __m256d limit = _mm256_set1_pd(r2);
  const std::size_t count = pairs.size();
  // In locals: the stores could otherwise alias the pointers and make them be read again.
  double* const dxs = offsets.dx;
  double* const dys = offsets.dy;
  double* const r2s = offsets.r2;
  std::uint32_t m = 0;
  std::size_t p = 0;
  for (; p + 4 <= count; p += 4) {
    const ParticlePair* const q = pairs.data() + p;
    __m256d xi, yi, xj, yj;
    Gather4(x, q[0].first, q[1].first, q[2].first, q[3].first, &xi, &yi);
    Gather4(x, q[0].second, q[1].second, q[2].second, q[3].second, &xj, &yj);
    // LengthSquared(x[i] − x[j]) lane by lane: the same IEEE operations in the same order.
    const __m256d dx = _mm256_sub_pd(xi, xj), dy = _mm256_sub_pd(yi, yj);
    const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const int keep = _mm256_movemask_pd(_mm256_cmp_pd(d2, limit, _CMP_LT_OQ));
    const __m256i four = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q));
    const __m256i lanes = _mm256_load_si256(reinterpret_cast<const __m256i*>(kKeep.lanes[keep]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + m), _mm256_permutevar8x32_epi32(four, lanes));
    _mm256_storeu_pd(dxs + m, KeepLanes(dx, lanes));
    _mm256_storeu_pd(dys + m, KeepLanes(dy, lanes));
    _mm256_storeu_pd(r2s + m, KeepLanes(d2, lanes));
    m += static_cast<std::uint32_t>(__builtin_popcount(static_cast<unsigned>(keep)));
  }
  return m + PairsWithinBy1(x, pairs.subspan(p), r2, out + m, {dxs + m, dys + m, r2s + m});
}

#define BALLBOX_AVX512 __attribute__((target("avx512f,avx2")))

// (x, y) of particles a, b, c and d in one vector of eight.
BALLBOX_AVX512 inline __m512d Load4(const Vec2* x, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                    std::uint32_t d) {
  const __m256d ab = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[a].x)), _mm_loadu_pd(&x[b].x), 1);
  const __m256d cd = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(&x[c].x)), _mm_loadu_pd(&x[d].x), 1);
  // maskz: GCC 12 warns of the undefined lanes the plain casts and inserts start from.
  const __m512d low = _mm512_maskz_insertf64x4(0xff, _mm512_setzero_pd(), ab, 0);
  return _mm512_maskz_insertf64x4(0xff, low, cd, 1);
}

// PairsWithinBy4 eight pairs at a time (AVX-512), the kept ones packed by compressing:
// the same IEEE operations lane by lane, the same pairs in the same order.
BALLBOX_AVX512 std::uint32_t PairsWithinBy8(const Vec2* x, std::span<const ParticlePair> pairs, double r2,
                                            ParticlePair* out, const PairOffsets& offsets) {
  const __m512d limit = _mm512_set1_pd(r2);
  const std::size_t count = pairs.size();
  double* const dxs = offsets.dx;
  double* const dys = offsets.dy;
  double* const r2s = offsets.r2;
  // The x and the y of pairs 0-3 (as (x, y) each) and 4-7 into lanes 0-7.
  const __m512i xs = _mm512_setr_epi64(0, 2, 4, 6, 8, 10, 12, 14), ys = _mm512_setr_epi64(1, 3, 5, 7, 9, 11, 13, 15);
  std::uint32_t m = 0;
  std::size_t p = 0;
  for (; p + 8 <= count; p += 8) {
    const ParticlePair* const q = pairs.data() + p;
    const __m512d d03 = _mm512_sub_pd(Load4(x, q[0].first, q[1].first, q[2].first, q[3].first),
                                      Load4(x, q[0].second, q[1].second, q[2].second, q[3].second));
    const __m512d d47 = _mm512_sub_pd(Load4(x, q[4].first, q[5].first, q[6].first, q[7].first),
                                      Load4(x, q[4].second, q[5].second, q[6].second, q[7].second));
    const __m512d dx = _mm512_permutex2var_pd(d03, xs, d47), dy = _mm512_permutex2var_pd(d03, ys, d47);
    const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
    const __mmask8 keep = _mm512_cmp_pd_mask(d2, limit, _CMP_LT_OQ);
    // Packed in the registers and stored whole (the lanes past the kept ones are overwritten
    // by the next eight, and m + 8 ≤ p + 8 ≤ the count): compressing straight to memory was
    // slower.
    _mm512_storeu_si512(out + m, _mm512_maskz_compress_epi64(keep, _mm512_loadu_si512(q)));
    _mm512_storeu_pd(dxs + m, _mm512_maskz_compress_pd(keep, dx));
    _mm512_storeu_pd(dys + m, _mm512_maskz_compress_pd(keep, dy));
    _mm512_storeu_pd(r2s + m, _mm512_maskz_compress_pd(keep, d2));
    m += static_cast<std::uint32_t>(__builtin_popcount(keep));
  }
  return m + PairsWithinBy4(x, pairs.subspan(p), r2, out + m, {dxs + m, dys + m, r2s + m});
}
#endif

}  // namespace

std::uint32_t PairsWithin(const Vec2* x, std::span<const ParticlePair> pairs, double r2, ParticlePair* out,
                          const PairOffsets& offsets, [[maybe_unused]] int lanes) {
#ifdef BALLBOX_AVX2_AT_RUN_TIME
  static const bool avx2 = __builtin_cpu_supports("avx2");
  static const bool avx512 = avx2 && __builtin_cpu_supports("avx512f");
  if (avx512 && lanes == 0) return PairsWithinBy8(x, pairs, r2, out, offsets);
  if (avx2 && lanes != 1) return PairsWithinBy4(x, pairs, r2, out, offsets);
#endif
  return PairsWithinBy1(x, pairs, r2, out, offsets);
}

}  // namespace engine::detail
