// What the polygon and chain colliders share: reference-face clipping (the incident edge cut to
// the reference face's extent, one contact point per surviving end; Catto, "Contact Manifolds",
// GDC 2007; Box2D's b2ClipPolygons), the incident edge, feature ids, and the world manifold.
#pragma once

#include <cstdint>

#include "engine/contact.h"
#include "engine/math.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// One side of a contact, as the clipper sees it: an edge of a core and its rounding radius.
struct ClipEdge {
  Vec2 start;
  Vec2 end;
  double radius = 0.0;
};

/// Clips `incident` to the extent of `reference` (whose outward unit normal is `normal`) and
/// writes the surviving points midway between the two rounded surfaces, their depth along the
/// normal (negative for a gap), and as id the incident end they came from (0 = start, 1 = end;
/// the caller adds the feature bits). Points farther apart than `margin` are dropped. Returns
/// how many points it wrote (0 to 2). Any frame, as long as all inputs share it.
int ClipToReferenceFace(const ClipEdge& reference, Vec2 normal, const ClipEdge& incident,
                        double margin, ContactPoint out[2]);

/// Two unit directions whose dot product reaches this are the same up to rounding (within about
/// 1.4e-6 rad). Closest corners lined up with a face normal that exactly are two equal faces
/// stacked end to end, for which clipping gives the two points a stack needs; any visible tilt
/// is a true corner contact, whose normal must follow the corners.
inline constexpr double kAlignedCos = 1.0 - 1e-12;

/// The edge of `incident` whose normal points most against `reference_normal` (ties: the lower).
int IncidentEdge(const Polygon& incident, Vec2 reference_normal);

/// Sets `out` from a contact worked out in `frame`: the normal turned, the points placed.
void WriteManifold(const Transform& frame, Vec2 normal, const ContactPoint* points, int count,
                   Manifold* out);

/// A contact point's id from the features that meet there: whether B holds the reference face,
/// the reference and incident edge indices (their low three bits: an 8-bit id cannot name 64
/// edges, so ids repeat only for features eight edges apart) and the incident end.
constexpr std::uint8_t FeatureId(bool flip, int reference, int incident, int end) {
  return static_cast<std::uint8_t>((flip ? 0x80 : 0) | ((reference & 7) << 4) | ((incident & 7) << 1) |
                                   (end & 1));
}

}  // namespace engine::geometry
