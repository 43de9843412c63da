// Input scripts (see docs/script-format.md): one event a line, applied before its step.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "game/status.h"

namespace game {

enum class EventKind {
  kClickPixel,  ///< `click px py`: pixel coordinates of the rendered image
  kClickWorld,  ///< `click-world x y`: world coordinates, metres
  kGrabPixel,   ///< `grab px py`: the right button went down there (docs/play.md: dragging)
  kGrabWorld,   ///< `grab-world x y`
  kDragPixel,   ///< `drag px py`: the held body's target moved there
  kDragWorld,   ///< `drag-world x y`
  kRelease,     ///< `release`: the right button went up; no coordinates
};

/// Whether the event's point is a pixel of an image (mapped through the camera).
constexpr bool IsPixelEvent(EventKind kind) {
  return kind == EventKind::kClickPixel || kind == EventKind::kGrabPixel ||
         kind == EventKind::kDragPixel;
}
constexpr bool IsClick(EventKind kind) {
  return kind == EventKind::kClickPixel || kind == EventKind::kClickWorld;
}
constexpr bool IsGrab(EventKind kind) {
  return kind == EventKind::kGrabPixel || kind == EventKind::kGrabWorld;
}
constexpr bool IsDrag(EventKind kind) {
  return kind == EventKind::kDragPixel || kind == EventKind::kDragWorld;
}

/// The event's name in a script: "click", "grab-world", "release", ...
const char* EventName(EventKind kind);
/// The world-point kind of the same event (a pixel click's is kClickWorld), as recordings hold.
EventKind WorldKind(EventKind kind);

struct InputEvent {
  std::int64_t step = 0;  ///< applied before this step is simulated
  EventKind kind = EventKind::kClickWorld;
  engine::Vec2 at;  ///< unused by kRelease
  /// Pixel events: the image size the pixel was made for (the script's `size W H` line), so it
  /// maps through the camera framed at that size; 0 × 0: the size being rendered.
  int image_width = 0;
  int image_height = 0;
};

/// Parses a script; errors name `file_label` and the line. Steps must not decrease. A UTF-8
/// byte order mark at the start is skipped (editors on Windows write one).
Expected<std::vector<InputEvent>> ParseScript(std::string_view text, const std::string& file_label);
Expected<std::vector<InputEvent>> LoadScript(const std::string& path);

/// Writes events in the script format, so that ParseScript reads back exactly the same values;
/// a `size` line comes first when the pixel events carry an image size.
std::string FormatScript(const std::vector<InputEvent>& events);

/// The line naming the image size pixel clicks were made for: "size 800 600\n".
std::string SizeLine(int image_width, int image_height);

}  // namespace game
