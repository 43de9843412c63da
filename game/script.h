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
};

struct InputEvent {
  std::int64_t step = 0;  ///< applied before this step is simulated
  EventKind kind = EventKind::kClickWorld;
  engine::Vec2 at;
};

/// Parses a script; errors name `file_label` and the line. Steps must not decrease.
Expected<std::vector<InputEvent>> ParseScript(std::string_view text, const std::string& file_label);
Expected<std::vector<InputEvent>> LoadScript(const std::string& path);

/// Writes events in the script format, so that ParseScript reads back exactly the same values.
std::string FormatScript(const std::vector<InputEvent>& events);

}  // namespace game
