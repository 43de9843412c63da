// Soft bodies as the renderer draws them: the rim through the particle centres, grown outward
// by the particle radius to the body's surface, filled with a triangle fan from its centroid
// and skirted by a band just outside it, every vertex carrying its signed distance to the
// outline edge its triangle belongs to. The shader shades that distance exactly as the body
// shaders shade theirs: an anti-aliased edge and a darker outline inside it. No GL.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/particle_style.h"

namespace render {

/// One vertex of the soft bodies' triangles: the attributes the soft body shader reads.
struct SoftBodyVertex {
  float position[2];      // m, relative to the camera centre
  float edge_distance;    // m to the outline edge's line, negative inside
  float outline_width;    // m: the body's outline band
  std::uint8_t color[4];  // the fill
};

/// One frame's soft bodies, in slot order (later slots on top), as plain triangles.
class SoftBodyMesh {
 public:
  /// Collects every soft body of `world`, coloured by `style`, for `camera` at `pixel_size`
  /// metres per pixel. Empty for a world with none, so nothing at all is drawn for it.
  void Build(const engine::World& world, const ParticleStyle& style, const Camera& camera,
             double pixel_size);
  const std::vector<SoftBodyVertex>& Vertices() const { return vertices_; }

  /// A soft body's surface: the rim points `outline` picks out of `positions` (anticlockwise),
  /// each moved `radius` outward along the mitre of its two edges, so every edge moves exactly
  /// `radius`; repeated points dropped. Fewer than 3 points when the rim has no area to fill.
  const std::vector<engine::Vec2>& GrowOutline(std::span<const engine::Vec2> positions,
                                               std::span<const std::uint32_t> outline,
                                               double radius);

 private:
  // Appends the fill and skirt of the surface GrowOutline made.
  void AddBody(Color color);
  void AddVertex(engine::Vec2 p, double edge_distance, double outline_width, Color color);

  std::vector<SoftBodyVertex> vertices_;
  // Scratch for the body being added, kept to reuse its storage.
  std::vector<engine::Vec2> rim_;      // its rim's particle centres
  std::vector<engine::Vec2> surface_;  // the rim grown to its surface
  std::vector<engine::Vec2> normals_;  // outward unit normals of the rim's or surface's edges
  engine::Vec2 origin_;                // the camera centre, subtracted in double
  double pixel_size_ = 1.0;            // m per pixel
};

}  // namespace render
