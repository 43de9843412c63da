// A body made of parts (BodyDef::parts) as the engine collides it: convex pieces in the frame of
// its centre of mass, with what the broad phase, the speculative margins and the pair budget
// need to know about them. Built once, when the body is made; never changed. Internal.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/body.h"
#include "engine/math.h"
#include "engine/shape.h"
#include "geometry/chain.h"
#include "geometry/gjk.h"
#include "geometry/mass.h"
#include "geometry/polygon.h"
#include "geometry/transform.h"

namespace engine::detail {

/// One convex piece, in the centre-of-mass frame.
struct Piece {
  enum class Kind : std::uint8_t { kCircle, kPolygon, kCapsule, kSegment };
  Kind kind = Kind::kCircle;
  std::uint32_t index = 0;  ///< into BodyGeometry::polygons (polygons, capsules) or ::segments
  Vec2 center;              ///< a circle's centre; else the centre of the bounding circle
  double radius = 0.0;      ///< a circle's or capsule's radius, a polygon's rounding
  double reach = 0.0;       ///< the bounding circle's radius about `center`
  double friction = 0.0;
  double restitution = 0.0;
};

struct BodyGeometry {
  std::vector<ShapePart> parts;            ///< as given
  /// The body's own material, which parts without their own take (kept for snapshots).
  double density = 0.0;
  double friction = 0.0;
  double restitution = 0.0;
  std::vector<Piece> pieces;
  std::vector<geometry::Polygon> polygons;  ///< polygon and capsule pieces (a capsule has two vertices)
  std::vector<geometry::ChainSegment> segments;
  std::vector<ConvexPiece> public_pieces;  ///< the pieces in the body's frame (World::Pieces)
  double mass = 0.0;       ///< kg, from the parts' densities (0 for segments only)
  double inertia = 0.0;    ///< kg·m² about the centre of mass
  Vec2 local_center;       ///< the centre of mass in the body's frame
  double reach = 0.0;      ///< the farthest surface point from the centre of mass
  double thickness = 0.0;  ///< the thinnest piece's smallest width
  Vec2 half_size;          ///< half the sides of the pieces' box in the centre-of-mass frame
};

/// The geometry of a body made of `def.parts` (each part valid: CheckShapePart), its materials
/// defaulting to the body's.
std::shared_ptr<const BodyGeometry> MakeBodyGeometry(const BodyDef& def);

/// Where the body's centre-of-mass frame stands.
inline geometry::Transform FrameOf(const BodyState& state) { return {state.position, MakeRot(state.angle)}; }

/// The world box around a body of pieces.
AABB PiecesBounds(const BodyGeometry& geometry, const BodyState& state);

/// The origin of the body's frame, from its centre of mass.
inline Vec2 OriginOf(const BodyGeometry& geometry, const BodyState& state) {
  return state.position - Rotate(MakeRot(state.angle), geometry.local_center);
}

/// A piece as a GJK proxy, in the centre-of-mass frame.
geometry::ShapeProxy ProxyOf(const BodyGeometry& geometry, const Piece& piece);

/// The width of the body across the direction `along` (a unit vector), for drag.
double PiecesWidth(const BodyGeometry& geometry, const BodyState& state, Vec2 along);

}  // namespace engine::detail
