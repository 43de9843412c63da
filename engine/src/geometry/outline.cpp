// Outline checks by brute force over point and edge pairs: with at most 64 points that is at
// most 2016 pairs, done once when a scene loads.
#include "geometry/outline.h"

#include <algorithm>
#include <cmath>

namespace engine::geometry {

namespace {

double Orient(Vec2 a, Vec2 b, Vec2 c) { return Cross(b - a, c - a); }

// For p on the line through a and b: whether it lies between them (ends included).
bool WithinBounds(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Two edges that share the vertex `joint` (edge in → joint → out) overlap only when the second
// doubles back along the first.
bool FoldsBack(Vec2 in, Vec2 joint, Vec2 out) {
  return Orient(in, joint, out) == 0.0 && Dot(joint - in, out - joint) < 0.0;
}

// The first pair of edges (i < j, in order) that meet other than at the vertex they share.
bool FindCrossing(std::span<const Vec2> p, int* first, int* second) {
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const Vec2 a = p[i], b = p[(i + 1) % n], c = p[j], d = p[(j + 1) % n];
      bool meet;
      if (j == i + 1) {
        meet = FoldsBack(a, b, d);
      } else if (i == 0 && j == n - 1) {
        meet = FoldsBack(c, a, b);
      } else {
        meet = SegmentsIntersect(a, b, c, d);
      }
      if (meet) {
        *first = i, *second = j;
        return true;
      }
    }
  }
  return false;
}

bool FindDuplicate(std::span<const Vec2> p, int* first, int* second) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if (p[i] == p[j]) {
        *first = static_cast<int>(i), *second = static_cast<int>(j);
        return true;
      }
    }
  }
  return false;
}

// Whether every point lies within the tolerance of the line from the first point to the point
// farthest from it.
bool AllCollinear(std::span<const Vec2> p, double tolerance) {
  Vec2 farthest = p[0];
  for (const Vec2& q : p) {
    if (LengthSquared(q - p[0]) > LengthSquared(farthest - p[0])) farthest = q;
  }
  const Vec2 axis = farthest - p[0];
  const double length = Length(axis);
  return std::all_of(p.begin(), p.end(), [&](Vec2 q) {
    return std::abs(Cross(axis, q - p[0])) <= tolerance * length;
  });
}

// Whether p lies on the segment from prev to next, strictly between them, within the tolerance.
bool CollinearBetween(Vec2 prev, Vec2 p, Vec2 next, double tolerance) {
  const Vec2 chord = next - prev;
  const double along = Dot(p - prev, chord), chord_squared = LengthSquared(chord);
  return std::abs(Cross(chord, p - prev)) <= tolerance * std::sqrt(chord_squared) && along > 0.0 &&
         along < chord_squared;
}

void Erase(Outline* outline, int index) {
  std::copy(outline->points + index + 1, outline->points + outline->count, outline->points + index);
  --outline->count;
}

// Drops the collinear point at `index` if the outline stays simple without it.
bool TryDropCollinear(Outline* outline, int index, double tolerance) {
  const int n = outline->count;
  const Vec2 prev = outline->points[(index + n - 1) % n], next = outline->points[(index + 1) % n];
  if (n <= 3 || !CollinearBetween(prev, outline->points[index], next, tolerance)) return false;
  Outline without = *outline;
  Erase(&without, index);
  int first, second;
  if (FindCrossing(without.View(), &first, &second)) return false;
  *outline = without;
  return true;
}

bool IsConvex(const Outline& outline) {
  const int n = outline.count;
  for (int i = 0; i < n; ++i) {
    const Vec2 a = outline.points[i], b = outline.points[(i + 1) % n], c = outline.points[(i + 2) % n];
    if (Orient(a, b, c) <= 0.0) return false;
  }
  return true;
}

}  // namespace

bool SegmentsIntersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double o1 = Orient(a, b, c), o2 = Orient(a, b, d);
  const double o3 = Orient(c, d, a), o4 = Orient(c, d, b);
  if (((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0)) &&
      ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))) {
    return true;  // a proper crossing
  }
  // Touching: an end of one segment lies on the other.
  return (o1 == 0.0 && WithinBounds(a, b, c)) || (o2 == 0.0 && WithinBounds(a, b, d)) ||
         (o3 == 0.0 && WithinBounds(c, d, a)) || (o4 == 0.0 && WithinBounds(c, d, b));
}

double OutlineSize(std::span<const Vec2> points) {
  Vec2 lower = points[0], upper = points[0];
  for (const Vec2& p : points) {
    lower = {std::min(lower.x, p.x), std::min(lower.y, p.y)};
    upper = {std::max(upper.x, p.x), std::max(upper.y, p.y)};
  }
  return Length(upper - lower);
}

double TwiceSignedArea(std::span<const Vec2> points) {
  // Relative to the first point, so a polygon far from the origin keeps its precision.
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    sum += Cross(points[i] - points[0], points[i + 1] - points[0]);
  }
  return sum;
}

const char* Describe(OutlineProblem problem) {
  switch (problem) {
    case OutlineProblem::kNone: return "is valid";
    case OutlineProblem::kTooFewPoints: return "needs at least 3 points";
    case OutlineProblem::kTooManyPoints: return "has more than 64 points";
    case OutlineProblem::kNotFinite: return "has a point that is not a finite number";
    case OutlineProblem::kDuplicatePoint: return "has duplicate points";
    case OutlineProblem::kAllCollinear: return "has all its points on one line (no area)";
    case OutlineProblem::kSelfCrossing: return "crosses itself (two edges meet)";
  }
  return "is invalid";
}

OutlineCheck CheckOutline(std::span<const Vec2> points) {
  OutlineCheck check;
  if (points.size() < 3) return {OutlineProblem::kTooFewPoints};
  if (points.size() > kMaxPolygonVertices) return {OutlineProblem::kTooManyPoints};
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!IsFinite(points[i])) return {OutlineProblem::kNotFinite, static_cast<int>(i)};
  }
  if (FindDuplicate(points, &check.first, &check.second)) {
    check.problem = OutlineProblem::kDuplicatePoint;
    return check;
  }
  if (AllCollinear(points, kCollinearTolerance * OutlineSize(points))) {
    return {OutlineProblem::kAllCollinear};
  }
  if (FindCrossing(points, &check.first, &check.second)) {
    check.problem = OutlineProblem::kSelfCrossing;
    return check;
  }
  check.clockwise = TwiceSignedArea(points) < 0.0;
  check.convex = IsConvex(NormaliseOutline(points));
  return check;
}

Outline NormaliseOutline(std::span<const Vec2> points) {
  Outline outline;
  outline.count = static_cast<int>(points.size());
  std::copy(points.begin(), points.end(), outline.points);
  if (TwiceSignedArea(points) < 0.0) std::reverse(outline.points, outline.points + outline.count);
  // Passes until nothing more drops: dropping one point can make its neighbour collinear-between.
  const double tolerance = kCollinearTolerance * OutlineSize(points);
  for (bool dropped = true; dropped;) {
    dropped = false;
    for (int i = 0; i < outline.count;) {
      if (TryDropCollinear(&outline, i, tolerance)) {
        dropped = true;
      } else {
        ++i;
      }
    }
  }
  return outline;
}

}  // namespace engine::geometry
