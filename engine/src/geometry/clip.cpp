// Clipping an incident edge against the two side planes of a reference face.
#include "geometry/clip.h"

#include <cmath>

namespace engine::geometry {

int IncidentEdge(const Polygon& incident, Vec2 reference_normal) {
  int edge = 0;
  double most_against = INFINITY;
  for (int i = 0; i < incident.count; ++i) {
    const double d = Dot(incident.normals[i], reference_normal);
    if (d < most_against) most_against = d, edge = i;
  }
  return edge;
}

int ClipToReferenceFace(const ClipEdge& reference, Vec2 normal, const ClipEdge& incident,
                        double margin, ContactPoint out[2]) {
  const Vec2 origin = reference.start;
  const Vec2 along = reference.end - origin;
  const double face_length = Length(along);
  const Vec2 tangent = along / face_length;
  Vec2 ends[2] = {incident.start, incident.end};
  // The incident edge keeps the part with 0 ≤ tangent·(p − origin) ≤ face_length; an end cut
  // off is replaced by the crossing, but keeps its name, so that which end survives a rounding
  // error (two equal faces stacked exactly) never changes a point's id.
  for (int side = 0; side < 2; ++side) {
    const auto inside = [&](Vec2 p) {
      const double s = Dot(tangent, p - origin);
      return side == 0 ? s : face_length - s;
    };
    const double d0 = inside(ends[0]), d1 = inside(ends[1]);
    if (d0 < 0.0 && d1 < 0.0) return 0;
    if (d0 < 0.0) {
      ends[0] = ends[0] + (d0 / (d0 - d1)) * (ends[1] - ends[0]);
    } else if (d1 < 0.0) {
      ends[1] = ends[1] + (d1 / (d1 - d0)) * (ends[0] - ends[1]);
    }
  }
  int count = 0;
  const double radii = reference.radius + incident.radius;
  for (int i = 0; i < 2; ++i) {
    const double core_gap = Dot(normal, ends[i] - origin);
    const double separation = core_gap - radii;
    if (separation > margin) continue;
    // The reference surface is at core_gap − reference.radius behind the incident core along
    // the normal, the incident surface at incident.radius: the point sits halfway between.
    const Vec2 point = ends[i] + (0.5 * (reference.radius - incident.radius - core_gap)) * normal;
    out[count++] = {point, -separation, static_cast<std::uint8_t>(i)};
  }
  return count;
}

void WriteManifold(const Transform& frame, Vec2 normal, const ContactPoint* points, int count,
                   Manifold* out) {
  out->normal = Rotate(frame.rotation, normal);
  out->point_count = count;
  for (int i = 0; i < count; ++i) {
    out->points[i] = {TransformPoint(frame, points[i].point), points[i].depth, points[i].id};
  }
}

}  // namespace engine::geometry
