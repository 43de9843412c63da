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

/// Springs (a zig-zag), joints (lines through their anchors) and the mouse's grab (a line from
/// the grabbed point to the cursor): dark on the light rim every link line has, so they read
/// over the background and over any body's fill.
inline constexpr Color kSpringColor{0x6b, 0x4f, 0x2a};
inline constexpr Color kJointColor{0x22, 0x25, 0x2e};
inline constexpr Color kGrabColor{0xd6, 0x1f, 0x69};
inline constexpr Color kLinkHaloColor = kBackgroundColor;

}  // namespace render
