// Body colours and the default palette.
#pragma once

#include <cstddef>
#include <cstdint>

namespace render {

struct Color {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend constexpr bool operator==(Color, Color) = default;
};

/// The colour of the body at `index` when its scene gives none; cycles through a fixed palette.
Color PaletteColor(std::size_t index);

/// The colour static bodies get when their scene gives none.
inline constexpr Color kStaticColor{0x5a, 0x60, 0x6b};

/// What the renderer clears to: a warm off-white that every palette colour stands out from.
inline constexpr Color kBackgroundColor{0xf4, 0xf1, 0xea};

}  // namespace render
