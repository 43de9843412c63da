// How `ballbox play` lays its picture out in a window and reads clicks back from it: pure
// functions of sizes and the camera, so they are tested without a window.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "engine/math.h"
#include "render/camera.h"
#include "render/rect.h"

namespace game {

/// Where the picture goes in a framebuffer_width × framebuffer_height window: the largest
/// rectangle with the aspect of image_width × image_height that fits, centred (letterbox bars
/// on the other sides). Empty (0 × 0) when the window has no area, e.g. minimised.
render::PixelRect Letterbox(int framebuffer_width, int framebuffer_height, int image_width,
                            int image_height);

/// The world point under framebuffer pixel (x, y) when `picture` shows `camera`'s view, or
/// nothing outside the picture (on a bar).
std::optional<engine::Vec2> WindowPointToWorld(const render::Camera& camera,
                                               const render::PixelRect& picture, double x,
                                               double y);

/// The world point under framebuffer pixel (x, y) when `picture` shows `camera`'s view, also
/// beyond the picture's edges (a drag goes on over the bars). Precondition: a picture with area.
engine::Vec2 PicturePointToWorld(const render::Camera& camera, const render::PixelRect& picture,
                                 double x, double y);

/// The status line drawn over the picture, e.g. "STEP 120  T 2.00 S  60 FPS  PAUSED".
std::string StatusLine(std::int64_t step, double time, double frames_per_second, bool paused);

/// A screenshot's file name without ".png": the scene name (characters other than letters,
/// digits, '.', '_' and '-' become '_') and the step, e.g. "default_step_000090".
std::string ScreenshotStem(const std::string& scene_name, std::int64_t step);

}  // namespace game
