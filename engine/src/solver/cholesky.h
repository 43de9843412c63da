// Dense Cholesky factor and solve, for the direct solves of small islands (contacts, joints).
// Row-major, lower triangle, rows `stride` apart. Internal to the engine.
#pragma once

#include <cmath>
#include <cstdint>

namespace engine::detail {

/// Factors the n×n matrix in `a` in place into L (K = L·Lᵀ); false unless positive definite.
/// With `dependent` (n entries), a row whose pivot falls to `tolerance` of its diagonal or
/// below depends on the rows before it: it is marked, left out of the factor (a unit pivot, its
/// column zeroed) and gets 0 from CholeskySolve; then only a non-finite pivot fails.
inline bool CholeskyFactor(double* a, int n, int stride, std::uint8_t* dependent = nullptr,
                           double tolerance = 0.0) {
  for (int j = 0; j < n; ++j) {
    const double diagonal = a[j * stride + j];
    double d = diagonal;
    for (int k = 0; k < j; ++k) d -= a[j * stride + k] * a[j * stride + k];
    if (dependent) {
      dependent[j] = 0;
      if (!std::isfinite(d)) return false;
      if (!(d > tolerance * diagonal)) {
        dependent[j] = 1;
        a[j * stride + j] = 1.0;
        for (int i = j + 1; i < n; ++i) a[i * stride + j] = 0.0;
        continue;
      }
    } else if (!(d > 0.0)) {
      return false;
    }
    d = std::sqrt(d);
    a[j * stride + j] = d;
    for (int i = j + 1; i < n; ++i) {
      double s = a[i * stride + j];
      for (int k = 0; k < j; ++k) s -= a[i * stride + k] * a[j * stride + k];
      a[i * stride + j] = s / d;
    }
  }
  return true;
}

/// Solves L·Lᵀ·x = b in place (x comes in as b), x = 0 for rows marked `dependent`.
inline void CholeskySolve(const double* l, int n, int stride, double* x,
                          const std::uint8_t* dependent = nullptr) {
  for (int i = 0; i < n; ++i) {
    if (dependent && dependent[i]) {
      x[i] = 0.0;
      continue;
    }
    double s = x[i];
    for (int k = 0; k < i; ++k) s -= l[i * stride + k] * x[k];
    x[i] = s / l[i * stride + i];
  }
  for (int i = n - 1; i >= 0; --i) {
    if (dependent && dependent[i]) continue;
    double s = x[i];
    for (int k = i + 1; k < n; ++k) s -= l[k * stride + i] * x[k];
    x[i] = s / l[i * stride + i];
  }
}

}  // namespace engine::detail
