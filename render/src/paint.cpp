// Rectangles into an RGB image, clipped.
#include "render/paint.h"

#include <algorithm>

namespace render {

void PaintRects(Image& image, std::span<const FilledRect> rects) {
  for (const FilledRect& filled : rects) {
    const PixelRect& r = filled.rect;
    const int x0 = std::max(0, r.x), x1 = std::min(image.width, r.x + r.width);
    const int y0 = std::max(0, r.y), y1 = std::min(image.height, r.y + r.height);
    for (int y = y0; y < y1; ++y) {
      std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(y) * image.width + x0) * 3];
      for (int x = x0; x < x1; ++x, p += 3) {
        p[0] = filled.color.r;
        p[1] = filled.color.g;
        p[2] = filled.color.b;
      }
    }
  }
}

}  // namespace render
