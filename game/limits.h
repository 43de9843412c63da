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
