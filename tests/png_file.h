// A PNG file read back as the renderer's image (stb_image, an independent decoder from the
// writer's zlib path), for the tests that look at what `ballbox render` and `play` wrote.
#pragma once

#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <cstddef>
#include <filesystem>
#include <vector>

#include "render/image.h"

namespace testing {

inline render::Image LoadPng(const std::filesystem::path& path) {
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &n, 3);
  INFO(path);
  REQUIRE(pixels != nullptr);
  render::Image image{w, h, std::vector<std::uint8_t>(pixels, pixels + static_cast<std::size_t>(w) * h * 3)};
  stbi_image_free(pixels);
  return image;
}

}  // namespace testing
