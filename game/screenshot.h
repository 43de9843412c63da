// Screenshots from the play window: PNG files that never replace an existing file.
#pragma once

#include <string>

#include "game/status.h"
#include "render/image.h"

namespace game {

/// Writes `image` as `dir/<stem>.png`, or `dir/<stem>-2.png`, `-3`, … when that name is taken
/// (never overwriting), creating `dir` when missing. The file appears whole: it is written
/// under a temporary name and then linked to its final one. Returns the path written.
Expected<std::string> SaveScreenshot(const render::Image& image, const std::string& dir,
                                     const std::string& stem);

}  // namespace game
