// The default palette: distinct, mid-saturation colours that read well on a light background.
#include "render/color.h"

namespace render {

Color PaletteColor(std::size_t index) {
  static constexpr Color kPalette[] = {
      {0xe4, 0x57, 0x2e}, {0x29, 0x80, 0xb9}, {0xf3, 0xa7, 0x12}, {0x27, 0xae, 0x60},
      {0x8e, 0x44, 0xad}, {0x16, 0xa0, 0x85}, {0xd3, 0x54, 0x7f}, {0x2c, 0x3e, 0x50},
  };
  return kPalette[index % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

}  // namespace render
