// The closest points between two segments (Ericson, "Real-Time Collision Detection", 5.1.9).
#pragma once

#include "engine/math.h"

namespace engine::geometry {

struct SegmentDistanceResult {
  Vec2 closest1;           ///< on the first segment: p1 + fraction1·(q1 − p1)
  Vec2 closest2;           ///< on the second
  double fraction1 = 0.0;  ///< in [0, 1]; exactly 0 or 1 when the closest point is an end
  double fraction2 = 0.0;
  double distance_squared = 0.0;
};

/// Segments p1 → q1 and p2 → q2 (either may be a point). For parallel segments, whose closest
/// pairs are not unique, the pair through p1 (or its nearest end) is returned.
SegmentDistanceResult SegmentDistance(Vec2 p1, Vec2 q1, Vec2 p2, Vec2 q2);

}  // namespace engine::geometry
