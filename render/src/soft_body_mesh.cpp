// A soft body's surface as a fan from its centroid plus a one-pixel skirt outside it. The fan
// fills the body correctly while its surface stays star-shaped seen from the centroid, which
// the soft bodies' area and shear constraints keep it close to; a body crumpled past that
// would show overlapping or missing slivers, not a crash.
#include "soft_body_mesh.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

using engine::Vec2;

/// The outline band's width, as the body shaders draw it (kOutlinePixels there).
constexpr double kOutlinePixels = 2.0;
/// The skirt reaches this far outside the surface: the anti-aliased edge fades out within
/// half a pixel of it.
constexpr double kSkirtPixels = 1.0;
/// A mitre at a sharp corner is cut to this many times the distance it offsets by, so a rim
/// folded back on itself does not throw a spike across the picture.
constexpr double kMitreLimit = 2.0;

Vec2 RightPerp(Vec2 a) { return {a.y, -a.x}; }

// The outward unit normal of each edge k (from point k to point k + 1) of a closed
// anticlockwise loop; {0, 0} for an edge of no length.
void EdgeNormals(const std::vector<Vec2>& loop, std::vector<Vec2>& normals) {
  const std::size_t n = loop.size();
  normals.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 d = loop[(k + 1) % n] - loop[k];
    const double length = engine::Length(d);
    normals[k] = length > 0.0 ? RightPerp(d) / length : Vec2{};
  }
}

// The offset m of a corner between edges with outward normals a and b that moves both edges
// by 1 (Dot(m, a) = Dot(m, b) = 1), cut to kMitreLimit long.
Vec2 Mitre(Vec2 a, Vec2 b) {
  if (a == Vec2{}) return b;
  if (b == Vec2{}) return a;
  const double one_plus_cos = 1.0 + engine::Dot(a, b);
  // |m|² = 2 / (1 + cos θ).
  if (2.0 < kMitreLimit * kMitreLimit * one_plus_cos) return (a + b) / one_plus_cos;
  const Vec2 sum = a + b;
  const double length = engine::Length(sum);
  // Folded right back: the corner points along the incoming edge.
  const Vec2 direction = length > 1e-12 ? sum / length : engine::LeftPerp(a);
  return kMitreLimit * direction;
}

// The area centroid of a closed loop, and its area; the mean of its points when it has none.
Vec2 Centroid(const std::vector<Vec2>& loop, double& area) {
  const Vec2 base = loop.front();  // relative to a point on it, against cancellation
  double twice_area = 0.0;
  Vec2 weighted;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Vec2 a = loop[k] - base;
    const Vec2 b = loop[(k + 1) % loop.size()] - base;
    const double cross = engine::Cross(a, b);
    twice_area += cross;
    weighted += cross * (a + b);
  }
  area = 0.5 * twice_area;
  if (twice_area > 0.0) return base + weighted / (3.0 * twice_area);
  Vec2 sum;
  for (const Vec2 p : loop) sum += p - base;
  return base + sum / static_cast<double>(loop.size());
}

}  // namespace

void SoftBodyMesh::Build(const engine::World& world, const ParticleStyle& style,
                         const Camera& camera, double pixel_size) {
  vertices_.clear();
  origin_ = camera.center;
  pixel_size_ = pixel_size;
  for (const engine::SoftBodyId id : world.SoftBodyIds()) {
    GrowOutline(world.SoftBodyPositions(id), world.SoftBodyOutline(id),
                world.SoftBodyParticleRadius(id));
    AddBody(style.SoftBodyColor(id));
  }
}

const std::vector<Vec2>& SoftBodyMesh::GrowOutline(std::span<const Vec2> positions,
                                                   std::span<const std::uint32_t> outline,
                                                   double radius) {
  rim_.clear();
  for (const std::uint32_t index : outline) {
    const Vec2 p = positions[index];
    if (rim_.empty() || !(p == rim_.back())) rim_.push_back(p);
  }
  while (rim_.size() > 1 && rim_.front() == rim_.back()) rim_.pop_back();
  surface_.clear();
  if (rim_.size() < 3) return surface_;
  EdgeNormals(rim_, normals_);
  const std::size_t n = rim_.size();
  for (std::size_t k = 0; k < n; ++k) {
    surface_.push_back(rim_[k] + radius * Mitre(normals_[(k + n - 1) % n], normals_[k]));
  }
  return surface_;
}

void SoftBodyMesh::AddBody(Color color) {
  const std::vector<Vec2>& surface = surface_;
  const std::size_t n = surface.size();
  if (n < 3) return;
  EdgeNormals(surface, normals_);
  double area = 0.0;
  const Vec2 center = Centroid(surface, area);
  double perimeter = 0.0;
  for (std::size_t k = 0; k < n; ++k) perimeter += engine::Length(surface[(k + 1) % n] - surface[k]);
  // Thin bodies keep some fill, as in the body shaders: the outline takes at most half the
  // body's thickness, here twice its area over its perimeter (a disc's radius, a square's
  // half side).
  const double thickness = perimeter > 0.0 ? std::max(2.0 * area / perimeter, 0.0) : 0.0;
  const double outline = std::min(kOutlinePixels * pixel_size_, 0.5 * thickness);
  const double skirt = kSkirtPixels * pixel_size_;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 normal = normals_[k];
    if (normal == Vec2{}) continue;
    const Vec2 q0 = surface[k];
    const Vec2 q1 = surface[(k + 1) % n];
    // The distance to the edge's line is linear, so the triangle's own interpolation gives it
    // exactly at every pixel; each edge's triangles carry their own edge's distances.
    AddVertex(center, engine::Dot(center - q0, normal), outline, color);
    AddVertex(q0, 0.0, outline, color);
    AddVertex(q1, 0.0, outline, color);
    const Vec2 o0 = q0 + skirt * Mitre(normals_[(k + n - 1) % n], normal);
    const Vec2 o1 = q1 + skirt * Mitre(normal, normals_[(k + 1) % n]);
    const double d0 = engine::Dot(o0 - q0, normal);
    const double d1 = engine::Dot(o1 - q0, normal);
    AddVertex(q0, 0.0, outline, color);
    AddVertex(q1, 0.0, outline, color);
    AddVertex(o1, d1, outline, color);
    AddVertex(q0, 0.0, outline, color);
    AddVertex(o1, d1, outline, color);
    AddVertex(o0, d0, outline, color);
  }
}

void SoftBodyMesh::AddVertex(Vec2 p, double edge_distance, double outline_width, Color color) {
  SoftBodyVertex vertex{};
  // Relative to the camera in double before going to float, as the bodies are.
  vertex.position[0] = static_cast<float>(p.x - origin_.x);
  vertex.position[1] = static_cast<float>(p.y - origin_.y);
  vertex.edge_distance = static_cast<float>(edge_distance);
  vertex.outline_width = static_cast<float>(outline_width);
  vertex.color[0] = color.r;
  vertex.color[1] = color.g;
  vertex.color[2] = color.b;
  vertex.color[3] = 255;
  vertices_.push_back(vertex);
}

}  // namespace render
