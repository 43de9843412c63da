// Springs and joints as the renderer draws them: thin lines and dots over the bodies, collected
// from World::Draw (DrawSpring, DrawJoint) as segments in camera-relative metres. No GL.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/renderer.h"

namespace render {

/// Line widths and sizes in pixels, the same at every zoom (Box2D's debug draw does the same).
inline constexpr double kLinkLinePixels = 2.0;      ///< a joint's or spring's line, full width
inline constexpr double kLinkDotPixels = 3.5;       ///< an anchor dot's radius
inline constexpr double kLinkHaloPixels = 1.0;      ///< the light rim that sets lines off fills
inline constexpr double kSpringAmplitudePixels = 5.0;  ///< how far a spring's zig-zag swings
inline constexpr int kSpringZigs = 12;  ///< corners of a zig-zag, whatever the spring's length

/// One segment (a dot when a == b), drawn as a capsule: the vertex attributes of its instance.
struct LinkInstance {
  float a[2];         // m, relative to the camera centre
  float b[2];
  float radius;       // m: half the line's width, or the dot's radius
  std::uint8_t color[4];
};

/// One frame's links, in the order World::Draw describes them: springs, then joints.
class LinkLines {
 public:
  /// Collects the world's springs and joints as `layers` selects, for `camera` at `pixel_size`
  /// metres per pixel. Empty for a world with neither, so nothing at all is drawn for it.
  void Build(const engine::World& world, const Camera& camera, double pixel_size,
             LinkLayers layers);
  const std::vector<LinkInstance>& Instances() const { return instances_; }

  // What World::Draw hands over, in world metres (LinkLines' DebugDraw forwards here).
  void AddSpring(engine::Vec2 a, engine::Vec2 b);
  void AddJoint(engine::JointType type, engine::Vec2 center_a, engine::Vec2 anchor_a,
                engine::Vec2 anchor_b, engine::Vec2 center_b);

 private:
  void AddSegment(engine::Vec2 a, engine::Vec2 b, double radius_pixels, Color color);
  void AddDot(engine::Vec2 p, double radius_pixels, Color color);

  std::vector<LinkInstance> instances_;
  engine::Vec2 origin_;       // the camera centre, subtracted in double
  double pixel_size_ = 1.0;   // m per pixel
};

}  // namespace render
