// Rectangles of a window's pixels: where the picture goes and what the overlay is made of.
#pragma once

#include "render/color.h"

namespace render {

/// A rectangle of a window's framebuffer in pixels: (x, y) is its top-left corner, y down.
struct PixelRect {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
  friend constexpr bool operator==(const PixelRect&, const PixelRect&) = default;
};

/// A rectangle filled with one colour: what the window's overlay (text, its backdrop) is made of.
struct FilledRect {
  PixelRect rect;
  Color color;
};

}  // namespace render
