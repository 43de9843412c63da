// The wall's share of the kernel, integrated numerically once per kernel size.
#include "particles/sph_kernels.h"

#include <algorithm>

namespace engine::detail {

namespace {
constexpr int kTableSize = 256;
constexpr int kLineSamples = 256;
}  // namespace

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

double WallShare::Lookup(const std::vector<double>& table, double d) const {
  const double at = std::clamp(d, 0.0, h_) / h_ * kTableSize;
  const int k = std::min(static_cast<int>(at), kTableSize - 1);
  const double f = at - k;
  return table[k] + f * (table[k + 1] - table[k]);
}

}  // namespace engine::detail
