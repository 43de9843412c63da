// The limits input must keep (docs/limits.md): past each one a run would crash, exhaust memory or
// turn numbers into infinities, so the edge refuses it as bad input (exit 2) instead.
#pragma once

#include <cstddef>
#include <cstdint>

namespace game {

/// Bodies in one scene. A million load in ~1 GB; beyond, memory and load time run away first.
inline constexpr std::size_t kMaxBodies = 1'000'000;

/// Joints in one scene: 100 000 hinged balls load in 1.4 s and 0.3 GB (docs/limits.md).
inline constexpr std::size_t kMaxJoints = 100'000;

/// Soft bodies in one scene: each is made in time that grows with the number before it, so
/// 10 000 load in well under a second (docs/limits.md).
inline constexpr std::size_t kMaxSoftBodies = 10'000;

/// Particles in one soft body: the engine's own limit (World::CreateSoftBody), checked by its
/// formula (2π·radius / spacing for a circle, (width / spacing + 1)·(height / spacing + 1) for
/// a box), which bounds the particles made from above.
inline constexpr double kMaxSoftBodyParticles = 100'000;

/// Soft-body and fluid particles in one scene together: a million step at about 2 s a step in
/// about 0.6 GB (docs/limits.md).
inline constexpr std::size_t kMaxParticles = 1'000'000;

/// The least particle spacing, as a share of how far the particles lie from the origin: finer,
/// neighbouring particles are a few roundings of a double apart (at 1e9 m a double resolves
/// 1.2e-7 m), a lattice collapses onto itself and a fluid's rows would never advance.
inline constexpr double kMinRelativeSpacing = 1e-9;

/// Emitters in one scene, and the effect particles they may keep alive at once (the sum of
/// their max_particles).
inline constexpr std::size_t kMaxEmitters = 10'000;
inline constexpr double kMaxEffectParticles = 1'000'000;

/// The least `dt` of a scene with soft bodies or fluid, s: their solver divides by the square of
/// the substep, which must stay a normal double.
inline constexpr double kMinParticleDt = 1e-9;

/// Particle substeps in one step (dt / particles.substep) and passes in one substep, as the
/// contact solver's substeps and iterations.
inline constexpr double kMaxParticleSubsteps = 1000;
inline constexpr double kMaxParticleIterations = 1000;

/// Every number in a scene, in magnitude (metres, m/s, kg, ...). Squares and products of such
/// numbers stay far inside a double's range, and a double still resolves 1e-7 m at 1e9 m.
inline constexpr double kMaxSceneMagnitude = 1e9;

/// The least mass of a dynamic body, given or density × area (kg): the largest click (1e9 N·s)
/// then changes its speed by a finite amount, and its inverse mass is a finite number.
inline constexpr double kMinBodyMass = 1e-12;

/// The least radius and box side, m: half of a smaller side can round to 0 (a side of 5e-324 is
/// positive, its half is not), and at a nanometre a body is already rounding noise beside any
/// position a scene may hold.
inline constexpr double kMinBodySize = 1e-9;

/// Scene and script files, in bytes: read whole into memory, so a huge file or an endless one
/// (/dev/zero) is refused rather than allowed to take all memory. A million-body scene is ~70 MB.
inline constexpr std::uint64_t kMaxInputFileBytes = 128ull << 20;

/// Pixels per image side: a 16384² RGBA frame is 1 GiB, and a run holds a few at once.
inline constexpr std::int64_t kMaxImageSide = 16384;

}  // namespace game
