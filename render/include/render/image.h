// An image in memory as the renderer reads it back and the PNG writer takes it: 8-bit RGB,
// rows top-down (row 0 is the top of the picture), tightly packed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/color.h"

namespace render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< width × height × 3 bytes

  /// The pixel in column x, row y (from the top). Precondition: inside the image.
  Color At(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

}  // namespace render
