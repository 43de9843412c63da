// A body's parts as primitives in the body's frame, their quads, which of them lie near each
// other (a sweep over their boxes), and the records and instances the part shader reads.
#include "part_batch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace render {
namespace {

using engine::Vec2;

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

// The part of segment a0 a1 (as t from 0 to 1) inside a convex polygon grown by `slack`:
// Cyrus–Beck clipping. Empty when t_enter >= t_exit.
std::pair<double, double> ClipToConvex(Vec2 a0, Vec2 a1, const Vec2* poly, std::size_t n,
                                       double slack) {
  double twice_area = 0.0;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) twice_area += engine::Cross(poly[j], poly[i]);
  const double side = twice_area >= 0.0 ? 1.0 : -1.0;  // outward normals either winding
  double enter = 0.0, exit = 1.0;
  for (std::size_t i = 0, j = n - 1; i < n && enter < exit; j = i++) {
    const Vec2 e = poly[i] - poly[j];
    const Vec2 normal = side * Vec2{e.y, -e.x};
    const double limit = slack * engine::Length(normal) - engine::Dot(normal, a0 - poly[j]);
    const double rate = engine::Dot(normal, a1 - a0);
    if (rate == 0.0) {
      if (limit < 0.0) return {1.0, 0.0};
    } else if (rate > 0.0) {
      exit = std::min(exit, limit / rate);
    } else {
      enter = std::max(enter, limit / rate);
    }
  }
  return {enter, exit};
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
  outline_.clear();
  const engine::BodyState& state = world.State(id);
  const std::span<const engine::ShapePart> parts = world.Parts(id);
  const double line_radius = 0.5 * kLineWidthPixels * pixel_size;
  Vec2 origin;
  double angle = 0.0, thickness = 0.0;
  if (parts.empty()) {
    // A lone circle or box, at its centre.
    const engine::Shape& shape = world.Info(id).shape;
    if (shape.type == engine::ShapeType::kCircle) {
      AddRound(PrimitiveKind::kCircle, {}, {shape.radius, 0.0}, shape.radius, 0);
    } else {
      const Vec2 h = shape.half_extents;
      AddPolygon({{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}}, 0.0, {1.0, 0.0}, 0);
    }
    origin = state.position;
    angle = rotation ? state.angle : 0.0;
    thickness = shape.type == engine::ShapeType::kCircle
                    ? shape.radius
                    : std::min(shape.half_extents.x, shape.half_extents.y);
  } else {
    for (const engine::ConvexPiece& piece : world.Pieces(id)) AddPiece(piece, parts, line_radius);
    // Grouped polygon pieces first, each group's one after another, as the shader gathers them.
    std::stable_sort(primitives_.begin(), primitives_.end(),
                     [](const Primitive& a, const Primitive& b) { return a.group < b.group; });
    // A body made of parts is drawn where the engine collides it, angle and all.
    for (const engine::ShapePart& part : parts) {
      thickness = std::max(thickness, PartThickness(part, line_radius));
    }
    origin = world.Origin(id);
    angle = state.angle;
  }
  // A turned quad reaches √2 times its margin beyond its box; a little more absorbs rounding.
  FindNeighbours(1.5 * kQuadMarginPixels * pixel_size);
  MarkOutline();
  Emit(origin - camera.center, engine::MakeRot(angle), color, thickness);
}

void PartBatch::AddPiece(const engine::ConvexPiece& piece,
                         std::span<const engine::ShapePart> parts, double line_radius) {
  // A part's own x axis: a circle's spoke runs along it, a polygon's quad is squared to it.
  const double part_angle = parts.empty() ? 0.0 : parts[piece.part].angle;
  const Vec2 axis = engine::Rotate(engine::MakeRot(part_angle), {1.0, 0.0});
  const std::vector<Vec2>& v = piece.vertices;
  switch (piece.type) {
    case engine::ShapeType::kCircle:
      AddRound(PrimitiveKind::kCircle, v[0], v[0] + piece.radius * axis, piece.radius, piece.part);
      return;
    case engine::ShapeType::kCapsule:
      AddRound(PrimitiveKind::kCapsule, v[0], v[1], piece.radius, piece.part);
      return;
    case engine::ShapeType::kSegments:
      AddRound(PrimitiveKind::kCapsule, v[0], v[1], line_radius, piece.part);
      return;
    default:
      AddPolygon(v, piece.radius, axis, piece.part);
      return;
  }
}

void PartBatch::AddPolygon(const std::vector<Vec2>& points, double radius, Vec2 axis, int part) {
  Primitive p;
  p.kind = PrimitiveKind::kPolygon;
  p.first = vertices_.size();
  p.count = points.size();
  p.radius = radius;
  p.part = part;
  // Sharp pieces all share one group, so parts that touch or overlap have one outline; a rounded
  // part's pieces have their own, since the rounding is the group's.
  p.group = radius == 0.0 ? 0 : 1 + part;
  for (const Vec2 v : points) {
    vertices_.push_back(v);
    outline_.push_back(1);
  }
  // The quad: the least-area rectangle around the piece, which has a side along one of its
  // edges (Freeman and Shapira, 1975); the part's axis first, so a box's quad is the box.
  double least = INFINITY;
  const auto try_axis = [&](Vec2 u) {
    Vec2 lower{INFINITY, INFINITY}, upper{-INFINITY, -INFINITY};
    for (const Vec2 v : points) {
      const Vec2 q{engine::Dot(v, u), engine::Cross(u, v)};
      lower = {std::min(lower.x, q.x), std::min(lower.y, q.y)};
      upper = {std::max(upper.x, q.x), std::max(upper.y, q.y)};
    }
    const Vec2 size = upper - lower;
    if (!(size.x * size.y < least)) return;
    least = size.x * size.y;
    const Vec2 mid = 0.5 * (lower + upper);
    p.axis = u;
    p.center = mid.x * u + mid.y * engine::LeftPerp(u);
    p.half = 0.5 * size + Vec2{radius, radius};
  };
  try_axis(axis);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 e = points[(i + 1) % points.size()] - points[i];
    const double length = engine::Length(e);
    if (length > 0.0) try_axis(e / length);
  }
  primitives_.push_back(p);
}

void PartBatch::AddRound(PrimitiveKind kind, Vec2 a, Vec2 b, double radius, int part) {
  Primitive p;
  p.kind = kind;
  p.first = vertices_.size();
  p.count = 2;
  p.radius = radius;
  p.part = part;
  p.group = std::numeric_limits<int>::max();  // round kinds join the union one by one
  vertices_.push_back(a);
  vertices_.push_back(b);
  outline_.insert(outline_.end(), {1, 1});
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

void PartBatch::MarkOutline() {
  // An edge, or the stretch of one, that lies inside or on another piece of its group is not the
  // outline: a cut the engine made in a concave polygon, or where two parts touch or overlap.
  // Such edges are split where the stretch begins and ends, the stretch marked.
  double scale = 1.0;
  for (const Vec2 v : vertices_) scale = std::max({scale, std::abs(v.x), std::abs(v.y)});
  const double slack = 1e-9 * scale;  // coincident edges of turned parts differ by rounding
  split_vertices_.clear();
  split_outline_.clear();
  split_start_.clear();
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& a = primitives_[i];
    split_start_.push_back(split_vertices_.size());
    for (std::size_t m = 0; m < a.count; ++m) {
      const Vec2 a0 = vertices_[a.first + m], a1 = vertices_[a.first + (m + 1) % a.count];
      covered_.clear();
      for (std::size_t k = neighbour_start_[i]; k < neighbour_start_[i + 1]; ++k) {
        const Primitive& b = primitives_[neighbours_[k]];
        if (a.kind != PrimitiveKind::kPolygon || b.kind != PrimitiveKind::kPolygon ||
            neighbours_[k] == static_cast<int>(i) || b.group != a.group) {
          continue;
        }
        const auto [enter, exit] = ClipToConvex(a0, a1, &vertices_[b.first], b.count, slack);
        if (exit - enter > 1e-9) covered_.emplace_back(enter, exit);
      }
      AppendEdge(a0, a1);
    }
  }
  // A circle's or capsule's two points come through as the edge there and back: both kept.
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    primitives_[i].first = split_start_[i];
    const std::size_t end = i + 1 < primitives_.size() ? split_start_[i + 1] : split_vertices_.size();
    primitives_[i].count = end - split_start_[i];
  }
  vertices_.swap(split_vertices_);
  outline_.swap(split_outline_);
}

void PartBatch::AppendEdge(Vec2 a0, Vec2 a1) {
  // covered_ holds the stretches (as t) other pieces cover: merged, they split the edge.
  std::sort(covered_.begin(), covered_.end());
  double t = 0.0;
  split_vertices_.push_back(a0);
  split_outline_.push_back(1);
  for (const auto& [enter, exit] : covered_) {
    if (exit <= t) continue;
    if (enter > t) {  // an outline stretch ends where the covered one begins
      split_vertices_.push_back(a0 + enter * (a1 - a0));
      split_outline_.push_back(1);
    }
    split_outline_.back() = 0;
    t = exit;
    if (t >= 1.0) break;
    split_vertices_.push_back(a0 + t * (a1 - a0));
    split_outline_.push_back(1);
  }
}

bool PartBatch::QuadsMeet(int a, int b, double margin) const {
  // Separating axes: the two rectangles' own axes.
  const Primitive& p = primitives_[a];
  const Primitive& q = primitives_[b];
  const Vec2 d = q.center - p.center;
  for (const Vec2 u : {p.axis, engine::LeftPerp(p.axis), q.axis, engine::LeftPerp(q.axis)}) {
    const auto reach = [&](const Primitive& r) {
      return std::abs(engine::Dot(u, r.axis)) * (r.half.x + margin) +
             std::abs(engine::Cross(u, r.axis)) * (r.half.y + margin);
    };
    if (std::abs(engine::Dot(u, d)) > reach(p) + reach(q)) return false;
  }
  return true;
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
      if (engine::Overlaps(a, boxes_[order_[m]]) && QuadsMeet(order_[k], order_[m], margin)) {
        pairs_.emplace_back(order_[k], order_[m]);
      }
    }
  }
  // Each primitive's list: itself and its neighbours, in primitive order (so the pieces of a
  // part come one after another, and every list breaks ties the same way), in one array.
  neighbour_start_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) neighbour_start_[i + 1] = 1;
  for (const auto& [a, b] : pairs_) {
    ++neighbour_start_[a + 1];
    ++neighbour_start_[b + 1];
  }
  for (int i = 0; i < n; ++i) neighbour_start_[i + 1] += neighbour_start_[i];
  neighbours_.resize(neighbour_start_[n]);
  cursor_.assign(neighbour_start_.begin(), neighbour_start_.end() - 1);
  for (int i = 0; i < n; ++i) neighbours_[cursor_[i]++] = i;
  for (const auto& [a, b] : pairs_) {
    neighbours_[cursor_[a]++] = b;
    neighbours_[cursor_[b]++] = a;
  }
  for (int i = 0; i < n; ++i) {
    std::sort(neighbours_.begin() + neighbour_start_[i], neighbours_.begin() + neighbour_start_[i + 1]);
  }
}

bool PartBatch::OnlyOwnGroup(std::size_t i) const {
  const Primitive& p = primitives_[i];
  if (p.kind != PrimitiveKind::kPolygon) return false;
  for (std::size_t k = neighbour_start_[i]; k < neighbour_start_[i + 1]; ++k) {
    const Primitive& other = primitives_[neighbours_[k]];
    if (other.kind != PrimitiveKind::kPolygon || other.group != p.group) return false;
  }
  return true;
}

void PartBatch::Emit(Vec2 origin, engine::Rot rotation, Color color, double thickness) {
  // Records first, so neighbour lists can name them by texel.
  records_.resize(primitives_.size());
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    records_[i] = TexelCount();
    PutTexel(texels_, static_cast<double>(p.kind), static_cast<double>(p.count), p.radius,
             p.kind == PrimitiveKind::kPolygon ? static_cast<double>(p.group) : -1.0);
    if (p.kind != PrimitiveKind::kPolygon) {
      const Vec2 a = vertices_[p.first], b = vertices_[p.first + 1];
      PutTexel(texels_, a.x, a.y, b.x, b.y);
      continue;
    }
    // A vertex a texel, with whether the edge from it to the next one is on the outline.
    for (std::size_t v = p.first; v < p.first + p.count; ++v) {
      PutTexel(texels_, vertices_[v].x, vertices_[v].y, outline_[v], 0.0);
    }
  }
  for (std::size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    const std::size_t first = TexelCount();
    // A lone primitive needs no list: the shader takes the body to be it.
    const std::size_t count =
        primitives_.size() == 1 ? 0 : neighbour_start_[i + 1] - neighbour_start_[i];
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
    instance.only_own_group = OnlyOwnGroup(i) ? 1.0f : 0.0f;
    instances_.push_back(instance);
  }
}

}  // namespace render
