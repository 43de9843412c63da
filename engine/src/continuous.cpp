// The continuous pass: the first time of impact of each fast body made of parts, over its
// candidate pairs and their pieces.
#include "continuous.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "geometry/time_of_impact.h"
#include "wakefulness.h"

namespace engine::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A body's pieces by their bounding circles in its centre-of-mass frame (a lone circle or box
// is one piece); the GJK proxy is built only for pieces whose swept bounds meet.
struct SweptPiece {
  Vec2 center;
  double reach;
};

std::vector<SweptPiece> PiecesOf(const Bodies& bodies, BodyIndex i) {
  std::vector<SweptPiece> out;
  if (const BodyGeometry* g = bodies.geometries[i].get()) {
    for (const Piece& piece : g->pieces) out.push_back({piece.center, piece.reach});
    return out;
  }
  const Shape& shape = bodies.infos[i].shape;
  out.push_back({{}, shape.type == ShapeType::kCircle ? shape.radius : Length(shape.half_extents)});
  return out;
}

geometry::ShapeProxy ProxyAt(const Bodies& bodies, BodyIndex i, std::size_t piece) {
  if (const BodyGeometry* g = bodies.geometries[i].get()) return ProxyOf(*g, g->pieces[piece]);
  const Shape& shape = bodies.infos[i].shape;
  if (shape.type == ShapeType::kCircle) {
    const Vec2 center[1] = {{0.0, 0.0}};
    return geometry::MakeProxy(center, shape.radius);
  }
  return geometry::MakeProxy(geometry::MakeBox(shape.half_extents.x, shape.half_extents.y));
}

// A body's motion over the part [t0, t1] of the step: its centre along the straight line, its
// angle turning evenly.
struct Pose {
  Vec2 center;
  double angle;
};

Pose PoseAt(const Bodies& bodies, std::span<const double> start_angles, BodyIndex i, double t) {
  const BodyState& s = bodies.states[i];
  return {(1.0 - t) * bodies.start_positions[i] + t * s.position, start_angles[i] + t * (s.angle - start_angles[i])};
}

geometry::Sweep SweepBetween(const Pose& from, const Pose& to) {
  return {{}, from.center, to.center, MakeRot(from.angle), MakeRot(to.angle)};
}

// The box a piece's bounding circle covers over the sweep.
AABB SweptBounds(const geometry::Sweep& sweep, const SweptPiece& piece) {
  const Vec2 p1 = sweep.center1 + Rotate(sweep.rotation1, piece.center);
  const Vec2 p2 = sweep.center2 + Rotate(sweep.rotation2, piece.center);
  const Vec2 r{piece.reach, piece.reach};
  return {Vec2{std::fmin(p1.x, p2.x), std::fmin(p1.y, p2.y)} - r, Vec2{std::fmax(p1.x, p2.x), std::fmax(p1.y, p2.y)} + r};
}

// The fraction of the step at which `fast` first comes within the slop of `other`; 1 if never.
// The step is cut into parts that turn neither body by more than a quarter turn, as the sweep's
// blend of rotations needs (geometry/time_of_impact.h), and swept part by part.
double FirstImpact(const Bodies& bodies, std::span<const double> start_angles, BodyIndex fast, BodyIndex other,
                   const WorldDef& def) {
  const geometry::ToiSettings settings{.target = def.linear_slop, .tolerance = 0.25 * def.linear_slop};
  auto turn = [&](BodyIndex i) { return std::abs(bodies.states[i].angle - start_angles[i]); };
  const int parts = std::max(1, static_cast<int>(std::ceil(std::max(turn(fast), turn(other)) / (0.5 * kPi))));
  const std::vector<SweptPiece> pieces_fast = PiecesOf(bodies, fast);
  const std::vector<SweptPiece> pieces_other = PiecesOf(bodies, other);
  for (int part = 0; part < parts; ++part) {
    const double t0 = static_cast<double>(part) / parts, t1 = static_cast<double>(part + 1) / parts;
    const geometry::Sweep sweep_fast = SweepBetween(PoseAt(bodies, start_angles, fast, t0),
                                                    PoseAt(bodies, start_angles, fast, t1));
    const geometry::Sweep sweep_other = SweepBetween(PoseAt(bodies, start_angles, other, t0),
                                                     PoseAt(bodies, start_angles, other, t1));
    double first = 1.0;
    for (std::size_t i = 0; i < pieces_fast.size(); ++i) {
      const AABB box_a = SweptBounds(sweep_fast, pieces_fast[i]);
      std::optional<geometry::ShapeProxy> proxy_a;
      for (std::size_t j = 0; j < pieces_other.size(); ++j) {
        if (!Overlaps(box_a, SweptBounds(sweep_other, pieces_other[j]))) continue;
        if (!proxy_a) proxy_a = ProxyAt(bodies, fast, i);
        const geometry::ToiOutput toi =
            geometry::TimeOfImpact(*proxy_a, sweep_fast, ProxyAt(bodies, other, j), sweep_other, settings);
        // A pair touching where the part begins is the contact solver's (or was stopped by an
        // earlier part); a hit, or an advancement that ran out of iterations (its fraction is
        // still safe: no touch before it), stops the body there.
        const bool stops = toi.state == geometry::ToiState::kHit || toi.state == geometry::ToiState::kFailed;
        if (stops && toi.fraction < first) first = toi.fraction;
      }
    }
    if (first < 1.0) return t0 + first * (t1 - t0);
  }
  return 1.0;
}

}  // namespace

void SolveContinuous(Bodies& bodies, std::span<const double> start_angles, std::span<const BodyPair> pairs,
                     std::span<const std::uint8_t> awake, std::span<const std::uint8_t> joined,
                     const WorldDef& def) {
  const std::size_t n = bodies.states.size();
  // Which bodies are fast: moved or turned through more than half their thinnest width.
  std::vector<double> first(n, 2.0);  // 2: not a fast body of parts
  bool any = false;
  for (BodyIndex i = 0; i < n; ++i) {
    const BodyGeometry* g = bodies.geometries[i].get();
    const BodyInfo& info = bodies.infos[i];
    if (!g || awake[i] != kAwake || HasInfiniteMass(info) || info.is_sensor || !bodies.enabled[i]) continue;
    if (!joined.empty() && joined[i]) continue;
    const BodyState& s = bodies.states[i];
    const double turn = std::abs(s.angle - start_angles[i]);
    const double motion = Length(s.position - bodies.start_positions[i]) + turn * g->reach;
    if (motion > 0.5 * g->thickness) first[i] = 1.0, any = true;
  }
  if (!any) return;
  auto blocks = [&](BodyIndex fast, BodyIndex other) {
    const BodyInfo& o = bodies.infos[other];
    if (o.is_sensor) return false;
    return HasInfiniteMass(o) || (bodies.infos[fast].bullet && !o.bullet);
  };
  for (const BodyPair& p : pairs) {
    if (first[p.a] <= 1.0 && blocks(p.a, p.b)) first[p.a] = std::min(first[p.a], FirstImpact(bodies, start_angles, p.a, p.b, def));
    if (first[p.b] <= 1.0 && blocks(p.b, p.a)) first[p.b] = std::min(first[p.b], FirstImpact(bodies, start_angles, p.b, p.a, def));
  }
  for (BodyIndex i = 0; i < n; ++i) {
    if (!(first[i] < 1.0)) continue;
    BodyState& s = bodies.states[i];
    const double t = first[i];
    s.position = (1.0 - t) * bodies.start_positions[i] + t * s.position;
    s.angle = start_angles[i] + t * (s.angle - start_angles[i]);
  }
}

}  // namespace engine::detail
