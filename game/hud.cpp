// The HUD is painted on the frame in memory after read-back, so the GL picture stays the scene.
#include "game/hud.h"

#include <cinttypes>
#include <cstdio>

#include "render/bitmap_text.h"
#include "render/paint.h"

namespace game {

std::string HudText(std::int64_t step, double time, std::uint64_t state_hash) {
  char text[96];
  std::snprintf(text, sizeof text, "STEP %" PRId64 "  T %.3f S  HASH %016" PRIX64, step, time,
                state_hash);
  return text;
}

void PaintHud(render::Image& frame, const std::string& text) {
  const int cell = frame.width >= 480 ? 2 : 1;
  render::PaintRects(frame, render::TextPanel(text, cell, render::kPanelBackdrop, render::kPanelText));
}

}  // namespace game
