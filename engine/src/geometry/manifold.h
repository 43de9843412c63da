// Contact manifolds for convex polygons (rounded or not), capsules, circles and chain segments,
// with the narrow phase's margin convention (narrow_phase/collide.h): each function returns
// false and leaves `out` alone when the shapes are farther apart than `margin`; touching shapes
// give depth 0, shapes up to `margin` apart a speculative point with negative depth. Shapes are
// given in their own frames and placed by a Transform; points come out in the world, the
// normal from A to B, at most two points, ids stable while the same features touch.
#pragma once

#include "engine/contact.h"
#include "geometry/chain.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::geometry {

/// Linear slop of the default WorldDef: the scale of the tolerances below.
inline constexpr double kLinearSlop = 0.005;
/// B's face replaces A's as the reference only when it separates the shapes by this much more,
/// so the choice does not flicker between nearly equal faces (the oriented-box collider's rule).
inline constexpr double kFaceTolerance = 0.1 * kLinearSlop;
/// Cores farther apart than this may touch corner to corner (rounded shapes, speculative
/// contacts), which needs the closest features rather than a face.
inline constexpr double kCoreGapTolerance = 0.1 * kLinearSlop;

/// Separating axes over both polygons' edge normals, then the incident edge clipped against the
/// reference face (up to two points); for separated cores whose closest features are two
/// corners, one point along the line between them. Capsules are two-vertex polygons.
bool CollidePolygons(const Polygon& a, const Transform& xa, const Polygon& b, const Transform& xb,
                     Manifold* out, double margin = 0.0);

/// A circle (centre in the world) against a polygon: the face it is farthest in front of, or the
/// nearest corner when its centre lies beyond the face's ends.
bool CollideCirclePolygon(Vec2 center_a, double radius_a, const Polygon& b, const Transform& xb,
                          Manifold* out, double margin = 0.0);

bool CollideCapsules(const Capsule& a, const Transform& xa, const Capsule& b, const Transform& xb,
                     Manifold* out, double margin = 0.0);
bool CollideCapsulePolygon(const Capsule& a, const Transform& xa, const Polygon& b,
                           const Transform& xb, Manifold* out, double margin = 0.0);

/// A chain segment (A, two-sided) against a shape. The side is the one of the polyline the
/// shape's centre lies on (the ghost vertices settle it beyond the segment's ends). A normal
/// that the neighbouring segment's face or a flat or concave join should give is snapped to
/// this segment's face or left to the neighbour, so a shape sliding along a straight run gets
/// the face normal at every join (Catto, "Ghost vertices", 2010; Box2D v3's chain colliders).
bool CollideChainCircle(const ChainSegment& a, const Transform& xa, Vec2 center_b, double radius_b,
                        Manifold* out, double margin = 0.0);
bool CollideChainPolygon(const ChainSegment& a, const Transform& xa, const Polygon& b,
                         const Transform& xb, Manifold* out, double margin = 0.0);
bool CollideChainCapsule(const ChainSegment& a, const Transform& xa, const Capsule& b,
                         const Transform& xb, Manifold* out, double margin = 0.0);

}  // namespace engine::geometry
