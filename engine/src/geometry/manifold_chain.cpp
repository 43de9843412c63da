// Chain segments against circles and polygons without ghost collisions. The segment is seen from
// the shape's side; a candidate normal that leans past the segment's face towards an end is
// checked against the join there (after Box2D v3's b2ClassifyNormal): at a free end or within a
// convex join's fan it is admitted, beyond the fan it belongs to the neighbour (skipped), and at
// a flat or concave join it is snapped to the face normal, the only normal such a join can give.
#include <cmath>

#include "geometry/clip.h"
#include "geometry/gjk.h"
#include "geometry/manifold.h"

namespace engine::geometry {

namespace {

// Joins turning less than this (sine of the turn, about 0.6°) count as flat; a normal leaning
// this much past a convex join's fan belongs to the neighbour.
constexpr double kFlatSin = 0.01;
constexpr double kSkipSin = 0.01;

enum class Verdict { kAdmit, kSkip, kSnap };

// One end of the segment as seen from the shape's side.
struct SegmentEnd {
  bool free = true;
  bool convex = false;  // the polyline turns away from the shape there
  Vec2 neighbour_normal;
};

// The segment turned so that the shape's side is on the left: normal = LeftPerp(tangent).
struct SideView {
  Vec2 start, end, tangent, normal;
  double length = 0.0;
  SegmentEnd at_start, at_end;
};

// Whether c is on the left of the polyline prev → joint → next near the joint: on the left of
// both lines where the polyline turns left (the left side is the narrow one), of either where it
// turns right.
bool LeftOfJoin(Vec2 prev, Vec2 joint, Vec2 next, Vec2 c) {
  const bool left_in = Cross(joint - prev, c - joint) >= 0.0;
  const bool left_out = Cross(next - joint, c - joint) >= 0.0;
  return Cross(joint - prev, next - joint) < 0.0 ? left_in || left_out : left_in && left_out;
}

// The side of the polyline the point c lies on: the segment's line settles it alongside the
// segment, the join beyond an end that continues.
bool OnLeft(const ChainSegment& s, Vec2 c) {
  const Vec2 t = s.point2 - s.point1;
  const double along = Dot(c - s.point1, t);
  if (along < 0.0 && !HasFreeStart(s)) return LeftOfJoin(s.ghost1, s.point1, s.point2, c);
  if (along > Dot(t, t) && !HasFreeEnd(s)) return LeftOfJoin(s.point1, s.point2, s.ghost2, c);
  return Cross(t, c - s.point1) >= 0.0;
}

// `direction` runs along the neighbour away from (into) the segment's end; `turn_sign` makes a
// turn away from the left side negative at either end.
SegmentEnd MakeEnd(bool free, Vec2 direction, Vec2 tangent, double turn_sign) {
  const double length = Length(direction);
  if (free || !(length > 0.0)) return {};  // a neighbour of no length (rounding) continues nothing
  const Vec2 t = direction / length;
  return {false, turn_sign * Cross(t, tangent) < -kFlatSin, LeftPerp(t)};
}

SideView MakeSideView(const ChainSegment& s, Vec2 shape_center) {
  const bool left = OnLeft(s, shape_center);
  SideView v;
  v.start = left ? s.point1 : s.point2;
  v.end = left ? s.point2 : s.point1;
  const Vec2 ghost_start = left ? s.ghost1 : s.ghost2, ghost_end = left ? s.ghost2 : s.ghost1;
  v.length = Length(v.end - v.start);
  v.tangent = (v.end - v.start) / v.length;
  v.normal = LeftPerp(v.tangent);
  const bool free_start = left ? HasFreeStart(s) : HasFreeEnd(s);
  const bool free_end = left ? HasFreeEnd(s) : HasFreeStart(s);
  v.at_start = MakeEnd(free_start, v.start - ghost_start, v.tangent, 1.0);
  v.at_end = MakeEnd(free_end, ghost_end - v.end, v.tangent, -1.0);
  return v;
}

Verdict Classify(const SideView& v, Vec2 n) {
  if (Dot(n, v.tangent) <= 0.0) {  // leans towards the start
    if (v.at_start.free) return Verdict::kAdmit;
    if (!v.at_start.convex) return Verdict::kSnap;
    return Cross(v.at_start.neighbour_normal, n) > kSkipSin ? Verdict::kSkip : Verdict::kAdmit;
  }
  if (v.at_end.free) return Verdict::kAdmit;
  if (!v.at_end.convex) return Verdict::kSnap;
  return Cross(n, v.at_end.neighbour_normal) > kSkipSin ? Verdict::kSkip : Verdict::kAdmit;
}

}  // namespace

bool CollideChainCircle(const ChainSegment& a, const Transform& xa, Vec2 center_b, double radius_b,
                        Manifold* out, double margin) {
  const Vec2 c = InvTransformPoint(xa, center_b);
  const SideView v = MakeSideView(a, c);
  const double along = Dot(c - v.start, v.tangent);
  const Vec2 closest = v.start + Clamp(along, 0.0, v.length) * v.tangent;
  const double distance = Length(c - closest);
  if (distance > radius_b + margin) return false;
  // The face: the circle's centre above its foot on the segment's line.
  Vec2 n = v.normal, surface_a = c - Dot(c - v.start, n) * n;
  double gap = Dot(c - v.start, n);
  std::uint8_t id = 0;
  if ((along < 0.0 || along > v.length) && distance > 0.0) {
    const Vec2 corner_normal = (c - closest) / distance;
    const Verdict verdict = Classify(v, corner_normal);
    if (verdict == Verdict::kSkip) return false;
    if (verdict == Verdict::kAdmit) {
      n = corner_normal, surface_a = closest, gap = distance;
      id = along < 0.0 ? 1 : 2;
    }
  }
  if (gap - radius_b > margin) return false;
  const ContactPoint point{0.5 * (surface_a + (c - radius_b * n)), radius_b - gap, id};
  WriteManifold(xa, n, &point, 1, out);
  return true;
}

namespace {

// The segment as reference face, the polygon's edge most against its normal clipped to it.
int SegmentFaceContact(const SideView& v, const Polygon& p, double margin, Vec2* normal, ContactPoint points[2]) {
  const int incident = IncidentEdge(p, v.normal);
  const ClipEdge inc{p.vertices[incident], p.vertices[(incident + 1) % p.count], p.radius};
  const int count = ClipToReferenceFace({v.start, v.end, 0.0}, v.normal, inc, margin, points);
  for (int i = 0; i < count; ++i) points[i].id = FeatureId(false, 0, incident, points[i].id);
  *normal = v.normal;
  return count;
}

// A polygon face as reference, the segment clipped to it; the normal still points at the polygon.
int PolygonFaceContact(const SideView& v, const Polygon& p, int face, double margin, Vec2* normal,
                       ContactPoint points[2]) {
  const ClipEdge ref{p.vertices[face], p.vertices[(face + 1) % p.count], p.radius};
  const int count = ClipToReferenceFace(ref, p.normals[face], {v.start, v.end, 0.0}, margin, points);
  for (int i = 0; i < count; ++i) points[i].id = FeatureId(true, face, 0, points[i].id);
  *normal = -p.normals[face];
  return count;
}

// Separated cores with an admitted normal n: a polygon face lying along it touches with its
// clipped edge, anything else corner to corner at the closest points.
int AdmittedContact(const SideView& v, const Polygon& p, const DistanceOutput& d, double margin,
                    Vec2* normal, ContactPoint points[2]) {
  int face = 0;
  for (int j = 1; j < p.count; ++j) {
    if (Dot(p.normals[j], d.normal) < Dot(p.normals[face], d.normal)) face = j;
  }
  if (-Dot(p.normals[face], d.normal) >= kAlignedCos) return PolygonFaceContact(v, p, face, margin, normal, points);
  if (d.separation > margin) return 0;
  *normal = d.normal;
  const Vec2 surface_b = d.point_b - p.radius * d.normal;
  points[0] = {0.5 * (d.point_a + surface_b), -d.separation,
               FeatureId(true, d.simplex[0].index_b, d.simplex[0].index_a, 1)};
  return 1;
}

// Overlapping cores: separating axes over the segment's face, its convex neighbours' faces and
// the polygon's faces. A neighbour's face separating best leaves the contact to the neighbour.
int OverlapContact(const SideView& v, const Polygon& p, double margin, Vec2* normal, ContactPoint points[2]) {
  const auto deepest = [&](Vec2 n, Vec2 origin) {
    double s = INFINITY;
    for (int j = 0; j < p.count; ++j) s = std::fmin(s, Dot(n, p.vertices[j] - origin));
    return s;
  };
  const double face_separation = deepest(v.normal, v.start);
  double neighbour_separation = -INFINITY;
  if (v.at_start.convex) neighbour_separation = deepest(v.at_start.neighbour_normal, v.start);
  if (v.at_end.convex) neighbour_separation = std::fmax(neighbour_separation, deepest(v.at_end.neighbour_normal, v.end));
  int face = 0;
  double polygon_separation = -INFINITY;
  for (int j = 0; j < p.count; ++j) {
    const double s = std::fmin(Dot(p.normals[j], v.start - p.vertices[j]), Dot(p.normals[j], v.end - p.vertices[j]));
    if (s > polygon_separation) polygon_separation = s, face = j;
  }
  const double edge_separation = std::fmax(face_separation, neighbour_separation);
  if (polygon_separation > edge_separation + kFaceTolerance) {
    const Verdict verdict = Classify(v, -p.normals[face]);
    if (verdict == Verdict::kSkip) return 0;
    if (verdict == Verdict::kAdmit) return PolygonFaceContact(v, p, face, margin, normal, points);
  } else if (neighbour_separation > face_separation + kFaceTolerance) {
    return 0;
  }
  return SegmentFaceContact(v, p, margin, normal, points);
}

}  // namespace

bool CollideChainPolygon(const ChainSegment& a, const Transform& xa, const Polygon& b,
                         const Transform& xb, Manifold* out, double margin) {
  const Polygon p = PlacePolygon(b, InvMulTransforms(xa, xb));
  const SideView v = MakeSideView(a, p.centroid);
  const Vec2 segment[2] = {v.start, v.end};
  const DistanceOutput d = ShapeDistance(MakeProxy(segment, 0.0), Transform{}, MakeProxy(p), Transform{});
  if (d.distance > p.radius + margin) return false;
  Vec2 normal;
  ContactPoint points[2];
  int count = 0;
  if (d.distance <= kCoreGapTolerance) {
    count = OverlapContact(v, p, margin, &normal, points);
  } else if (Dot(d.normal, v.normal) >= kAlignedCos) {
    count = SegmentFaceContact(v, p, margin, &normal, points);
  } else {
    const Verdict verdict = Classify(v, d.normal);
    if (verdict == Verdict::kAdmit) count = AdmittedContact(v, p, d, margin, &normal, points);
    if (verdict == Verdict::kSnap) count = SegmentFaceContact(v, p, margin, &normal, points);
  }
  if (count == 0) return false;
  WriteManifold(xa, normal, points, count, out);
  return true;
}

bool CollideChainCapsule(const ChainSegment& a, const Transform& xa, const Capsule& b,
                         const Transform& xb, Manifold* out, double margin) {
  return CollideChainPolygon(a, xa, MakeCapsulePolygon(b), xb, out, margin);
}

}  // namespace engine::geometry
