// Polygon manifolds in the manner of Box2D v3's b2CollidePolygons (Catto, "Contact Manifolds",
// GDC 2007): separating axes in A's frame, the reference face the one that separates most
// (B's only when clearly better), the incident edge the one most against its normal, clipped;
// rounded and speculative contacts between two corners by the closest points of the two edges.
#include <cmath>

#include "geometry/clip.h"
#include "geometry/manifold.h"
#include "geometry/segment_distance.h"

namespace engine::geometry {

namespace {

// The face of `reference` that `other` lies farthest in front of, by its deepest vertex
// (negative when overlapping). Ties keep the lower face index.
//
// The deepest vertex under face i is other's support point against normal i. As i goes round,
// the normal turns counter-clockwise and the support point moves forward round `other`, so a
// face's search can walk on from the last face's support (rotating calipers): O(n + m) rather
// than O(n·m), which matters at 64 vertices. After a sharp turn (over 60°, a box's corners, a
// capsule's half turn) the walk would start near the far side, where a rounding error can stop
// it at once, so those faces scan every vertex.
double MaxSeparation(const Polygon& reference, const Polygon& other, int* face) {
  const auto depth = [&](int i, int j) {
    return Dot(reference.normals[i], other.vertices[j] - reference.vertices[i]);
  };
  constexpr double kWalkCos = 0.5;
  int deepest = 0;
  double best = -INFINITY;
  for (int i = 0; i < reference.count; ++i) {
    const Vec2 previous = reference.normals[(i + reference.count - 1) % reference.count];
    if (i == 0 || Dot(previous, reference.normals[i]) < kWalkCos) {
      deepest = 0;
      for (int j = 1; j < other.count; ++j) {
        if (depth(i, j) < depth(i, deepest)) deepest = j;
      }
    }
    for (int steps = 1; steps < other.count; ++steps) {
      const int next = (deepest + 1) % other.count;
      if (!(depth(i, next) < depth(i, deepest))) break;
      deepest = next;
    }
    const double separation = depth(i, deepest);
    if (separation > best) best = separation, *face = i;
  }
  return best;
}

ClipEdge EdgeOf(const Polygon& p, int edge) {
  return {p.vertices[edge], p.vertices[(edge + 1) % p.count], p.radius};
}

struct FacePair {
  const Polygon* reference;
  const Polygon* incident;
  int reference_edge;
  int incident_edge;
  bool flip;  // B holds the reference face
};

// One point between the closest corners of the two edges, along the line joining them.
bool CornerContact(const FacePair& f, const SegmentDistanceResult& closest, double margin,
                   Vec2* normal, ContactPoint* point) {
  const double distance = std::sqrt(closest.distance_squared);
  const double r_ref = f.reference->radius, r_inc = f.incident->radius;
  if (distance - r_ref - r_inc > margin) return false;
  const Vec2 n = (closest.closest2 - closest.closest1) / distance;
  const Vec2 surface_ref = closest.closest1 + r_ref * n, surface_inc = closest.closest2 - r_inc * n;
  const int ref_corner = (f.reference_edge + (closest.fraction1 == 1.0)) % f.reference->count;
  const int inc_corner = (f.incident_edge + (closest.fraction2 == 1.0)) % f.incident->count;
  *normal = n;
  *point = {0.5 * (surface_ref + surface_inc), r_ref + r_inc - distance,
            FeatureId(f.flip, ref_corner, inc_corner, 0)};
  return true;
}

// One point at the incident edge's deeper end, unclipped, for overlapping cores.
int DeeperEndContact(const ClipEdge& ref, Vec2 n, const ClipEdge& inc, const FacePair& f, ContactPoint* point) {
  const double gap_start = Dot(n, inc.start - ref.start), gap_end = Dot(n, inc.end - ref.start);
  const int end = gap_end < gap_start ? 1 : 0;
  const Vec2 c = end == 1 ? inc.end : inc.start;
  const double gap = end == 1 ? gap_end : gap_start;
  *point = {c + (0.5 * (ref.radius - inc.radius - gap)) * n, ref.radius + inc.radius - gap,
            FeatureId(f.flip, f.reference_edge, f.incident_edge, end)};
  return 1;
}

// The contact between the reference face and the incident edge, in the reference's frame, with
// the normal pointing from the reference to the incident polygon. Returns the point count.
int FaceContact(const FacePair& f, bool cores_apart, double margin, Vec2* normal, ContactPoint points[2]) {
  const ClipEdge ref = EdgeOf(*f.reference, f.reference_edge);
  const ClipEdge inc = EdgeOf(*f.incident, f.incident_edge);
  const Vec2 face_normal = f.reference->normals[f.reference_edge];
  SegmentDistanceResult closest;
  bool at_corners = false;
  if (cores_apart) {
    closest = SegmentDistance(ref.start, ref.end, inc.start, inc.end);
    const auto at_end = [](double fraction) { return fraction == 0.0 || fraction == 1.0; };
    at_corners = at_end(closest.fraction1) && at_end(closest.fraction2);
    const double along_normal = Dot(closest.closest2 - closest.closest1, face_normal);
    if (at_corners && along_normal < kAlignedCos * std::sqrt(closest.distance_squared)) {
      return CornerContact(f, closest, margin, normal, points) ? 1 : 0;
    }
  }
  const int count = ClipToReferenceFace(ref, face_normal, inc, margin, points);
  for (int i = 0; i < count; ++i) {
    points[i].id = FeatureId(f.flip, f.reference_edge, f.incident_edge, points[i].id);
  }
  *normal = face_normal;
  // Lined-up corners that rounding clipped away still touch corner to corner.
  if (count == 0 && at_corners) return CornerContact(f, closest, margin, normal, points) ? 1 : 0;
  // Deep in, a short reference face (a 64-gon's) may lie wholly beside the incident edge: the
  // incident edge's deeper end still says how far to push along the face normal.
  if (count == 0 && !cores_apart) return DeeperEndContact(ref, face_normal, inc, f, points);
  return count;
}

}  // namespace

bool CollidePolygons(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                     Manifold* out, double margin) {
  const Polygon local_b = PlacePolygon(b, InvMulTransforms(xa, xb));
  const double reach = margin + a.radius + b.radius;
  int edge_a = 0, edge_b = 0;
  const double separation_a = MaxSeparation(a, local_b, &edge_a);
  if (separation_a > reach) return false;
  const double separation_b = MaxSeparation(local_b, a, &edge_b);
  if (separation_b > reach) return false;

  const bool flip = separation_b > separation_a + kFaceTolerance;
  const FacePair f = flip ? FacePair{&local_b, &a, edge_b, IncidentEdge(a, local_b.normals[edge_b]), true}
                          : FacePair{&a, &local_b, edge_a, IncidentEdge(local_b, a.normals[edge_a]), false};
  const bool cores_apart = std::fmax(separation_a, separation_b) > kCoreGapTolerance;
  Vec2 normal;
  ContactPoint points[2];
  const int count = FaceContact(f, cores_apart, margin, &normal, points);
  if (count == 0) return false;
  WriteManifold(xa, flip ? -normal : normal, points, count, out);
  return true;
}

bool CollideCirclePolygon(Vec2 center_a, double radius_a, const Polygon& b, const Transform& xb,
                          Manifold* out, double margin) {
  const Vec2 c = InvTransformPoint(xb, center_a);
  int face = 0;
  double separation = -INFINITY;
  for (int i = 0; i < b.count; ++i) {
    const double s = Dot(b.normals[i], c - b.vertices[i]);
    if (s > separation) separation = s, face = i;
  }
  const double radii = radius_a + b.radius;
  if (separation > radii + margin) return false;
  const Vec2 v1 = b.vertices[face], v2 = b.vertices[(face + 1) % b.count];
  // Outside the core and beyond an end of the face, the corner is nearest.
  Vec2 corner = v1;
  bool at_corner = separation > 0.0 && Dot(c - v1, v2 - v1) < 0.0;
  if (!at_corner && separation > 0.0 && Dot(c - v2, v1 - v2) < 0.0) corner = v2, at_corner = true;
  Vec2 n = b.normals[face];  // from the polygon to the circle
  double gap = separation;
  if (at_corner) {
    const double distance = Length(c - corner);
    if (distance - radii > margin) return false;
    // On the corner itself (rounding put it a hair outside the face) the face's normal serves.
    if (distance > 0.0) gap = distance, n = (c - corner) / distance;
  }
  const Vec2 surface_b = c - gap * n + b.radius * n, surface_a = c - radius_a * n;
  const auto id = static_cast<std::uint8_t>(at_corner ? 0x40 | (corner == v1 ? face : (face + 1) % b.count) : face);
  const ContactPoint point{0.5 * (surface_a + surface_b), radii - gap, id};
  WriteManifold(xb, -n, &point, 1, out);
  return true;
}

bool CollideCapsules(const Capsule& a, const Transform& xa, const Capsule& b, const Transform& xb,
                     Manifold* out, double margin) {
  return CollidePolygons(MakeCapsulePolygon(a), xa, MakeCapsulePolygon(b), xb, out, margin);
}

bool CollideCapsulePolygon(const Capsule& a, const Transform& xa, const Polygon& b,
                           const Transform& xb, Manifold* out, double margin) {
  return CollidePolygons(MakeCapsulePolygon(a), xa, b, xb, out, margin);
}

}  // namespace engine::geometry
