// The smoothing kernel of the fluid in 2D: the spiky kernel (Müller, Charypar and Gross 2003,
// "Particle-based fluid simulation for interactive applications"), W(r) = 10/(πh⁵)·(h − r)³,
// normalised over the plane, used for the density and, as its own gradient, for the pressure.
// (PBF pairs the poly6 kernel's density with the spiky gradient; in 2D with ~20 neighbours that
// mismatch let a fluid at rest boil, measured: its kinetic energy grew to 3 kJ in a 5 m² tank,
// where the consistent pair lets it settle.) Internal.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "engine/math.h"

namespace engine::detail {

struct SphKernels {
  explicit SphKernels(double radius)
      : h(radius), h2(radius * radius), scale(10.0 / (std::numbers::pi * std::pow(radius, 5))) {}

  /// W(r) for r² = `r2`, 0 beyond h.
  double W(double r2) const { return r2 >= h2 ? 0.0 : W(r2, std::sqrt(r2)); }
  /// W(r) when r = sqrt(r2) is known already.
  double W(double r2, double r) const {
    if (r2 >= h2) return 0.0;
    const double f = h - r;
    return scale * f * f * f;
  }
  /// ∇W at offset `d` (length r): −30/(πh⁵)·(h − r)²·d/r inside h, else 0.
  Vec2 Gradient(Vec2 d, double r) const {
    if (r >= h || r == 0.0) return {};
    const double f = h - r;
    return (-3.0 * scale * f * f / r) * d;
  }

  double h, h2, scale;
};

/// A pair's kernel, its gradient at x_i − x_j (the j side's is minus it), and PBF's artificial
/// pressure between them (Macklin and Müller 2013, §4: clumping_scale·(W/W(Δq))⁴).
struct PairTerms {
  double weight;
  Vec2 gradient;
  double clumping;
};

/// A batch of pairs within the kernel: offsets dx, dy (x_i − x_j) and r2 = dx² + dy², each
/// array holding `count` rounded up to 4 entries (the extra ones finite).
struct PairBatch {
  const double* dx;
  const double* dy;
  const double* r2;
  std::uint32_t count;
};

/// terms[q] for each pair q of the batch: SphKernels::W(r2, √r2) and Gradient(d, √r2)
/// operation for operation (only the weight unless `with_gradients`), lane by lane: four
/// lanes where the processor has AVX, else two. The bits are the scalar functions' on every
/// machine: each lane's IEEE operations are the scalar ones, in their order.
void KernelTermsOfPairs(const SphKernels& k, double inv_clumping_w, double clumping_scale, bool with_gradients,
                        const PairBatch& batch, PairTerms* terms);

/// The share of the kernel's weight lying beyond a straight wall `d` from the particle (the
/// part of its neighbourhood a wall fills), and the weight along the wall's line at `d`, which
/// is minus its derivative: tabulated once, for a wall treated as fluid at rest density
/// (boundary handling after Akinci et al. 2012, "Versatile rigid-fluid coupling", with the
/// boundary's particles integrated away).
class WallShare {
 public:
  explicit WallShare(const SphKernels& kernels);
  static constexpr int kTableSize = 256;
  /// d ≥ 0 (a particle at the wall or past it counts as at the wall).
  double Share(double d) const { return Lookup(share_, d); }
  double Slope(double d) const { return -Lookup(line_, d); }
  double Reach() const { return h_; }

 private:
  // Inline: each fluid particle near a wall looks its share and slope up every substep.
  double Lookup(const std::vector<double>& table, double d) const {
    const double at = std::clamp(d, 0.0, h_) / h_ * kTableSize;
    const int k = std::min(static_cast<int>(at), kTableSize - 1);
    const double f = at - k;
    return table[k] + f * (table[k + 1] - table[k]);
  }
  double h_;
  std::vector<double> share_, line_;
};

}  // namespace engine::detail
