// The film's heads-up display (--hud): step, simulated time and state hash in the top-left
// corner, in the window's bitmap font, so a frame says exactly which state it shows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/rect.h"

namespace game {

/// "STEP 120  T 2.000 S  HASH 61E9C117A690E3B1" (the font has upper case only).
std::string HudText(std::int64_t step, double time, std::uint64_t state_hash);

/// Paints the HUD onto `frame`: cells of 2 pixels on frames at least 480 wide, else 1.
void PaintHud(render::Image& frame, const std::string& text);

}  // namespace game
