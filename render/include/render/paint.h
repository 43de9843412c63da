// Filled rectangles painted straight into an image in memory: how a film's HUD goes onto its
// frames without touching the GL picture the window shows.
#pragma once

#include <span>

#include "render/image.h"
#include "render/rect.h"

namespace render {

/// Paints each rectangle in order, clipped to the image.
void PaintRects(Image& image, std::span<const FilledRect> rects);

}  // namespace render
