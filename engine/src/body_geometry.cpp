// Building a body's pieces from its parts: outlines normalised and split into convex pieces,
// everything placed in the body's frame, the masses summed, then the pieces moved into the frame
// of the centre of mass, where the step works.
#include "body_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/decompose.h"
#include "geometry/outline.h"

namespace engine::detail {

namespace {

using geometry::MassProperties;
using geometry::Polygon;
using geometry::Transform;

Transform PlacementOf(const ShapePart& part) { return {part.offset, MakeRot(part.angle)}; }

std::vector<Vec2> Placed(const Transform& xf, std::span<const Vec2> points) {
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const Vec2 p : points) out.push_back(geometry::TransformPoint(xf, p));
  return out;
}

// The convex outlines of a part, in the body's frame (a circle has none).
std::vector<std::vector<Vec2>> ConvexOutlines(const ShapePart& part) {
  const Transform xf = PlacementOf(part);
  switch (part.type) {
    case ShapeType::kBox: {
      const Vec2 h = part.half_extents;
      const Vec2 corners[4] = {{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}};
      return {Placed(xf, corners)};
    }
    case ShapeType::kCapsule: {
      const Vec2 centers[2] = {{-0.5 * part.length, 0.0}, {0.5 * part.length, 0.0}};
      return {Placed(xf, centers)};
    }
    case ShapeType::kPolygon: {
      // Placed first, so a part turned by its angle is split in the body's frame.
      const std::vector<Vec2> placed = Placed(xf, part.points);
      const geometry::Outline outline = geometry::NormaliseOutline(placed);
      std::vector<std::vector<Vec2>> out;
      for (const geometry::Outline& piece : geometry::DecomposeConvex(outline)) {
        out.emplace_back(piece.View().begin(), piece.View().end());
      }
      return out;
    }
    default:
      return {};
  }
}

double Density(const ShapePart& part, const BodyDef& def) { return part.density.value_or(def.density); }

// The smallest width of a convex piece: over its edge normals, how far it spans (plus rounding).
double Thickness(const Polygon& p) {
  if (p.count == 2) return 2.0 * p.radius;
  double thinnest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < p.count; ++i) {
    double deepest = 0.0;
    for (int j = 0; j < p.count; ++j) deepest = std::max(deepest, Dot(p.normals[i], p.vertices[i] - p.vertices[j]));
    thinnest = std::min(thinnest, deepest);
  }
  return thinnest + 2.0 * p.radius;
}

void Grow(AABB* box, Vec2 p, double r) {
  box->lower = {std::fmin(box->lower.x, p.x - r), std::fmin(box->lower.y, p.y - r)};
  box->upper = {std::fmax(box->upper.x, p.x + r), std::fmax(box->upper.y, p.y + r)};
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

std::shared_ptr<const BodyGeometry> MakeBodyGeometry(const BodyDef& def) {
  auto g = std::make_shared<BodyGeometry>();
  g->parts = def.parts;
  g->density = def.density;
  g->friction = def.friction;
  g->restitution = def.restitution;
  // First in the body's frame: pieces, and the mass of each.
  std::vector<MassProperties> masses;
  for (std::size_t part_index = 0; part_index < def.parts.size(); ++part_index) {
    const ShapePart& part = def.parts[part_index];
    const double friction = part.friction.value_or(def.friction);
    const double restitution = part.restitution.value_or(def.restitution);
    const int part_number = static_cast<int>(part_index);
    if (part.type == ShapeType::kCircle) {
      g->pieces.push_back({Piece::Kind::kCircle, 0, part.offset, part.radius, part.radius, friction, restitution});
      g->public_pieces.push_back({ShapeType::kCircle, {part.offset}, part.radius, part_number});
      masses.push_back(geometry::CircleMass(part.offset, part.radius, Density(part, def)));
      continue;
    }
    if (part.type == ShapeType::kSegments) {
      const std::vector<Vec2> placed = Placed(PlacementOf(part), part.points);
      for (const geometry::ChainSegment& s : geometry::MakeChain(placed, part.loop)) {
        g->pieces.push_back({Piece::Kind::kSegment, static_cast<std::uint32_t>(g->segments.size()), {}, 0.0, 0.0,
                             friction, restitution});
        g->segments.push_back(s);
        g->public_pieces.push_back({ShapeType::kSegments, {s.point1, s.point2}, 0.0, part_number});
      }
      continue;
    }
    const double radius = part.type == ShapeType::kBox ? 0.0 : part.radius;
    const bool capsule = part.type == ShapeType::kCapsule;
    std::vector<MassProperties> part_masses;
    for (const std::vector<Vec2>& outline : ConvexOutlines(part)) {
      const Polygon polygon = geometry::MakePolygon(outline, radius);
      g->pieces.push_back({capsule ? Piece::Kind::kCapsule : Piece::Kind::kPolygon,
                           static_cast<std::uint32_t>(g->polygons.size()), {}, radius, 0.0, friction, restitution});
      g->polygons.push_back(polygon);
      g->public_pieces.push_back({capsule ? ShapeType::kCapsule : ShapeType::kPolygon, outline, radius, part_number});
      part_masses.push_back(geometry::PolygonMass(polygon, Density(part, def)));
    }
    // A rounded concave polygon's pieces overlap by their rounding along the cuts: the mass
    // counts that skin twice (a sliver, of width 2·radius along each cut).
    masses.push_back(geometry::CombineMasses(part_masses));
  }
  const MassProperties total = geometry::CombineMasses(masses);
  g->local_center = total.mass > 0.0 ? total.center : Vec2{};
  const double scale = def.mass > 0.0 && total.mass > 0.0 ? def.mass / total.mass : 1.0;
  g->mass = scale * total.mass;
  g->inertia = scale * total.inertia;

  // Then into the frame of the centre of mass, with the bounds each piece needs.
  const Vec2 shift = -g->local_center;
  AABB box{{kInfinity, kInfinity}, {-kInfinity, -kInfinity}};
  g->thickness = kInfinity;
  for (Piece& piece : g->pieces) {
    switch (piece.kind) {
      case Piece::Kind::kCircle:
        piece.center = piece.center + shift;
        Grow(&box, piece.center, piece.radius);
        g->thickness = std::min(g->thickness, 2.0 * piece.radius);
        break;
      case Piece::Kind::kSegment: {
        geometry::ChainSegment& s = g->segments[piece.index];
        s = {s.ghost1 + shift, s.point1 + shift, s.point2 + shift, s.ghost2 + shift};
        piece.center = 0.5 * (s.point1 + s.point2);
        piece.reach = 0.5 * Length(s.point2 - s.point1);
        Grow(&box, s.point1, 0.0);
        Grow(&box, s.point2, 0.0);
        break;
      }
      default: {
        Polygon& p = g->polygons[piece.index];
        std::vector<Vec2> moved(p.vertices, p.vertices + p.count);
        for (Vec2& v : moved) v = v + shift;
        p = geometry::MakePolygon(moved, p.radius);
        piece.center = p.centroid;
        double farthest = 0.0;
        for (const Vec2 v : moved) {
          farthest = std::max(farthest, Length(v - p.centroid));
          Grow(&box, v, p.radius);
        }
        piece.reach = farthest + p.radius;
        g->thickness = std::min(g->thickness, Thickness(p));
      }
    }
  }
  g->half_size = 0.5 * (box.upper - box.lower);
  for (const Piece& piece : g->pieces) g->reach = std::max(g->reach, Length(piece.center) + piece.reach);
  if (!(g->thickness < kInfinity)) g->thickness = 0.0;  // segments only
  return g;
}

AABB PiecesBounds(const BodyGeometry& geometry, const BodyState& state) {
  const Transform xf = FrameOf(state);
  AABB box{{kInfinity, kInfinity}, {-kInfinity, -kInfinity}};
  for (const Piece& piece : geometry.pieces) {
    switch (piece.kind) {
      case Piece::Kind::kCircle:
        Grow(&box, geometry::TransformPoint(xf, piece.center), piece.radius);
        break;
      case Piece::Kind::kSegment: {
        const geometry::ChainSegment& s = geometry.segments[piece.index];
        Grow(&box, geometry::TransformPoint(xf, s.point1), 0.0);
        Grow(&box, geometry::TransformPoint(xf, s.point2), 0.0);
        break;
      }
      default: {
        const Polygon& p = geometry.polygons[piece.index];
        for (int i = 0; i < p.count; ++i) Grow(&box, geometry::TransformPoint(xf, p.vertices[i]), p.radius);
      }
    }
  }
  return box;
}

geometry::ShapeProxy ProxyOf(const BodyGeometry& g, const Piece& piece) {
  switch (piece.kind) {
    case Piece::Kind::kCircle: {
      const Vec2 center[1] = {piece.center};
      return geometry::MakeProxy(center, piece.radius);
    }
    case Piece::Kind::kSegment: {
      const geometry::ChainSegment& s = g.segments[piece.index];
      const Vec2 ends[2] = {s.point1, s.point2};
      return geometry::MakeProxy(ends, 0.0);
    }
    default:
      return geometry::MakeProxy(g.polygons[piece.index]);
  }
}

double PiecesWidth(const BodyGeometry& geometry, const BodyState& state, Vec2 along) {
  // Project every piece on the line across `along`, in the body's frame.
  const Vec2 across = InvRotate(MakeRot(state.angle), LeftPerp(along));
  double lowest = kInfinity, highest = -kInfinity;
  auto take = [&](Vec2 p, double r) {
    const double d = Dot(across, p);
    lowest = std::min(lowest, d - r);
    highest = std::max(highest, d + r);
  };
  for (const Piece& piece : geometry.pieces) {
    if (piece.kind == Piece::Kind::kCircle) {
      take(piece.center, piece.radius);
    } else if (piece.kind == Piece::Kind::kSegment) {
      take(geometry.segments[piece.index].point1, 0.0);
      take(geometry.segments[piece.index].point2, 0.0);
    } else {
      const Polygon& p = geometry.polygons[piece.index];
      for (int i = 0; i < p.count; ++i) take(p.vertices[i], p.radius);
    }
  }
  return highest > lowest ? highest - lowest : 0.0;
}

}  // namespace engine::detail
