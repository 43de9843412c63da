// Letterboxing, cursor-to-world mapping and the status line for the play window.
#include "game/play_view.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>

namespace game {

render::PixelRect Letterbox(int framebuffer_width, int framebuffer_height, int image_width,
                            int image_height) {
  if (framebuffer_width <= 0 || framebuffer_height <= 0 || image_width <= 0 ||
      image_height <= 0) {
    return {};
  }
  const double scale = std::min(static_cast<double>(framebuffer_width) / image_width,
                                static_cast<double>(framebuffer_height) / image_height);
  const int width = std::clamp(static_cast<int>(std::lround(image_width * scale)), 1,
                               framebuffer_width);
  const int height = std::clamp(static_cast<int>(std::lround(image_height * scale)), 1,
                                framebuffer_height);
  return {(framebuffer_width - width) / 2, (framebuffer_height - height) / 2, width, height};
}

std::optional<engine::Vec2> WindowPointToWorld(const render::Camera& camera,
                                               const render::PixelRect& picture, double x,
                                               double y) {
  const double px = x - picture.x;
  const double py = y - picture.y;
  if (picture.width <= 0 || picture.height <= 0 || px < 0.0 || py < 0.0 ||
      px >= picture.width || py >= picture.height) {
    return std::nullopt;
  }
  return PicturePointToWorld(camera, picture, x, y);
}

engine::Vec2 PicturePointToWorld(const render::Camera& camera, const render::PixelRect& picture,
                                 double x, double y) {
  // The picture is drawn at its own size through the camera, so its pixels map as an image
  // of that size does (the contract's pixel rule).
  return render::PixelToWorld(camera, picture.width, picture.height, x - picture.x, y - picture.y);
}

std::string StatusLine(std::int64_t step, double time, double frames_per_second, bool paused) {
  char line[96];
  std::snprintf(line, sizeof line, "STEP %" PRId64 "  T %.2f S  %.0f FPS%s", step, time,
                frames_per_second, paused ? "  PAUSED" : "");
  return line;
}

std::string ScreenshotStem(const std::string& scene_name, std::int64_t step) {
  std::string stem;
  for (const char c : scene_name) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == '_' || c == '-';
    stem += safe ? c : '_';
  }
  if (stem.empty() || stem[0] == '.') stem.insert(0, "scene");
  char suffix[40];
  std::snprintf(suffix, sizeof suffix, "_step_%06" PRId64, step);
  return stem + suffix;
}

}  // namespace game
