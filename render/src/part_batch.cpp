// A body's parts as primitives in the body's frame, their quads, which of them lie near each
// other (a sweep over their boxes), and the records and instances the part shader reads.
#include "part_batch.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

using engine::Vec2;

// A part's point in the body's frame.
Vec2 InBody(const engine::ShapePart& part, engine::Rot turn, Vec2 v) {
  return part.offset + engine::Rotate(turn, v);
}

// About the radius of the largest circle inside the polygon (exactly that for a regular one):
// 2·area / perimeter.
double PolygonThickness(const std::vector<Vec2>& points) {
  double twice_area = 0.0, perimeter = 0.0;
  for (std::size_t i = 0, j = points.size() - 1; i < points.size(); j = i++) {
    twice_area += engine::Cross(points[j], points[i]);
    perimeter += engine::Length(points[i] - points[j]);
  }
  return perimeter > 0.0 ? std::abs(twice_area) / perimeter : 0.0;
}

// How thick a part is, for the outline's width: thin shapes keep some fill.
double PartThickness(const engine::ShapePart& part, double line_radius) {
  switch (part.type) {
    case engine::ShapeType::kCircle:
    case engine::ShapeType::kCapsule:
      return part.radius;
    case engine::ShapeType::kBox:
      return std::min(part.half_extents.x, part.half_extents.y);
    case engine::ShapeType::kPolygon:
      return PolygonThickness(part.points) + part.radius;
    default:
      return line_radius;
  }
}

engine::AABB Grown(const engine::AABB& box, double margin) {
  return {box.lower - Vec2{margin, margin}, box.upper + Vec2{margin, margin}};
}

void PutTexel(std::vector<float>& texels, double a, double b, double c, double d) {
  texels.insert(texels.end(), {static_cast<float>(a), static_cast<float>(b),
                               static_cast<float>(c), static_cast<float>(d)});
}

}  // namespace

void PartBatch::Clear() {
  instances_.clear();
  texels_.clear();
}

void PartBatch::Truncate(std::size_t instances, std::size_t texels) {
  instances_.resize(instances);
  texels_.resize(4 * texels);
}

void PartBatch::Append(const engine::World& world, engine::BodyId id, Color color,
                       bool rotation, const Camera& camera, double pixel_size) {
  primitives_.clear();
  vertices_.clear();
  const engine::BodyState& state = world.State(id);
  const std::span<const engine::ShapePart> parts = world.Parts(id);
  Vec2 origin;
  double angle = 0.0, thickness = 0.0;
  if (parts.empty()) {
    const engine::Shape& shape = world.Info(id).shape;
    AddSimple(shape);
    origin = state.position;
    angle = rotation ? state.angle : 0.0;
    thickness = shape.type == engine::ShapeType::kCircle
                    ? shape.radius
                    : std::min(shape.half_extents.x, shape.half_extents.y);
  } else {
    // A body made of parts is drawn where the engine collides it, angle and all.
    const double line_radius = 0.5 * kLineWidthPixels * pixel_size;
    for (const engine::ShapePart& part : parts) {
      AddPart(part, line_radius);
      thickness = std::max(thickness, PartThickness(part, line_radius));
    }
    origin = world.Origin(id);
    angle = state.angle;
  }
  // A turned quad reaches √2 times its margin beyond its box; a little more absorbs rounding.
  FindNeighbours(1.5 * kQuadMarginPixels * pixel_size);
  Emit(origin - camera.center, engine::MakeRot(angle), color, thickness);
}

void PartBatch::AddSimple(const engine::Shape& shape) {
  if (shape.type == engine::ShapeType::kCircle) {
    AddRound(PrimitiveKind::kCircle, {}, {shape.radius, 0.0}, shape.radius);
    return;
  }
  const Vec2 h = shape.half_extents;
  const std::size_t first = vertices_.size();
  vertices_.insert(vertices_.end(), {{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}});
  AddPolygon(first, 0.0, {1.0, 0.0});
}

void PartBatch::AddPart(const engine::ShapePart& part, double line_radius) {
  const engine::Rot turn = engine::MakeRot(part.angle);
  const Vec2 axis = engine::Rotate(turn, {1.0, 0.0});
  switch (part.type) {
    case engine::ShapeType::kCircle:
      AddRound(PrimitiveKind::kCircle, part.offset, InBody(part, turn, {part.radius, 0.0}),
               part.radius);
      return;
    case engine::ShapeType::kCapsule:
      AddRound(PrimitiveKind::kCapsule, InBody(part, turn, {-0.5 * part.length, 0.0}),
               InBody(part, turn, {0.5 * part.length, 0.0}), part.radius);
      return;
    case engine::ShapeType::kBox: {
      const Vec2 h = part.half_extents;
      const std::size_t first = vertices_.size();
      for (const Vec2 corner : {Vec2{-h.x, -h.y}, Vec2{h.x, -h.y}, h, Vec2{-h.x, h.y}}) {
        vertices_.push_back(InBody(part, turn, corner));
      }
      AddPolygon(first, 0.0, axis);
      return;
    }
    case engine::ShapeType::kPolygon: {
      const std::size_t first = vertices_.size();
      for (const Vec2 p : part.points) vertices_.push_back(InBody(part, turn, p));
      AddPolygon(first, part.radius, axis);
      return;
    }
    case engine::ShapeType::kSegments: {
      const std::size_t n = part.points.size();
      const std::size_t segments = part.loop ? n : n - 1;
      for (std::size_t i = 0; i < segments; ++i) {
        AddRound(PrimitiveKind::kCapsule, InBody(part, turn, part.points[i]),
                 InBody(part, turn, part.points[(i + 1) % n]), line_radius);
      }
      return;
    }
    case engine::ShapeType::kCompound:
      return;  // never a part's type
  }
}

void PartBatch::AddPolygon(std::size_t first, double radius, Vec2 axis) {
  Primitive p;
  p.kind = PrimitiveKind::kPolygon;
  p.first = first;
  p.count = vertices_.size() - first;
  p.radius = radius;
  p.axis = axis;
  // The quad is the polygon's bounds along the axis and across it.
  Vec2 lower{INFINITY, INFINITY}, upper{-INFINITY, -INFINITY};
  for (std::size_t i = first; i < vertices_.size(); ++i) {
    const Vec2 q{engine::Dot(vertices_[i], axis), engine::Cross(axis, vertices_[i])};
    lower = {std::min(lower.x, q.x), std::min(lower.y, q.y)};
    upper = {std::max(upper.x, q.x), std::max(upper.y, q.y)};
  }
  const Vec2 mid = 0.5 * (lower + upper);
  p.center = mid.x * axis + mid.y * engine::LeftPerp(axis);
  p.half = 0.5 * (upper - lower) + Vec2{radius, radius};
  primitives_.push_back(p);
}

void PartBatch::AddRound(PrimitiveKind kind, Vec2 a, Vec2 b, double radius) {
  Primitive p;
  p.kind = kind;
  p.first = vertices_.size();
  p.count = 2;
  p.radius = radius;
  vertices_.push_back(a);
  vertices_.push_back(b);
  if (kind == PrimitiveKind::kCircle) {
    // b is the tip of the spoke, on the rim.
    p.center = a;
    p.half = {radius, radius};
  } else {
    const double length = engine::Length(b - a);
    p.center = 0.5 * (a + b);
    p.axis = length > 0.0 ? (b - a) / length : Vec2{1.0, 0.0};
    p.half = {0.5 * length + radius, radius};
  }
  primitives_.push_back(p);
}

void PartBatch::FindNeighbours(double margin) {
  const int n = static_cast<int>(primitives_.size());
  boxes_.clear();
  for (const Primitive& p : primitives_) {
    // The quad's box: its half-size seen along the body's axes.
    const Vec2 h{std::abs(p.axis.x) * p.half.x + std::abs(p.axis.y) * p.half.y,
                 std::abs(p.axis.y) * p.half.x + std::abs(p.axis.x) * p.half.y};
    boxes_.push_back(Grown({p.center - h, p.center + h}, margin));
  }
  // Sweep and prune along x: only primitives whose boxes overlap can share a pixel.
  order_.resize(n);
  for (int i = 0; i < n; ++i) order_[i] = i;
  std::sort(order_.begin(), order_.end(), [&](int a, int b) {
    return boxes_[a].lower.x < boxes_[b].lower.x || (boxes_[a].lower.x == boxes_[b].lower.x && a < b);
  });
  pairs_.clear();
  for (int k = 0; k < n; ++k) {
    const engine::AABB& a = boxes_[order_[k]];
    for (int m = k + 1; m < n && boxes_[order_[m]].lower.x <= a.upper.x; ++m) {
      if (engine::Overlaps(a, boxes_[order_[m]])) pairs_.emplace_back(order_[k], order_[m]);
    }
  }
  // Each primitive's list of neighbours, both ways round, in one array.
  neighbour_start_.assign(n + 1, 0);
  for (const auto& [a, b] : pairs_) {
    ++neighbour_start_[a + 1];
    ++neighbour_start_[b + 1];
  }
  for (int i = 0; i < n; ++i) neighbour_start_[i + 1] += neighbour_start_[i];
  neighbours_.resize(neighbour_start_[n]);
  cursor_.assign(neighbour_start_.begin(), neighbour_start_.end() - 1);
  for (const auto& [a, b] : pairs_) {
    neighbours_[cursor_[a]++] = b;
    neighbours_[cursor_[b]++] = a;
  }
}

void PartBatch::Emit(Vec2 origin, engine::Rot rotation, Color color, double thickness) {
  // Records first, so neighbour lists can name them by texel.
  records_.resize(primitives_.size());
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    records_[i] = TexelCount();
    PutTexel(texels_, static_cast<double>(p.kind), static_cast<double>(p.count), p.radius, 0.0);
    for (std::size_t v = 0; v < p.count; v += 2) {
      const Vec2 a = vertices_[p.first + v];
      const Vec2 b = v + 1 < p.count ? vertices_[p.first + v + 1] : Vec2{};
      PutTexel(texels_, a.x, a.y, b.x, b.y);
    }
  }
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    const std::size_t first = TexelCount();
    const std::size_t count = neighbour_start_[i + 1] - neighbour_start_[i];
    for (std::size_t k = 0; k < count; ++k) {
      texels_.push_back(static_cast<float>(records_[neighbours_[neighbour_start_[i] + k]]));
    }
    texels_.resize((texels_.size() + 3) / 4 * 4, 0.0f);  // the next list starts on a texel
    PartInstance instance{};
    instance.origin[0] = static_cast<float>(origin.x);
    instance.origin[1] = static_cast<float>(origin.y);
    instance.rotation[0] = static_cast<float>(rotation.c);
    instance.rotation[1] = static_cast<float>(rotation.s);
    instance.quad_center[0] = static_cast<float>(p.center.x);
    instance.quad_center[1] = static_cast<float>(p.center.y);
    instance.quad_axis[0] = static_cast<float>(p.axis.x);
    instance.quad_axis[1] = static_cast<float>(p.axis.y);
    instance.quad_half[0] = static_cast<float>(p.half.x);
    instance.quad_half[1] = static_cast<float>(p.half.y);
    instance.color[0] = color.r;
    instance.color[1] = color.g;
    instance.color[2] = color.b;
    instance.color[3] = 255;
    instance.record[0] = static_cast<float>(records_[i]);
    instance.record[1] = static_cast<float>(first);
    instance.record[2] = static_cast<float>(count);
    instance.record[3] = static_cast<float>(thickness);
    instances_.push_back(instance);
  }
}

}  // namespace render
