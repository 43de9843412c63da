// The engine's own cos/sin, n-th root and hypot (engine/portable_math.h) against long double libm:
// the error bounds their comments state, over dense sweeps and the edge values, and identities.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "engine/math.h"
#include "engine/portable_math.h"

using engine::ComputeCosSin;
using engine::CosSin;

namespace {

// The double nearest π/2 (a little below the true π/2).
constexpr double kHalfPi = 1.5707963267948966;

// The spacing of doubles at the true value `want`: its error unit.
long double UlpOf(long double want) {
  int e = 0;
  std::frexp(want, &e);
  return std::max(std::ldexp(1.0L, e - 53), std::ldexp(1.0L, -1074));
}

long double Ulps(double got, long double want) { return std::abs(got - want) / UlpOf(want); }

// The larger of the cosine's and the sine's absolute error at x.
long double CosSinError(double x) {
  const CosSin q = ComputeCosSin(x);
  return std::max(std::abs(q.c - std::cos(static_cast<long double>(x))),
                  std::abs(q.s - std::sin(static_cast<long double>(x))));
}

long double UnitLengthError(double x) {
  const CosSin q = ComputeCosSin(x);
  return std::abs(static_cast<long double>(q.c) * q.c + static_cast<long double>(q.s) * q.s - 1.0L);
}

// A dense sweep of [-10, 10], then a million random angles up to ±1e6 and ten thousand up to the
// exact range's end, 1.5·2^32.
std::vector<double> Angles() {
  std::vector<double> x;
  for (int i = -1'000'000; i <= 1'000'000; ++i) x.push_back(i * 1e-5);
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> wide(-1e6, 1e6);
  for (int i = 0; i < 1'000'000; ++i) x.push_back(wide(rng));
  std::uniform_real_distribution<double> widest(-0x1.8p32, 0x1.8p32);
  for (int i = 0; i < 10'000; ++i) x.push_back(widest(rng));
  return x;
}

}  // namespace

TEST_CASE("portable math: the reference is more precise than double", "[portable_math]") {
  REQUIRE(std::numeric_limits<long double>::digits >= 64);
}

TEST_CASE("ComputeCosSin: within 1 ulp of cos and sin where |x| <= pi/4", "[portable_math]") {
  long double worst = 0;
  for (int i = -1'000'000; i <= 1'000'000; ++i) {
    const double x = i * (0.78539816339744828 / 1'000'000);  // up to the double nearest π/4
    const CosSin q = ComputeCosSin(x);
    worst = std::max({worst, Ulps(q.c, std::cos(static_cast<long double>(x))),
                      Ulps(q.s, std::sin(static_cast<long double>(x)))});
  }
  INFO("worst " << static_cast<double>(worst) << " ulp");
  CHECK(worst <= 1.0L);
}

TEST_CASE("ComputeCosSin: within 1.5e-16 up to 6.4e9 rad, unit length within 1.2 * 2^-52",
          "[portable_math]") {
  long double worst = 0, worst_length = 0;
  for (double x : Angles()) {
    worst = std::max(worst, CosSinError(x));
    worst_length = std::max(worst_length, UnitLengthError(x));
  }
  INFO("worst " << static_cast<double>(worst) << ", |c^2 + s^2 - 1| "
                << static_cast<double>(worst_length / 0x1p-52L) << " * 2^-52");
  CHECK(worst <= 1.5e-16L);
  CHECK(worst_length <= 1.2L * 0x1p-52L);
}

TEST_CASE("ComputeCosSin: multiples of pi/2 and pi, and quarter turns' neighbours",
          "[portable_math]") {
  long double worst = 0;
  for (int k = -1'000'000; k <= 1'000'000; k += 997) {
    for (double x : {k * kHalfPi, k * 3.141592653589793, std::nextafter(k * kHalfPi, 0.0)}) {
      worst = std::max(worst, CosSinError(x));
    }
  }
  // Halfway between quadrants the reduction's rounding of k is decided by an ulp.
  for (int k = -1000; k <= 1000; ++k) {
    const double x = (k + 0.5) * kHalfPi;
    for (double y : {std::nextafter(x, -1e300), x, std::nextafter(x, 1e300)}) {
      worst = std::max(worst, CosSinError(y));
    }
  }
  CHECK(worst <= 1.5e-16L);
}

TEST_CASE("ComputeCosSin: edge values", "[portable_math]") {
  // No turn is exactly no turn: the axis-aligned game depends on it.
  const CosSin zero = ComputeCosSin(0.0);
  CHECK(zero.c == 1.0);
  CHECK(zero.s == 0.0);
  CHECK(!std::signbit(zero.s));
  CHECK(std::signbit(ComputeCosSin(-0.0).s));
  const engine::Rot none = engine::MakeRot(0.0);
  CHECK((none.c == 1.0 && none.s == 0.0));

  // At the double nearest π/2 the cosine is the tiny gap to the true π/2, 6.12e-17: the
  // reduction must keep it to many digits, not to an absolute 1e-16.
  const CosSin quarter = ComputeCosSin(kHalfPi);
  CHECK(quarter.s == 1.0);
  CHECK(quarter.c == Approx(static_cast<double>(std::cos(static_cast<long double>(kHalfPi)))).epsilon(1e-14));
  CHECK(quarter.c > 0.0);
  CHECK(ComputeCosSin(-kHalfPi).s == -1.0);
  const CosSin half = ComputeCosSin(3.141592653589793);
  CHECK(half.c == -1.0);
  CHECK(half.s == Approx(1.2246467991473532e-16).epsilon(1e-14));

  for (double x : {1e6, -1e6, 1e9, -1e9, 6e9, 0.5235987755982988, 1.0471975511965976}) {
    INFO("x = " << x);
    CHECK(CosSinError(x) <= 1.5e-16L);
  }
  CHECK(ComputeCosSin(0.5235987755982988).s == Approx(0.5).epsilon(2e-16));  // π/6

  // Non-finite angles give NaNs with the same bits on every machine: a NaN comes back as it is,
  // infinities give the quiet NaN (inf − inf would set the sign bit on x86-64 only).
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double payload = std::bit_cast<double>(bits(nan) | 0x8000000000000123);
  for (double x : {nan, payload, std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()}) {
    const CosSin q = ComputeCosSin(x);
    const double want = std::isnan(x) ? x : nan;
    CHECK(bits(q.c) == bits(want));
    CHECK(bits(q.s) == bits(want));
  }
}

TEST_CASE("ComputeCosSin: past 6.4e9 rad, within an ulp of the angle and still a rotation",
          "[portable_math]") {
  for (double x : {1e10, -3e10, 1e12, 1e15}) {
    for (int i = 0; i < 100; ++i) {
      const double y = x * (1 + i * 1e-9);
      INFO("x = " << y);
      CHECK(CosSinError(y) <= std::nextafter(std::abs(y), 1e300) - std::abs(y));
      CHECK(UnitLengthError(y) <= 1.2L * 0x1p-52L);
    }
  }
  for (double x : {1e18, 1e300, std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()}) {
    INFO("x = " << x);
    CHECK(UnitLengthError(x) <= 1.2L * 0x1p-52L);
  }
}

TEST_CASE("ComputeCosSin: sin is odd and cos even, bit for bit", "[portable_math]") {
  int broken = 0;
  for (double x : Angles()) {
    const CosSin p = ComputeCosSin(x);
    const CosSin m = ComputeCosSin(-x);
    if (std::bit_cast<std::uint64_t>(m.s) != std::bit_cast<std::uint64_t>(-p.s) ||
        std::bit_cast<std::uint64_t>(m.c) != std::bit_cast<std::uint64_t>(p.c)) {
      ++broken;
    }
  }
  CHECK(broken == 0);
}

TEST_CASE("NthRoot: within 1.1 ulp of a^(1/n)", "[portable_math]") {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  long double worst = 0;
  for (int n = 1; n <= 64; ++n) {
    for (int i = 0; i < 20'000; ++i) {
      const double a = i % 2 == 0 ? unit(rng) : std::pow(10.0, exponent(rng));
      worst = std::max(worst, Ulps(engine::NthRoot(a, n), std::pow(static_cast<long double>(a), 1.0L / n)));
    }
  }
  INFO("worst " << static_cast<double>(worst) << " ulp");
  CHECK(worst <= 1.1L);
  // The substep solver's push-out rate: (1 - 0.8)^(1/n) with 4 and 8 substeps.
  for (int n : {4, 8}) CHECK(Ulps(engine::NthRoot(0.2, n), std::pow(0.2L, 1.0L / n)) <= 0.5L);
}

TEST_CASE("NthRoot: exact roots, the ends of the range, bad input", "[portable_math]") {
  CHECK(engine::NthRoot(0.0625, 4) == 0.5);
  CHECK(engine::NthRoot(81.0, 4) == 3.0);
  CHECK(engine::NthRoot(0x1p-1000, 8) == 0x1p-125);
  CHECK(engine::NthRoot(0x1p1000, 8) == 0x1p125);
  CHECK(engine::NthRoot(1e-300, 2) == std::sqrt(1e-300));
  CHECK(engine::NthRoot(0.3, 1) == 0.3);
  CHECK(engine::NthRoot(0.0, 7) == 0.0);
  CHECK(engine::NthRoot(1.0, 7) == 1.0);
  CHECK(engine::NthRoot(std::numeric_limits<double>::infinity(), 3) == std::numeric_limits<double>::infinity());
  const std::uint64_t nan = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::quiet_NaN());
  CHECK(std::bit_cast<std::uint64_t>(engine::NthRoot(-0.5, 3)) == nan);
  CHECK(std::bit_cast<std::uint64_t>(engine::NthRoot(-std::numeric_limits<double>::infinity(), 3)) == nan);
  CHECK(std::bit_cast<std::uint64_t>(engine::NthRoot(std::numeric_limits<double>::quiet_NaN(), 3)) == nan);
}

TEST_CASE("Hypot: within 1.25 ulp from subnormal to near overflow", "[portable_math]") {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> exponent(-320.0, 304.0);
  std::uniform_real_distribution<double> spread(-3.0, 3.0);
  long double worst = 0;
  for (int i = 0; i < 1'000'000; ++i) {
    const double a = (i % 2 == 0 ? 1 : -1) * std::pow(10.0, exponent(rng));
    // Half the pairs of like size (the sum matters), half of any sizes.
    const double b = i % 4 < 2 ? a * std::pow(10.0, spread(rng)) : std::pow(10.0, exponent(rng));
    const long double la = a, lb = b;
    worst = std::max(worst, Ulps(engine::Hypot(a, b), std::sqrt(la * la + lb * lb)));
  }
  INFO("worst " << static_cast<double>(worst) << " ulp");
  CHECK(worst <= 1.25L);
}

TEST_CASE("Hypot: exact cases and the edges", "[portable_math]") {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  CHECK(engine::Hypot(3.0, 4.0) == 5.0);
  CHECK(engine::Hypot(-3.0, -4.0) == 5.0);
  CHECK(engine::Hypot(0.0, 0.0) == 0.0);
  CHECK(engine::Hypot(0.0, -2.5) == 2.5);
  CHECK(engine::Hypot(3e300, 4e300) == Approx(5e300).epsilon(1e-15));
  CHECK(engine::Hypot(3e-310, 4e-310) == Approx(5e-310).epsilon(1e-9));  // subnormal: fewer digits
  CHECK(engine::Hypot(std::numeric_limits<double>::max(), 0.0) == std::numeric_limits<double>::max());
  CHECK(engine::Hypot(kInf, 1.0) == kInf);
  CHECK(engine::Hypot(1.0, -kInf) == kInf);
  CHECK(std::isnan(engine::Hypot(std::numeric_limits<double>::quiet_NaN(), 1.0)));
}

TEST_CASE("portable Exp is within 1 ulp of e^x, overflows and underflows where libm does", "[portable_math]") {
  long double worst = 0.0L;
  double worst_at = 0.0;
  const auto check = [&](double x) {
    const long double want = std::exp(static_cast<long double>(x));
    if (want < std::numeric_limits<double>::min()) return;  // subnormal results: checked below
    const long double e = Ulps(engine::Exp(x), want);
    if (e > worst) worst = e, worst_at = x;
  };
  for (int i = -200000; i <= 200000; ++i) check(i * 1e-5);            // |x| ≤ 2, where drag lives
  for (int i = -70800; i <= 70900; ++i) check(i * 0.01 + 1e-7 * i);   // the whole range
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> any(-708.0, 709.0);
  for (int i = 0; i < 200000; ++i) check(any(random));
  INFO("worst " << static_cast<double>(worst) << " ulp at " << worst_at);
  CHECK(worst <= 1.0L);
  CHECK(engine::Exp(0.0) == 1.0);
  CHECK(engine::Exp(1.0) == Approx(2.718281828459045).epsilon(1e-15));
  CHECK(std::isinf(engine::Exp(710.0)));
  CHECK(engine::Exp(-746.0) == 0.0);
  CHECK(std::isnan(engine::Exp(std::nan(""))));
  CHECK(engine::Exp(-740.0) > 0.0);  // subnormal, not flushed
  CHECK(std::abs(engine::Exp(-740.0) - std::exp(-740.0)) <= std::ldexp(1.0, -1074));
}

TEST_CASE("Larger and Smaller: a > b ? a : b and a < b ? a : b, signed zeros and NaN included",
          "[portable_math]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(engine::Larger(1.0, 2.0) == 2.0);
  CHECK(engine::Larger(-1.0, -2.0) == -1.0);
  CHECK(engine::Smaller(1.0, 2.0) == 1.0);
  CHECK(engine::Smaller(-1.0, -2.0) == -2.0);
  // Equal: the second, whichever zero it is (std::fmax may give either, by machine).
  CHECK(std::signbit(engine::Larger(0.0, -0.0)));
  CHECK_FALSE(std::signbit(engine::Larger(-0.0, 0.0)));
  CHECK(std::signbit(engine::Smaller(0.0, -0.0)));
  CHECK_FALSE(std::signbit(engine::Smaller(-0.0, 0.0)));
  // NaN on either side: the second.
  CHECK(engine::Larger(nan, 3.0) == 3.0);
  CHECK(std::isnan(engine::Larger(3.0, nan)));
  CHECK(engine::Smaller(nan, 3.0) == 3.0);
  CHECK(std::isnan(engine::Smaller(3.0, nan)));
}
