// Bodies as the part shader draws them: every convex piece of a body (World::Pieces: a circle, a
// capsule, a polygon or a polyline's segment) is one primitive (a record in a texture buffer)
// drawn as one instance of a quad, and the pixels where a body's primitives meet are drawn once,
// with the distance to their union, so a body shows one outline however many parts and pieces
// it is made of: edges where pieces meet (a concave polygon's cuts, parts that touch or overlap)
// are marked as not outline. No GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
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
  // The texel of the primitive's record; the first texel and the length of its list of
  // neighbours' record texels, itself included (four a texel); the body's thickness (m), which
  // caps its outline's width.
  float record[4];
  // 1 when the primitive is a polygon piece and every primitive near it is a polygon piece of
  // its group: deep inside it the shader needs no list.
  float only_own_group;
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
  // A primitive of the body being appended, in the body's frame: one of its convex pieces.
  struct Primitive {
    PrimitiveKind kind = PrimitiveKind::kPolygon;
    std::size_t first = 0;  // into vertices_
    std::size_t count = 0;
    double radius = 0.0;    // m: circle, capsule or line half-width, polygon rounding
    int part = 0;           // which of the body's parts it comes from
    // Polygon pieces whose outlines merge: 0 for every sharp piece, 1 + part for a rounded
    // part's; round kinds (circles, capsules, segments) come last and merge one by one.
    int group = 0;
    engine::Vec2 center, axis{1.0, 0.0}, half;  // the quad
  };

  void AddPiece(const engine::ConvexPiece& piece, std::span<const engine::ShapePart> parts,
                double line_radius);
  void AddPolygon(const std::vector<engine::Vec2>& points, double radius, engine::Vec2 axis,
                  int part);
  /// A circle (a: centre, b: the spoke's tip on the rim) or a capsule (a, b: the cap centres).
  void AddRound(PrimitiveKind kind, engine::Vec2 a, engine::Vec2 b, double radius, int part);
  void MarkOutline();
  void FindNeighbours(double margin);
  bool OnlyOwnGroup(std::size_t i) const;
  /// Appends the edge a0 a1 to split_vertices_, split where covered_ begins and ends.
  void AppendEdge(engine::Vec2 a0, engine::Vec2 a1);
  /// Whether the quads of primitives a and b, each grown by `margin`, overlap.
  bool QuadsMeet(int a, int b, double margin) const;
  void Emit(engine::Vec2 origin, engine::Rot rotation, Color color, double thickness);

  std::vector<PartInstance> instances_;
  std::vector<float> texels_;
  // Scratch for the body being appended, kept to reuse its storage.
  std::vector<Primitive> primitives_;
  std::vector<engine::Vec2> vertices_;
  std::vector<std::uint8_t> outline_;          // per vertex: its edge to the next is outline
  std::vector<std::pair<int, int>> pairs_;     // neighbouring primitives, each pair once
  std::vector<int> order_;                     // primitives by the left side of their box
  std::vector<engine::AABB> boxes_;
  std::vector<std::size_t> neighbour_start_;   // per primitive, into neighbours_; then the end
  std::vector<std::size_t> cursor_;            // where each list is filled up to
  std::vector<int> neighbours_;
  std::vector<std::size_t> records_;           // per primitive, its record's texel
  std::vector<std::pair<double, double>> covered_;  // stretches of one edge inside others
  std::vector<engine::Vec2> split_vertices_;   // vertices_ and outline_ as MarkOutline splits
  std::vector<std::uint8_t> split_outline_;
  std::vector<std::size_t> split_start_;       // per primitive, into split_vertices_
};

}  // namespace render
