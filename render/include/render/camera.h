// The camera: which part of the world an image shows, and the pixel <-> world mapping (no GL).
#pragma once

#include "engine/math.h"
#include "engine/world.h"

namespace render {

/// A view of the world: `center` lands at the image centre and `width` metres span the image's
/// width; the visible height follows the image's aspect ratio.
struct Camera {
  engine::Vec2 center;
  double width = 20.0;
};

/// The image size a scene's camera is framed for: its `width` is what an 800x600 image shows.
inline constexpr int kFramingWidth = 800;
inline constexpr int kFramingHeight = 600;

/// The camera of a width × height image that shows at least the region `view` shows at
/// 800x600, centred the same: the image's wider side (relative to 4:3) shows more, so nothing
/// drops out of the picture at any size or aspect. At 4:3 sizes it is `view` itself, bit for bit.
Camera FrameCamera(const Camera& view, int image_width, int image_height);

/// Pixel coordinates are continuous with (0, 0) at the image's top-left corner and y down.
/// World y points up. s = width / image_width metres per pixel.
engine::Vec2 PixelToWorld(const Camera& camera, int image_width, int image_height, double px,
                          double py);
/// The inverse of PixelToWorld.
engine::Vec2 WorldToPixel(const Camera& camera, int image_width, int image_height, engine::Vec2 p);

/// A camera showing every body, soft body and fluid particle of the world with a margin around
/// them in an image of this size, for scenes that set none.
Camera FitCamera(const engine::World& world, int image_width, int image_height);

}  // namespace render
