// The narrow phase for bodies made of parts: every pair of convex pieces whose bounding circles
// come within the margin, one contact each, the shape pair choosing the collider. A lone circle
// or box meeting such a body takes part as one piece. Internal.
#pragma once

#include <vector>

#include "body_geometry.h"
#include "engine/body.h"
#include "engine/contact.h"

namespace engine::detail {

/// A body as the pieces' narrow phase sees it.
struct PieceBody {
  BodyIndex index;
  const BodyInfo& info;
  const BodyState& state;
  const BodyGeometry* geometry;  ///< null for a lone circle or box
};

/// Appends the contacts between `a` and `b` (a below b, at least one made of parts) in piece
/// order, each with its pieces' material: restitution the larger, friction the geometric mean.
void CollidePieces(const PieceBody& a, const PieceBody& b, double margin, std::vector<Contact>* out);

/// Whether some piece of `a` overlaps or touches some piece of `b`.
bool PiecesOverlap(const PieceBody& a, const PieceBody& b);

}  // namespace engine::detail
