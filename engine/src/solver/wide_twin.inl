// Two runs of lanes worked on together (Twin): each operation done on one run's lanes and then on
// the other's, side by side in the instruction stream. Included after wide_kernels.inl, before
// wide_turning_kernels.inl.
//
// Why: a turning strip's contacts follow one another body by body, so each block waits for the
// velocities the block before it wrote, and a pass over one run of blocks is a chain of latencies
// (in the turning pyramid of base 40 a substep's first velocity pass, which also gathers the
// moves and turns and works out the separations, took no longer than the passes after it). Two
// runs that share no moving body (the even and the odd strips) are two chains: interleaved
// operation by operation, the processor works on one while the other waits. Each run's lanes
// still see exactly their own operations in their own order: the same bits. (Interleaved block
// by block instead, tried before, the strips were no faster: a block is several hundred
// instructions, about as many as the processor looks ahead.)
//
// The blocks of one colour share no moving body either, so the solver cuts each colour's run in
// two halves and gives them to the twins as well (ColourHalves). There the gain is in the
// instructions: where the processor has AVX-512 (wide_passes_4_evex.cpp defines
// BALLBOX_TWIN_512_BITS), a Twin is one 512-bit vector, the first run's four lanes in its low
// half, and each operation one instruction for both blocks. The AMD EPYC of 2026-11-30 does a
// 512-bit operation in two halves, but the contacts' arithmetic waits less on the processor's
// queues of vector operations, which a block's velocity pass (about a hundred of them) had
// filled: the turning 4 000-circle pour 1.85-1.92 -> 1.72-1.78 ms/step on one thread, where
// two 256-bit Twins had made no difference (1.86-1.88).

// Two pointers into two runs' blocks, moved together: `k.field + o` of a TwinBlock.
template <typename T>
struct TwinPtr {
  T* one;
  T* two;
  TwinPtr operator+(int o) const { return {one + o, two + o}; }
};

// The bits of the first run's lanes in a Twin's lane bits (Bits): the low ones.
inline constexpr unsigned kFirstRunBits = (1u << Lanes::kCount) - 1;

#if defined(BALLBOX_TWIN_512_BITS)
// One 512-bit vector: the first run's four lanes in its low half, the second's in its high half.
struct TwinMask {
  __mmask8 bits;
};
inline TwinMask operator&(TwinMask a, TwinMask b) { return {static_cast<__mmask8>(a.bits & b.bits)}; }
inline TwinMask operator|(TwinMask a, TwinMask b) { return {static_cast<__mmask8>(a.bits | b.bits)}; }
inline unsigned Bits(TwinMask m) { return m.bits; }
inline TwinMask TwinMaskOf(unsigned bits) { return {static_cast<__mmask8>(bits)}; }

struct Twin {
  static constexpr int kCount = 2 * Lanes::kCount;
  __m512d v;

  Twin() = default;
  explicit Twin(__m512d x) : v(x) {}
  Twin(Lanes a, Lanes b) : v(_mm512_insertf64x4(_mm512_castpd256_pd512(a.v), b.v, 1)) {}
  explicit Twin(double x) : v(_mm512_set1_pd(x)) {}
  Lanes One() const { return Lanes(_mm512_castpd512_pd256(v)); }
  Lanes Two() const { return Lanes(_mm512_extractf64x4_pd(v, 1)); }
  static Twin Load(TwinPtr<double> p) { return Twin(Lanes::Load(p.one), Lanes::Load(p.two)); }
  void Store(TwinPtr<double> p) const {
    One().Store(p.one);
    Two().Store(p.two);
  }
};
inline Twin operator+(Twin a, Twin b) { return Twin(_mm512_add_pd(a.v, b.v)); }
inline Twin operator-(Twin a, Twin b) { return Twin(_mm512_sub_pd(a.v, b.v)); }
inline Twin operator*(Twin a, Twin b) { return Twin(_mm512_mul_pd(a.v, b.v)); }
inline Twin operator-(Twin a) {
  return Twin(_mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a.v), _mm512_set1_epi64(INT64_MIN))));
}
inline TwinMask operator<(Twin a, Twin b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OQ)}; }
inline TwinMask operator>(Twin a, Twin b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OQ)}; }
inline TwinMask operator>=(Twin a, Twin b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GE_OQ)}; }
inline TwinMask operator!=(Twin a, Twin b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_NEQ_UQ)}; }
inline Twin Select(TwinMask m, Twin if_set, Twin if_clear) {
  return Twin(_mm512_mask_blend_pd(m.bits, if_clear.v, if_set.v));
}
inline Twin Abs(Twin a) {
  return Twin(_mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(a.v), _mm512_set1_epi64(INT64_MAX))));
}
inline Twin MaxOf(Twin a, Twin b) { return Twin(_mm512_max_pd(a.v, b.v)); }
inline Twin MinOf(Twin a, Twin b) { return Twin(_mm512_min_pd(a.v, b.v)); }
[[gnu::always_inline]] inline Twin Max0(Twin x) { return MaxOf(Twin(0.0), x); }

[[gnu::always_inline]] inline void Gather(const double* base, std::size_t stride, TwinPtr<std::int32_t> index,
                                          Twin* x, Twin* y) {
  Lanes x1, y1, x2, y2;
  Gather(base, stride, index.one, &x1, &y1);
  Gather(base, stride, index.two, &x2, &y2);
  *x = Twin(x1, x2);
  *y = Twin(y1, y2);
}
[[gnu::always_inline]] inline void Scatter(double* base, std::size_t stride, TwinPtr<std::int32_t> index, Twin x,
                                           Twin y, unsigned write) {
  Scatter(base, stride, index.one, x.One(), y.One(), write & kFirstRunBits);
  Scatter(base, stride, index.two, x.Two(), y.Two(), write >> Lanes::kCount);
}
[[gnu::always_inline]] inline Twin GatherOne(const double* base, std::size_t stride, TwinPtr<std::int32_t> index) {
  return Twin(GatherOne(base, stride, index.one), GatherOne(base, stride, index.two));
}
[[gnu::always_inline]] inline void ScatterOne(double* base, std::size_t stride, TwinPtr<std::int32_t> index, Twin x,
                                              unsigned write) {
  ScatterOne(base, stride, index.one, x.One(), write & kFirstRunBits);
  ScatterOne(base, stride, index.two, x.Two(), write >> Lanes::kCount);
}

// Eight bodies' rows of four doubles (a BodyState from its velocity on: vx, vy, angle, ω) into
// lanes, one 32-byte load a body, and back. Gathered field by field, the three fields a turning
// pass reads took 16 loads and 17 shuffles for a Twin; as rows, 8 loads and 12 shuffles (and 8
// stores instead of 16 back; the angle is written back as read).
inline constexpr bool kTwinRows = true;
[[gnu::always_inline]] inline void GatherRows(const double* base, std::size_t stride, TwinPtr<std::int32_t> index,
                                              Twin* x, Twin* y, Twin* z, Twin* w) {
  __m512d row[4];  // row k: body k's four doubles, then body k + 4's
  for (int k = 0; k < 4; ++k) {
    const __m256d low = _mm256_loadu_pd(base + static_cast<std::size_t>(index.one[k]) * stride);
    const __m256d high = _mm256_loadu_pd(base + static_cast<std::size_t>(index.two[k]) * stride);
    row[k] = _mm512_insertf64x4(_mm512_castpd256_pd512(low), high, 1);
  }
  // [x0 x1 | z0 z1 | x4 x5 | z4 z5] and [y0 y1 | w0 w1 | ...], then the same for bodies 2, 3, 6, 7.
  const __m512d xz01 = _mm512_unpacklo_pd(row[0], row[1]), yw01 = _mm512_unpackhi_pd(row[0], row[1]);
  const __m512d xz23 = _mm512_unpacklo_pd(row[2], row[3]), yw23 = _mm512_unpackhi_pd(row[2], row[3]);
  // Lanes 0, 1 from the first (elements 0, 1 or 2, 3), 2, 3 from the second (8, 9 or 10, 11), and
  // so on in the high half.
  const __m512i first = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i second = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  *x = Twin(_mm512_permutex2var_pd(xz01, first, xz23));
  *z = Twin(_mm512_permutex2var_pd(xz01, second, xz23));
  *y = Twin(_mm512_permutex2var_pd(yw01, first, yw23));
  *w = Twin(_mm512_permutex2var_pd(yw01, second, yw23));
}
[[gnu::always_inline]] inline void ScatterRows(double* base, std::size_t stride, TwinPtr<std::int32_t> index, Twin x,
                                               Twin y, Twin z, Twin w, unsigned write) {
  // GatherRows backwards.
  const __m512i low_pairs = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i high_pairs = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  const __m512d xz01 = _mm512_permutex2var_pd(x.v, low_pairs, z.v), xz23 = _mm512_permutex2var_pd(x.v, high_pairs, z.v);
  const __m512d yw01 = _mm512_permutex2var_pd(y.v, low_pairs, w.v), yw23 = _mm512_permutex2var_pd(y.v, high_pairs, w.v);
  const __m512d row[4] = {_mm512_unpacklo_pd(xz01, yw01), _mm512_unpackhi_pd(xz01, yw01),
                          _mm512_unpacklo_pd(xz23, yw23), _mm512_unpackhi_pd(xz23, yw23)};
  for (int k = 0; k < 4; ++k) {
    if (write & (1u << k)) {
      _mm256_storeu_pd(base + static_cast<std::size_t>(index.one[k]) * stride, _mm512_castpd512_pd256(row[k]));
    }
    if (write & (1u << (k + 4))) {
      _mm256_storeu_pd(base + static_cast<std::size_t>(index.two[k]) * stride, _mm512_extractf64x4_pd(row[k], 1));
    }
  }
}
#else
// Two 256-bit vectors, each operation done on the first and then on the second.
struct TwinMask {
  Mask one, two;
};
inline TwinMask operator&(TwinMask a, TwinMask b) { return {a.one & b.one, a.two & b.two}; }
inline TwinMask operator|(TwinMask a, TwinMask b) { return {a.one | b.one, a.two | b.two}; }
// The first run's lanes in the low bits, the second's above them.
inline unsigned Bits(TwinMask m) { return Bits(m.one) | Bits(m.two) << Lanes::kCount; }
inline TwinMask TwinMaskOf(unsigned bits) {
  return {MaskOf(bits & kFirstRunBits), MaskOf(bits >> Lanes::kCount)};
}

struct Twin {
  static constexpr int kCount = 2 * Lanes::kCount;
  Lanes one, two;
  Twin() = default;
  Twin(Lanes a, Lanes b) : one(a), two(b) {}
  explicit Twin(double x) : one(x), two(x) {}
  static Twin Load(TwinPtr<double> p) { return {Lanes::Load(p.one), Lanes::Load(p.two)}; }
  void Store(TwinPtr<double> p) const {
    one.Store(p.one);
    two.Store(p.two);
  }
};
inline Twin operator+(Twin a, Twin b) { return {a.one + b.one, a.two + b.two}; }
inline Twin operator-(Twin a, Twin b) { return {a.one - b.one, a.two - b.two}; }
inline Twin operator*(Twin a, Twin b) { return {a.one * b.one, a.two * b.two}; }
inline Twin operator-(Twin a) { return {-a.one, -a.two}; }
inline TwinMask operator<(Twin a, Twin b) { return {a.one < b.one, a.two < b.two}; }
inline TwinMask operator>(Twin a, Twin b) { return {a.one > b.one, a.two > b.two}; }
inline TwinMask operator>=(Twin a, Twin b) { return {a.one >= b.one, a.two >= b.two}; }
inline TwinMask operator!=(Twin a, Twin b) { return {a.one != b.one, a.two != b.two}; }
inline Twin Select(TwinMask m, Twin if_set, Twin if_clear) {
  return {Select(m.one, if_set.one, if_clear.one), Select(m.two, if_set.two, if_clear.two)};
}
inline Twin Abs(Twin a) { return {Abs(a.one), Abs(a.two)}; }
inline Twin MaxOf(Twin a, Twin b) { return {MaxOf(a.one, b.one), MaxOf(a.two, b.two)}; }
inline Twin MinOf(Twin a, Twin b) { return {MinOf(a.one, b.one), MinOf(a.two, b.two)}; }
[[gnu::always_inline]] inline Twin Max0(Twin x) { return {Max0(x.one), Max0(x.two)}; }

[[gnu::always_inline]] inline void Gather(const double* base, std::size_t stride, TwinPtr<std::int32_t> index,
                                          Twin* x, Twin* y) {
  Gather(base, stride, index.one, &x->one, &y->one);
  Gather(base, stride, index.two, &x->two, &y->two);
}
[[gnu::always_inline]] inline void Scatter(double* base, std::size_t stride, TwinPtr<std::int32_t> index, Twin x,
                                           Twin y, unsigned write) {
  Scatter(base, stride, index.one, x.one, y.one, write & kFirstRunBits);
  Scatter(base, stride, index.two, x.two, y.two, write >> Lanes::kCount);
}
[[gnu::always_inline]] inline Twin GatherOne(const double* base, std::size_t stride, TwinPtr<std::int32_t> index) {
  return {GatherOne(base, stride, index.one), GatherOne(base, stride, index.two)};
}
[[gnu::always_inline]] inline void ScatterOne(double* base, std::size_t stride, TwinPtr<std::int32_t> index, Twin x,
                                              unsigned write) {
  ScatterOne(base, stride, index.one, x.one, write & kFirstRunBits);
  ScatterOne(base, stride, index.two, x.two, write >> Lanes::kCount);
}
inline constexpr bool kTwinRows = false;
#endif

// Twin blocks: a block of each of two runs, field by field (TwinPtr), read and written as one
// through Twin lanes by the turning passes (wide_turning_kernels.inl).
struct TwinPointLanes {
  TwinPtr<double> base_separation, normal_mass, tangent_mass, normal_impulse, tangent_impulse;
  TwinPtr<double> anchor_a_x, anchor_a_y, anchor_b_x, anchor_b_y, min_normal_speed;
  TwinPointLanes(TurningPointLanes& x, TurningPointLanes& y)
      : base_separation{x.base_separation, y.base_separation}, normal_mass{x.normal_mass, y.normal_mass},
        tangent_mass{x.tangent_mass, y.tangent_mass}, normal_impulse{x.normal_impulse, y.normal_impulse},
        tangent_impulse{x.tangent_impulse, y.tangent_impulse}, anchor_a_x{x.anchor_a_x, y.anchor_a_x},
        anchor_a_y{x.anchor_a_y, y.anchor_a_y}, anchor_b_x{x.anchor_b_x, y.anchor_b_x},
        anchor_b_y{x.anchor_b_y, y.anchor_b_y}, min_normal_speed{x.min_normal_speed, y.min_normal_speed} {}
};

struct TwinSecondLanes : TwinPointLanes {
  TwinPtr<double> k11, k12, k22, det, inv_det, inv_k11, inv_k22;
  TwinSecondLanes(TurningSecondLanes& x, TurningSecondLanes& y)
      : TwinPointLanes(x, y), k11{x.k11, y.k11}, k12{x.k12, y.k12}, k22{x.k22, y.k22}, det{x.det, y.det},
        inv_det{x.inv_det, y.inv_det}, inv_k11{x.inv_k11, y.inv_k11}, inv_k22{x.inv_k22, y.inv_k22} {}
};

struct TwinBlock {
  TwinPtr<std::int32_t> a, b;
  TwinPtr<double> two_points, normal_x, normal_y, inv_mass_a, inv_mass_b, inv_inertia_a, inv_inertia_b, friction;
  TwinPointLanes first;
  TwinBlock(TurningBlock& x, TurningBlock& y)
      : a{x.a, y.a}, b{x.b, y.b}, two_points{x.two_points, y.two_points}, normal_x{x.normal_x, y.normal_x},
        normal_y{x.normal_y, y.normal_y}, inv_mass_a{x.inv_mass_a, y.inv_mass_a},
        inv_mass_b{x.inv_mass_b, y.inv_mass_b}, inv_inertia_a{x.inv_inertia_a, y.inv_inertia_a},
        inv_inertia_b{x.inv_inertia_b, y.inv_inertia_b}, friction{x.friction, y.friction}, first(x.first, y.first) {}
};
