// Polylines (open or closed) as chain segments: each segment carries its neighbours' far
// vertices (Box2D's ghost vertices), which tell the collider whether a join is flat, convex or
// concave, so that a shape sliding along a straight run never catches on a join.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/math.h"

namespace engine::geometry {

/// The segment from point1 to point2; ghost1 → point1 is the segment before it and
/// point2 → ghost2 the one after. At a free end of an open polyline the ghost is the end point
/// itself (ghost1 == point1 or ghost2 == point2): nothing continues there.
struct ChainSegment {
  Vec2 ghost1;
  Vec2 point1;
  Vec2 point2;
  Vec2 ghost2;
};

constexpr bool HasFreeStart(const ChainSegment& s) { return s.ghost1 == s.point1; }
constexpr bool HasFreeEnd(const ChainSegment& s) { return s.ghost2 == s.point2; }

enum class ChainProblem : std::uint8_t {
  kNone,
  kTooFewPoints,  ///< an open polyline needs 2 points, a loop 3
  kNotFinite,     ///< `index` is the point
  kZeroLength,    ///< segment `index` (from point index to the next) has no length
};

struct ChainCheck {
  ChainProblem problem = ChainProblem::kNone;
  int index = -1;
};

ChainCheck CheckChain(std::span<const Vec2> points, bool loop);

/// One segment per pair of consecutive points (plus the closing one for a loop), in order.
/// Precondition: CheckChain(points, loop).problem == kNone.
std::vector<ChainSegment> MakeChain(std::span<const Vec2> points, bool loop);

}  // namespace engine::geometry
