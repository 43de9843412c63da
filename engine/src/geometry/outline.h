// A user's polygon outline checked once at the edge: point count, finite numbers, duplicate or
// all-collinear points, self-crossing; then put in the form the rest of the layer expects
// (counter-clockwise, collinear points dropped where that is safe).
#pragma once

#include <cstdint>
#include <span>

#include "engine/math.h"
#include "geometry/polygon.h"

namespace engine::geometry {

enum class OutlineProblem : std::uint8_t {
  kNone,
  kTooFewPoints,   ///< fewer than 3
  kTooManyPoints,  ///< more than kMaxPolygonVertices
  kNotFinite,      ///< `first` is the point
  kDuplicatePoint, ///< `first` and `second` are the same point (adjacent or not)
  kAllCollinear,   ///< no area: every point lies on one line
  kSelfCrossing,   ///< edges `first` and `second` (edge i runs from point i to i + 1) meet
};

struct OutlineCheck {
  OutlineProblem problem = OutlineProblem::kNone;
  int first = -1;   ///< the point or edge at fault, see OutlineProblem
  int second = -1;
  bool clockwise = false;  ///< the winding as given (valid outlines only)
  bool convex = false;     ///< once collinear points are dropped (valid outlines only)
};

/// Short text for a loader's message: "crosses itself", "has duplicate points", ...
const char* Describe(OutlineProblem problem);

/// Points of an outline, counter-clockwise.
struct Outline {
  Vec2 points[kMaxPolygonVertices];
  int count = 0;
  std::span<const Vec2> View() const { return {points, static_cast<std::size_t>(count)}; }
};

/// A point counts as collinear with its neighbours when it lies within this fraction of the
/// outline's size (its bounding box diagonal) of the line through them: rounding-level
/// deviations only, so a point a user placed off the line on purpose is kept.
inline constexpr double kCollinearTolerance = 1e-9;

OutlineCheck CheckOutline(std::span<const Vec2> points);

/// The outline counter-clockwise, without the points that lie on the segment between their two
/// neighbours (within kCollinearTolerance). Such a point is dropped only if the outline stays
/// simple without it and keeps at least three points, so dropping never makes a valid outline
/// invalid; a point that doubles back (a spike) is not collinear-between and is never dropped
/// (CheckOutline reports it as a crossing). Precondition: CheckOutline(points).problem == kNone.
Outline NormaliseOutline(std::span<const Vec2> points);

/// The diagonal of the points' bounding box: the scale the collinear tolerance is relative to.
double OutlineSize(std::span<const Vec2> points);

/// Twice the signed area (positive for counter-clockwise), by the shoelace formula.
double TwiceSignedArea(std::span<const Vec2> points);

/// Whether the closed segments [a, b] and [c, d] share a point.
bool SegmentsIntersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

}  // namespace engine::geometry
