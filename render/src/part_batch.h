// Bodies as the part shader draws them: every circle, box, polygon, capsule and polyline segment
// of a body is one primitive (a record in a texture buffer) drawn as one instance of a quad, and
// the pixels where a body's primitives meet are drawn once, with the distance to their union, so
// a body shows one outline however many parts and pieces it is made of. No GL here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"

namespace render {

/// Segment polylines have no area: they are drawn as bands this many pixels wide at any zoom.
inline constexpr double kLineWidthPixels = 6.0;

/// Quads reach this many pixels beyond their primitive, room for its anti-aliased edge (the
/// vertex shader's 2.0; neighbour tests add the slack of a turned quad).
inline constexpr double kQuadMarginPixels = 2.0;

/// The kinds of primitive records, as the fragment shader reads them.
enum class PrimitiveKind : std::uint8_t { kCircle = 0, kCapsule = 1, kPolygon = 2 };

/// One primitive as drawn: the vertex attributes of its instance.
struct PartInstance {
  float origin[2];       // m, the body frame's origin relative to the camera centre
  float rotation[2];     // cos and sin of the body's angle
  float quad_center[2];  // m, body frame: the quad covers the primitive
  float quad_axis[2];    // unit vector in the body frame along which quad_half.x runs
  float quad_half[2];    // m
  std::uint8_t color[4];
  // The texel of the primitive's record; the first texel and the number of its neighbours'
  // record indices (four a texel); the body's thickness (m), which caps its outline's width.
  float record[4];
};

/// One frame's instances and texture buffer contents (RGBA32F texels).
class PartBatch {
 public:
  void Clear();
  /// Appends body `id`: a lone circle or box (at its centre, turned only when `rotation` is on,
  /// as the plain path draws it) or a body made of parts (at World::Origin, turned by its angle).
  /// `pixel_size` is the camera's metres per pixel.
  void Append(const engine::World& world, engine::BodyId id, Color color, bool rotation,
              const Camera& camera, double pixel_size);
  /// Drops everything appended after the batch had `instances` instances and `texels` texels.
  void Truncate(std::size_t instances, std::size_t texels);

  const std::vector<PartInstance>& Instances() const { return instances_; }
  const std::vector<float>& Texels() const { return texels_; }
  std::size_t TexelCount() const { return texels_.size() / 4; }

 private:
  // A primitive of the body being appended, in the body's frame.
  struct Primitive {
    PrimitiveKind kind = PrimitiveKind::kPolygon;
    std::size_t first = 0;  // into vertices_
    std::size_t count = 0;
    double radius = 0.0;    // m: circle, capsule or line half-width, polygon rounding
    engine::Vec2 center, axis{1.0, 0.0}, half;  // the quad
  };

  void AddSimple(const engine::Shape& shape);
  void AddPart(const engine::ShapePart& part, double line_radius);
  /// The polygon whose points are vertices_ from `first` on.
  void AddPolygon(std::size_t first, double radius, engine::Vec2 axis);
  void AddRound(PrimitiveKind kind, engine::Vec2 a, engine::Vec2 b, double radius);
  void FindNeighbours(double margin);
  void Emit(engine::Vec2 origin, engine::Rot rotation, Color color, double thickness);

  std::vector<PartInstance> instances_;
  std::vector<float> texels_;
  // Scratch for the body being appended, kept to reuse its storage.
  std::vector<Primitive> primitives_;
  std::vector<engine::Vec2> vertices_;
  std::vector<std::pair<int, int>> pairs_;     // neighbouring primitives, each pair once
  std::vector<int> order_;                     // primitives by the left side of their box
  std::vector<engine::AABB> boxes_;
  std::vector<std::size_t> neighbour_start_;   // per primitive, into neighbours_; then the end
  std::vector<std::size_t> cursor_;            // where each list is filled up to
  std::vector<int> neighbours_;
  std::vector<std::size_t> records_;           // per primitive, its record's texel
};

}  // namespace render
