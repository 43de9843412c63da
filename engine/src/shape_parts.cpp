// CheckShapePart: a part checked as CreateBody requires it, each problem named by the scene
// format's key, so a loader can report it instead of the engine stopping.
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/shape.h"
#include "geometry/chain.h"
#include "geometry/decompose.h"
#include "geometry/outline.h"
#include "geometry/transform.h"

namespace engine {

namespace {

// The most pieces a body can have: Contact::piece_a names one in 16 bits.
constexpr std::size_t kMaxPieces = 65535;

std::optional<PartProblem> Problem(std::string key, std::string message) {
  return PartProblem{std::move(key), std::move(message)};
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

std::string PointText(int index) { return "point " + std::to_string(index); }

std::optional<PartProblem> CheckPolygon(const ShapePart& part) {
  if (!(std::isfinite(part.radius) && part.radius >= 0.0)) return Problem("radius", "must be finite and >= 0");
  const geometry::OutlineCheck check = geometry::CheckOutline(part.points);
  if (check.problem != geometry::OutlineProblem::kNone) {
    std::string message = geometry::Describe(check.problem);
    if (check.problem == geometry::OutlineProblem::kNotFinite) message += " (" + PointText(check.first) + ")";
    if (check.problem == geometry::OutlineProblem::kDuplicatePoint) {
      message += " (points " + std::to_string(check.first) + " and " + std::to_string(check.second) + ")";
    }
    if (check.problem == geometry::OutlineProblem::kSelfCrossing) {
      message += " (edges " + std::to_string(check.first) + " and " + std::to_string(check.second) + ")";
    }
    return Problem("vertices", message);
  }
  // The pieces are cut where the part stands in the body; rounding there must leave an ear.
  std::vector<Vec2> placed;
  const geometry::Transform xf{part.offset, MakeRot(part.angle)};
  for (const Vec2 p : part.points) placed.push_back(geometry::TransformPoint(xf, p));
  if (geometry::CheckOutline(placed).problem != geometry::OutlineProblem::kNone) {
    return Problem("vertices", "is too thin to split into convex pieces");
  }
  // A corner a rounding error away from an edge can leave an ear of no area, or none at all.
  const std::vector<geometry::Outline> pieces = geometry::DecomposeConvex(geometry::NormaliseOutline(placed));
  const bool degenerate = std::any_of(pieces.begin(), pieces.end(), [](const geometry::Outline& piece) {
    return piece.count < 3 || !(geometry::TwiceSignedArea(piece.View()) > 0.0);
  });
  if (pieces.empty() || degenerate) return Problem("vertices", "is too thin to split into convex pieces");
  return std::nullopt;
}

std::optional<PartProblem> CheckSegments(const ShapePart& part, bool is_static) {
  if (!is_static) return Problem("shape", "a segment polyline must be on a static body");
  const geometry::ChainCheck check = geometry::CheckChain(part.points, part.loop);
  switch (check.problem) {
    case geometry::ChainProblem::kNone:
      break;
    case geometry::ChainProblem::kTooFewPoints:
      return Problem("points", part.loop ? "a loop needs at least 3 points" : "needs at least 2 points");
    case geometry::ChainProblem::kNotFinite:
      return Problem("points", "has a point that is not a finite number (" + PointText(check.index) + ")");
    case geometry::ChainProblem::kZeroLength:
      return Problem("points", "has a segment of zero length (from " + PointText(check.index) + ")");
  }
  if (part.points.size() > kMaxPieces) return Problem("points", "has more than 65535 segments");
  return std::nullopt;
}

}  // namespace

std::optional<PartProblem> CheckShapePart(const ShapePart& part, bool is_static) {
  if (!IsFinite(part.offset)) return Problem("offset", "must be finite");
  if (!std::isfinite(part.angle)) return Problem("angle", "must be finite");
  if (part.density && !Positive(*part.density)) return Problem("density", "must be > 0");
  if (part.friction && !(std::isfinite(*part.friction) && *part.friction >= 0.0)) {
    return Problem("friction", "must be finite and >= 0");
  }
  if (part.restitution && !(std::isfinite(*part.restitution) && *part.restitution >= 0.0)) {
    return Problem("restitution", "must be finite and >= 0");
  }
  switch (part.type) {
    case ShapeType::kCircle:
      if (!Positive(part.radius)) return Problem("radius", "must be > 0");
      return std::nullopt;
    case ShapeType::kBox:
      if (!Positive(part.half_extents.x) || !Positive(part.half_extents.y)) return Problem("size", "must be > 0");
      return std::nullopt;
    case ShapeType::kCapsule:
      if (!Positive(part.length)) return Problem("length", "must be > 0");
      if (!Positive(part.radius)) return Problem("radius", "must be > 0");
      return std::nullopt;
    case ShapeType::kPolygon:
      return CheckPolygon(part);
    case ShapeType::kSegments:
      return CheckSegments(part, is_static);
    case ShapeType::kCompound:
      break;
  }
  return Problem("shape", "must be circle, box, polygon, capsule or segment");
}

}  // namespace engine
