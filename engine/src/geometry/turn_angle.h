// The angle between two directions from + − × ÷ and √ only, so it is the same bits on every
// machine (libm's atan2 is not required to be).
#pragma once

#include "engine/math.h"

namespace engine::geometry {

inline constexpr double kPi = 3.14159265358979323846;

/// The arctangent of y / x in (−π, π], as std::atan2 (to within a few ulps), with (0, 0) → 0.
double PortableAtan2(double y, double x);

/// The counter-clockwise angle in [0, 2π) that turns direction `from` onto direction `to`
/// (neither needs unit length; a zero vector gives 0).
double TurnAngle(Vec2 from, Vec2 to);

}  // namespace engine::geometry
