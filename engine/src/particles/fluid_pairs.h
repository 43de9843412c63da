// The density and move passes' loops over the fluid's pairs within the kernel, for a fluid of
// one kind (every particle the same mass and rest density, as in one block): each pair's terms
// worked out once and added into both its particles, four pairs at a time with AVX2 where the
// processor has it (the density pass's kernel eight at a time with AVX-512), else one at a
// time, the same bits every way. Internal.
#pragma once

#include <cstdint>
#include <span>

#include "engine/math.h"
#include "particles/near_pairs.h"
#include "particles/sph_kernels.h"

namespace engine::detail {

/// What the density pass sums over a particle's neighbours.
struct DensitySums {
  double density = 0.0;
  Vec2 gradient;
  double denominator = 0.0;
};

/// A fluid of one kind, and where a chunk's pairs add: into `own` below `own_end` and into
/// `spill` from there on (DensityAndMoves). Particles are numbered from the fluid's first.
struct UniformPairs {
  SphKernels kernel;
  double mass, inv_mass, inv_rest;
  double clumping_over_w, clumping_strength;  ///< PBF's artificial pressure, as KernelTermsOfPairs
  std::uint32_t own_end;
};

/// For each pair (i, j) in order, with W and ∇W at x_i − x_j and g = (m/ρ0)·∇W: adds
/// (m·W, g, m⁻¹·|g|²) to i's sums and (m·W, −g, m⁻¹·|g|²) to j's. `offsets`: the pairs' as
/// PairsWithin left them. `lanes`: 1 for one pair at a time, 4 for four (AVX2, where the
/// processor has it), 0 for the widest it has (the kernel eight pairs at a time with AVX-512).
/// With four lanes or more, each full four pairs' ∇W and artificial pressure are left in
/// `terms` (3 doubles a pair) for AddMovesOfPairs.
void AddDensityOfPairs(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                       const PairOffsets& offsets, DensitySums* own, DensitySums* spill, double* terms,
                       int lanes = 0);

/// For each pair (i, j) in order, with s the artificial pressure: adds
/// ((λ_i + s)·m/ρ0 + m·(λ_j·ρ0⁻¹))·∇W to i's move and ((λ_j + s)·m/ρ0 + m·(λ_i·ρ0⁻¹))·(−∇W) to
/// j's. `terms`: AddDensityOfPairs', for the same pairs where they are, with the same `lanes`.
void AddMovesOfPairs(const UniformPairs& fluid, const Vec2* x, std::span<const ParticlePair> pairs,
                     const double* lambda, const double* terms, Vec2* own, Vec2* spill, int lanes = 0);

/// Each particle's own part of its density sums, for f in [begin, end): sums[f] = (m·W(0) +
/// ρ0·wall_share[f], wall_slope[f], 0), `self` being m·W(0); eight particles at a time with
/// AVX-512 where the processor has it (`lanes` 0), else one (`lanes` 1), the same bits.
void InitialSums(const UniformPairs& fluid, double self, double rest_density, const double* wall_share,
                 const Vec2* wall_slope, std::uint32_t begin, std::uint32_t end, DensitySums* sums, int lanes = 0);

/// Each particle's density and PBF multiplier from its sums (Macklin and Müller 2013, eq. 11),
/// for f in [begin, end): density[f] = ρ = sums[f].density and
/// lambda[f] = −max(0, ρ·ρ0⁻¹ − 1) / ((d + (m⁻¹·|g|² + wall_denominator[f])) + epsilon), d and g
/// the sums' denominator and gradient. Eight particles at a time with AVX-512 where the processor
/// has it (`lanes` 0), else one at a time (`lanes` 1), the same bits.
void MultipliersOf(const UniformPairs& fluid, const DensitySums* sums, const double* wall_denominator, double epsilon,
                   std::uint32_t begin, std::uint32_t end, double* density, double* lambda, int lanes = 0);

/// The particles moved by their moves, for f in [begin, end):
/// x[f] += share·(m⁻¹·(moves[f] + (wall_factor·lambda[f])·wall_slope[f])); four particles at a
/// time with AVX-512 where the processor has it (`lanes` 0), else one (`lanes` 1), the same bits.
void MoveParticles(const UniformPairs& fluid, const Vec2* moves, const double* lambda, const Vec2* wall_slope,
                   double wall_factor, double share, std::uint32_t begin, std::uint32_t end, Vec2* x, int lanes = 0);

/// A substep's prediction for particles [begin, end): previous[i] = x[i], then, where
/// inv_mass[i] ≠ 0, v[i] += h·gravity and x[i] += h·v[i]. Four particles at a time with AVX-512
/// where the processor has it (`lanes` 0), else one (`lanes` 1), the same bits.
void PredictParticles(Vec2 gravity, double h, const double* inv_mass, std::uint32_t begin, std::uint32_t end, Vec2* x,
                      Vec2* v, Vec2* previous, int lanes = 0);

/// A substep's velocities for particles [begin, end): v[i] = (x[i] − previous[i]) / h; lanes
/// as for PredictParticles.
void VelocitiesOfMoves(double h, const Vec2* x, const Vec2* previous, std::uint32_t begin, std::uint32_t end, Vec2* v,
                       int lanes = 0);

/// XSPH's pulls (ApplyViscosity), for any fluid (of `fluid` only the kernel and own_end count):
/// for each pair (i, j) in order, with W at x_i − x_j, adds (m_j/ρ_j·W)·(v_j − v_i) to i's pull
/// and (m_i/ρ_i·W)·(v_i − v_j) to j's, `mass_over_density` holding each particle's m/ρ.
/// `offsets` and `lanes` as for AddDensityOfPairs.
void AddPullsOfPairs(const UniformPairs& fluid, const Vec2* x, const Vec2* v, const double* mass_over_density,
                     std::span<const ParticlePair> pairs, const PairOffsets& offsets, Vec2* own, Vec2* spill,
                     int lanes = 0);

}  // namespace engine::detail
