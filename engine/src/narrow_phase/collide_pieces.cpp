// Pieces against pieces: a bounding-circle test, then the collider for the two kinds, called
// with the kinds in the order it takes them and its normal turned back to point from A to B.
#include "narrow_phase/collide_pieces.h"

#include <cmath>
#include <optional>

#include "geometry/manifold.h"
#include "narrow_phase/collide.h"

namespace engine::detail {

namespace {

using geometry::Polygon;
using geometry::Transform;
using Kind = Piece::Kind;

// One piece, wherever it is kept.
struct PieceRef {
  Kind kind;
  Vec2 center;
  double radius;
  double reach;
  const Polygon* polygon;
  const geometry::ChainSegment* segment;
  double friction;
  double restitution;
};

// The pieces of a body: its geometry's, or its own circle or box as one piece (the box's
// polygon kept in `box`).
class Pieces {
 public:
  explicit Pieces(const PieceBody& body) : body_(body) {
    if (body.geometry) return;
    const Shape& shape = body.info.shape;
    if (shape.type == ShapeType::kBox) box_.emplace(geometry::MakeBox(shape.half_extents.x, shape.half_extents.y));
  }
  std::size_t Count() const { return body_.geometry ? body_.geometry->pieces.size() : 1; }
  PieceRef operator[](std::size_t i) const {
    if (!body_.geometry) {
      const Shape& shape = body_.info.shape;
      if (shape.type == ShapeType::kCircle) {
        return {Kind::kCircle, {}, shape.radius, shape.radius, nullptr, nullptr, body_.info.friction,
                body_.info.restitution};
      }
      return {Kind::kPolygon, {}, 0.0, Length(shape.half_extents), &*box_, nullptr, body_.info.friction,
              body_.info.restitution};
    }
    const BodyGeometry& g = *body_.geometry;
    const Piece& p = g.pieces[i];
    const bool polygon = p.kind == Kind::kPolygon || p.kind == Kind::kCapsule;
    return {p.kind,
            p.center,
            p.radius,
            p.reach,
            polygon ? &g.polygons[p.index] : nullptr,
            p.kind == Kind::kSegment ? &g.segments[p.index] : nullptr,
            p.friction,
            p.restitution};
  }

 private:
  const PieceBody& body_;
  std::optional<Polygon> box_;  ///< a lone box's outline (2 KB: made only for a box)
};

geometry::Capsule CapsuleOf(const Polygon& p) { return {p.vertices[0], p.vertices[1], p.radius}; }

bool Flipped(bool touching, Manifold* m) {
  m->normal = -m->normal;
  return touching;
}

// The manifold of two pieces (normal from A to B); false when farther apart than `margin`.
bool CollideTwo(const PieceRef& a, const Transform& xa, const PieceRef& b, const Transform& xb, double margin,
                Manifold* m) {
  using namespace geometry;
  if (b.kind == Kind::kSegment) {
    if (a.kind == Kind::kSegment) return false;  // both static: nothing to solve
    return Flipped(CollideTwo(b, xb, a, xa, margin, m), m);
  }
  switch (a.kind) {
    case Kind::kSegment:
      if (b.kind == Kind::kCircle) {
        return CollideChainCircle(*a.segment, xa, TransformPoint(xb, b.center), b.radius, m, margin);
      }
      if (b.kind == Kind::kCapsule) return CollideChainCapsule(*a.segment, xa, CapsuleOf(*b.polygon), xb, m, margin);
      return CollideChainPolygon(*a.segment, xa, *b.polygon, xb, m, margin);
    case Kind::kCircle:
      if (b.kind == Kind::kCircle) {
        return CollideCircles(TransformPoint(xa, a.center), a.radius, TransformPoint(xb, b.center), b.radius, m,
                              margin);
      }
      return CollideCirclePolygon(TransformPoint(xa, a.center), a.radius, *b.polygon, xb, m, margin);
    case Kind::kCapsule:
      if (b.kind == Kind::kCircle) return Flipped(CollideTwo(b, xb, a, xa, margin, m), m);
      if (b.kind == Kind::kCapsule) return CollideCapsules(CapsuleOf(*a.polygon), xa, CapsuleOf(*b.polygon), xb, m, margin);
      return CollideCapsulePolygon(CapsuleOf(*a.polygon), xa, *b.polygon, xb, m, margin);
    case Kind::kPolygon:
      if (b.kind == Kind::kPolygon) return CollidePolygons(*a.polygon, xa, *b.polygon, xb, m, margin);
      return Flipped(CollideTwo(b, xb, a, xa, margin, m), m);
  }
  return false;
}

// Calls `each(i, j, manifold)` for every pair of pieces that collide within `margin`.
template <typename Each>
void ForEachTouchingPair(const PieceBody& a, const PieceBody& b, double margin, Each each) {
  const Pieces pa(a), pb(b);
  const Transform xa = FrameOf(a.state), xb = FrameOf(b.state);
  for (std::size_t i = 0; i < pa.Count(); ++i) {
    const PieceRef piece_a = pa[i];
    const Vec2 center_a = geometry::TransformPoint(xa, piece_a.center);
    for (std::size_t j = 0; j < pb.Count(); ++j) {
      const PieceRef piece_b = pb[j];
      const double reach = piece_a.reach + piece_b.reach + margin;
      if (LengthSquared(geometry::TransformPoint(xb, piece_b.center) - center_a) > reach * reach) continue;
      Manifold m;
      if (!CollideTwo(piece_a, xa, piece_b, xb, margin, &m)) continue;
      if (!each(i, j, piece_a, piece_b, m)) return;
    }
  }
}

}  // namespace

void CollidePieces(const PieceBody& a, const PieceBody& b, double margin, std::vector<Contact>* out) {
  ForEachTouchingPair(a, b, margin, [&](std::size_t i, std::size_t j, const PieceRef& pa, const PieceRef& pb,
                                        const Manifold& m) {
    const Contact c{.a = a.index,
                    .b = b.index,
                    .piece_a = static_cast<std::uint16_t>(i),
                    .piece_b = static_cast<std::uint16_t>(j),
                    .strike_first_touch = true,
                    .manifold = m,
                    .restitution = std::max(pa.restitution, pb.restitution),
                    .friction = std::sqrt(pa.friction * pb.friction)};
    out->push_back(c);
    return true;
  });
}

bool PiecesOverlap(const PieceBody& a, const PieceBody& b) {
  bool overlap = false;
  ForEachTouchingPair(a, b, 0.0, [&](std::size_t, std::size_t, const PieceRef&, const PieceRef&, const Manifold& m) {
    for (int k = 0; k < m.point_count; ++k) overlap = overlap || m.points[k].depth >= 0.0;
    return !overlap;
  });
  return overlap;
}

}  // namespace engine::detail
