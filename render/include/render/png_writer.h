// PNG encoding of rendered frames, in memory: fast settings for image sequences, or stb's
// stock settings as the baseline the render benchmark compares with.
#pragma once

#include <cstdint>
#include <vector>

#include "render/image.h"

namespace render {

enum class PngEncoding {
  kFast,        ///< filter "none" and zlib level 1: several times faster, and smaller on our frames
  kStbDefault,  ///< stb's own settings: all five filters tried per row, its own deflate
};

/// The image as a complete PNG file (RGB, 8 bits a channel). Empty only when memory ran out.
/// Safe to call from several threads at once.
std::vector<std::uint8_t> EncodePng(const Image& image, PngEncoding encoding = PngEncoding::kFast);

}  // namespace render
