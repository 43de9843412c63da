// The smoothing kernels of position-based fluids in 2D (Müller, Charypar and Gross 2003,
// "Particle-based fluid simulation for interactive applications"), normalised over the plane:
// poly6 for density, the spiky kernel's gradient for pressure. Internal.
#pragma once

#include <cmath>
#include <numbers>

#include "engine/math.h"

namespace engine::detail {

struct SphKernels {
  explicit SphKernels(double radius)
      : h(radius),
        h2(radius * radius),
        poly6(4.0 / (std::numbers::pi * std::pow(radius, 8))),
        spiky(-30.0 / (std::numbers::pi * std::pow(radius, 5))) {}

  /// W(r) for r² = `r2`: 4/(πh⁸)·(h² − r²)³ inside h, else 0.
  double Poly6(double r2) const {
    if (r2 >= h2) return 0.0;
    const double d = h2 - r2;
    return poly6 * d * d * d;
  }
  /// ∇W at offset `d` (length r): −30/(πh⁵)·(h − r)²·d/r inside h, else 0.
  Vec2 SpikyGradient(Vec2 d, double r) const {
    if (r >= h || r == 0.0) return {};
    const double f = h - r;
    return (spiky * f * f / r) * d;
  }

  double h, h2, poly6, spiky;
};

}  // namespace engine::detail
