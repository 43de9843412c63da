// Pixel <-> world mapping and the fit-everything camera.
#include "render/camera.h"

#include <algorithm>
#include <cstdint>

namespace render {

engine::Vec2 PixelToWorld(const Camera& camera, int image_width, int image_height, double px,
                          double py) {
  const double s = camera.width / image_width;
  return {camera.center.x + (px - image_width / 2.0) * s,
          camera.center.y - (py - image_height / 2.0) * s};
}

engine::Vec2 WorldToPixel(const Camera& camera, int image_width, int image_height, engine::Vec2 p) {
  const double s = camera.width / image_width;
  return {(p.x - camera.center.x) / s + image_width / 2.0,
          image_height / 2.0 - (p.y - camera.center.y) / s};
}

Camera FrameCamera(const Camera& view, int image_width, int image_height) {
  // Compared in integers, so every 4:3 size keeps the view's width exactly (800 / 600 is not a
  // double, and a width off by one ulp would move every pixel click).
  const std::int64_t wide = std::int64_t{image_width} * kFramingHeight;
  const std::int64_t tall = std::int64_t{image_height} * kFramingWidth;
  if (wide <= tall) return view;  // as wide as 4:3 or taller: the height grows
  // Wider than 4:3: the 800x600 height stays, the width grows with the aspect.
  return Camera{view.center, view.width * static_cast<double>(wide) / static_cast<double>(tall)};
}

namespace {

// Grows `all` (empty when `any` is false) to hold `box`.
void Include(engine::AABB& all, bool& any, const engine::AABB& box) {
  if (!any) {
    all = box;
    any = true;
    return;
  }
  all.lower = {std::min(all.lower.x, box.lower.x), std::min(all.lower.y, box.lower.y)};
  all.upper = {std::max(all.upper.x, box.upper.x), std::max(all.upper.y, box.upper.y)};
}

// A particle as the renderer draws it: a disc of `radius` round `p`.
engine::AABB Around(engine::Vec2 p, double radius) {
  return {{p.x - radius, p.y - radius}, {p.x + radius, p.y + radius}};
}

}  // namespace

Camera FitCamera(const engine::World& world, int image_width, int image_height) {
  // A tenth of the larger side as margin on every side keeps bodies clear of the image edge.
  constexpr double kMarginFraction = 0.1;
  engine::AABB all;
  bool any = false;
  for (const engine::BodyId id : world.BodyIds()) Include(all, any, world.BodyBounds(id));
  // Soft bodies and fluid are in the picture too (effect particles come and go: not framed).
  for (const engine::SoftBodyId id : world.SoftBodyIds()) {
    const double radius = world.SoftBodyParticleRadius(id);
    for (const engine::Vec2 p : world.SoftBodyPositions(id)) Include(all, any, Around(p, radius));
  }
  for (const engine::Vec2 p : world.FluidPositions()) {
    Include(all, any, Around(p, 0.5 * world.FluidSpacing()));
  }
  if (!any) return Camera{};
  const double w = all.upper.x - all.lower.x;
  const double h = all.upper.y - all.lower.y;
  const double aspect = static_cast<double>(image_width) / image_height;
  const double fit_width = std::max(w, h * aspect);
  const double margin = kMarginFraction * std::max(w, h * aspect);
  return Camera{0.5 * (all.lower + all.upper), fit_width + 2.0 * margin};
}

}  // namespace render
