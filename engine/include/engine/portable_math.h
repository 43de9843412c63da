// Cosine and sine, n-th roots and hypot built from + − × ÷ and sqrt alone: IEEE-754 rounds those
// exactly, so every 64-bit machine and compiler gets the same bits, which libm does not promise.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace engine {

/// The cosine and sine of one angle.
struct CosSin {
  double c = 1.0;
  double s = 0.0;
};

/// The larger of a and b, as `a > b ? a : b`: b where they are equal (±0 included) or either is
/// NaN. One instruction on x86-64 (maxsd), and the same answer on every machine, where
/// std::fmax is a call into libm and orders −0 and +0 as each machine's library does.
inline double Larger(double a, double b) { return a > b ? a : b; }
/// The smaller of a and b, as `a < b ? a : b` (b where they are equal or either is NaN).
inline double Smaller(double a, double b) { return a < b ? a : b; }

namespace portable_detail {

// π/2 = kPiOver2A + kPiOver2B + kPiOver2C to 95 bits. A and B hold 21 significant bits each, so
// k·A and k·B are exact for |k| ≤ 2^32 (Cody and Waite, "Software Manual for the Elementary
// Functions", 1980).
inline constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
inline constexpr double kPiOver2A = 0x1.921fbp+0;
inline constexpr double kPiOver2B = 0x1.5110bp-22;
inline constexpr double kPiOver2C = 0x1.18469898cc517p-44;

// Where |k| ≤ 2^32, so the reduction below is exact enough for any scene.
inline constexpr double kLargestExactAngle = 0x1.8p32;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Whole turns taken off an angle past kLargestExactAngle: k·A is rounded there, to about half an
// ulp of the angle, and each pass shrinks the angle by about 2^-51 until it is in range. The
// same rotation, as far as the angle resolves one. Precondition: `angle` is finite.
inline double ShrinkHugeAngle(double angle) {
  while (std::abs(angle) > kLargestExactAngle) {
    const double turns = angle * (kTwoOverPi / 4);  // a quarter of y: the power of two is exact
    const double k = 4 * (std::abs(turns) < 0x1p52 ? std::round(turns) : turns);
    angle = ((angle - k * kPiOver2A) - k * kPiOver2B) - k * kPiOver2C;
  }
  return angle;
}

// Taylor series for |r| ≤ π/4 (+ a few ulps): the first term left out is below 1e-19. Written
// for any T with + − × and T(double): the engine's SIMD lanes run the same operations in the same
// order (engine/src/solver/wide_cos_sin.inl), so a lane gets a double's bits.
template <typename T>
inline T SinTaylor(T r) {
  const T r2 = r * r;
  const T tail =
      T(-1.0 / 6) +
      r2 * (T(1.0 / 120) +
            r2 * (T(-1.0 / 5040) +
                  r2 * (T(1.0 / 362880) +
                        r2 * (T(-1.0 / 39916800) +
                              r2 * (T(1.0 / 6227020800) +
                                    r2 * (T(-1.0 / 1307674368000) + r2 * T(1.0 / 355687428096000)))))));
  return r + r * r2 * tail;
}

template <typename T>
inline T CosTaylor(T r) {
  const T r2 = r * r;
  const T tail =
      T(1.0 / 24) +
      r2 * (T(-1.0 / 720) +
            r2 * (T(1.0 / 40320) +
                  r2 * (T(-1.0 / 3628800) +
                        r2 * (T(1.0 / 479001600) +
                              r2 * (T(-1.0 / 87178291200) + r2 * T(1.0 / 20922789888000))))));
  return T(1.0) - (T(0.5) * r2 - r2 * r2 * tail);
}

// x^n by squaring, n ≥ 0: the same products in the same order everywhere.
inline double PowInt(double x, int n) {
  double result = 1.0;
  while (n > 0) {
    if (n & 1) result *= x;
    x *= x;
    n >>= 1;
  }
  return result;
}

/// ComputeCosSin's work, for a caller that takes it inline (the engine's StoreRot).
[[gnu::always_inline]] inline CosSin CosSinOf(double angle) {
  // No turn, the axis-aligned bodies' case, at no cost; ±0 keeps its sign, as sin(±0) = ±0.
  if (angle == 0.0) return {1.0, angle};
  if (!(std::abs(angle) <= kLargestExactAngle)) {
    if (std::isnan(angle)) return {angle, angle};
    // Not inf − inf: its NaN has the sign bit set on x86-64 and clear on arm64.
    if (std::isinf(angle)) return {kNaN, kNaN};
    angle = ShrinkHugeAngle(angle);
  }
  const double y = angle * kTwoOverPi;
  // k: y rounded to a whole number, halves away from zero (symmetric, so sin stays odd).
  const auto n = static_cast<std::int64_t>(y + std::copysign(0.5, y));
  const double k = static_cast<double>(n);
  const double r = ((angle - k * kPiOver2A) - k * kPiOver2B) - k * kPiOver2C;
  const double sin_r = SinTaylor(r);
  const double cos_r = CosTaylor(r);
  const int quadrant = static_cast<int>(n & 3);  // two's complement keeps it right below zero
  const bool odd = (quadrant & 1) != 0;
  double s = odd ? cos_r : sin_r;
  double c = odd ? sin_r : cos_r;
  if (quadrant >= 2) s = -s;
  if (quadrant == 1 || quadrant == 2) c = -c;
  return {c, s};
}

}  // namespace portable_detail

/// cos and sin of `angle` (radians). For |angle| ≤ 1.5·2^32 (6.4e9 rad, past any scene's limit
/// of 1e9) each is within 1.5e-16 of the true value (about an ulp of the larger), within
/// 1 ulp where no reduction is needed (|angle| ≤ π/4), and c² + s² is 1 within 1.2·2^-52; odd
/// and even symmetry hold bit for bit (tests/test_portable_math.cpp measures all of it). Past
/// 6.4e9 the error grows to about half an ulp of the angle itself, the angle's own resolution.
/// A NaN comes back as it is; infinities give std::numeric_limits<double>::quiet_NaN().
/// Method: angle = k·π/2 + r with |r| ≤ π/4 (Cody and Waite's reduction), Taylor polynomials
/// for sin r and cos r, and k mod 4 picks and signs them. Box2D v3's b2ComputeCosSin (Erin
/// Catto, "Determinism", box2d.org, 2024) also divides (c, s) by its length, which its coarse
/// approximation needs; here that division measured worse (1.6 ulp) and no closer to unit length.
/// Kept out of line: inlined, it grew its callers until GCC stopped inlining BodyBounds into the
/// broad phase's loop (+0.15 % instructions on a circle pour that never turns a body).
[[gnu::noinline]] inline CosSin ComputeCosSin(double angle) { return portable_detail::CosSinOf(angle); }

/// a^(1/n) for a ≥ 0 and n ≥ 1, within 1.1 ulp of the true root (1.04 the worst found for
/// n ≤ 64 and a from 1e-300 to 1e300; tests/test_portable_math.cpp checks the bound); exact
/// roots come out exact, +inf stays +inf. std::numeric_limits<double>::quiet_NaN() for a < 0 or a NaN.
/// Method: Newton's iteration on x^n = a from a power of two above the root (at most twice it),
/// where it falls monotonically; it stops when a step no longer lowers x, so it always ends.
inline double NthRoot(double a, int n) {
  using portable_detail::kNaN;
  if (n == 1 || a == 0.0 || a == 1.0 || std::isinf(a)) return a >= 0.0 ? a : kNaN;
  if (!(a > 0.0)) return kNaN;
  int e = 0;
  std::frexp(a, &e);  // a < 2^e, so a^(1/n) < 2^(e/n) ≤ 2^ceil(e/n)
  const int up = e > 0 ? (e + n - 1) / n : -(-e / n);
  double x = std::ldexp(1.0, up);
  for (;;) {
    // x − (x^n − a) / (n·x^(n−1)), written so the correction is a small difference.
    const double next = x - (x - a / portable_detail::PowInt(x, n - 1)) / n;
    if (!(next < x)) return x;
    x = next;
  }
}

/// √(a² + b²) within 1.25 ulp for any finite a and b (the squares, their sum and the root round
/// once each); where the squares would overflow or underflow, a and b are scaled by a power of
/// two first. An infinity gives +inf; a NaN, even beside an infinity, comes back as NaN.
inline double Hypot(double a, double b) {
  a = std::abs(a);
  b = std::abs(b);
  const double big = a > b ? a : b;
  if ((big > 0x1p-500 && big < 0x1p500) || big == 0.0 || !std::isfinite(big)) {
    return std::sqrt(a * a + b * b);
  }
  int e = 0;
  std::frexp(big, &e);
  const double sa = std::ldexp(a, -e);
  const double sb = std::ldexp(b, -e);
  return std::ldexp(std::sqrt(sa * sa + sb * sb), e);
}

/// e^x within 1 ulp (0.93 the worst tests/test_portable_math.cpp finds against long double libm), the same
/// bits everywhere. Overflows to +inf above 709.78, underflows to 0 below −745.2; a NaN comes
/// back as it is. Method: x = k·ln 2 + r with |r| ≤ ln(2)/2 (Cody and Waite's reduction, ln 2
/// split in two as fdlibm's e_exp.c splits it, so k·ln2_hi is exact), a Taylor polynomial for
/// e^r to the 14th power (the next term is below 2^-60 of it), scaled by 2^k.
inline double Exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0.0;
  constexpr double kLn2Hi = 0x1.62e42feep-1;  // ln 2 to 33 bits: k·kLn2Hi is exact for |k| < 2^20
  constexpr double kLn2Lo = 0x1.a39ef35793c76p-33;
  constexpr double kInvLn2 = 0x1.71547652b82fep0;
  const double y = x * kInvLn2;
  const auto n = static_cast<std::int64_t>(y + std::copysign(0.5, y));
  const double k = static_cast<double>(n);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  // e^r = 1 + r + r²·(1/2! + r/3! + …): the small tail added last keeps the rounding small.
  double tail = 1.0 / 87178291200.0;  // 1/14!
  constexpr double kInverseFactorials[] = {1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0,
                                           1.0 / 3628800.0,    1.0 / 362880.0,    1.0 / 40320.0,
                                           1.0 / 5040.0,       1.0 / 720.0,       1.0 / 120.0,
                                           1.0 / 24.0,         1.0 / 6.0,         1.0 / 2.0};
  for (const double f : kInverseFactorials) tail = f + r * tail;
  return std::ldexp(1.0 + (r + r * r * tail), static_cast<int>(n));
}

}  // namespace engine
