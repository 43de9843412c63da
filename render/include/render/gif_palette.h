// A 256-colour palette for a GIF film and the mapping of RGB pictures onto it. Our pictures are
// flat colours (the background, each body's fill and outline) plus the anti-aliased blends at
// their edges, so the colours that cover most pixels get exact entries and a median cut shares
// the rest among the blends. No dithering: on flat colour it adds noise and defeats GIF's LZW.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "render/color.h"
#include "render/image.h"

namespace render {

inline constexpr int kGifPaletteSize = 256;

/// At most 256 distinct colours, in a deterministic order: `keep` first (in the order given,
/// duplicates dropped), then the picture's most common colours, then the median-cut means of
/// the rest. Every colour of `keep` and every colour that covers at least 1/2000 of the picture
/// is in it exactly (as long as there is room: 256 entries in all).
std::vector<Color> BuildGifPalette(const Image& picture, std::span<const Color> keep);

/// Maps pictures onto a palette: each colour to the nearest entry (squared RGB distance, the
/// first on a tie), so a colour of the palette maps to itself. Remembers the colours it has
/// seen, so one mapper per thread.
class PaletteMapper {
 public:
  explicit PaletteMapper(std::vector<Color> palette);
  /// Writes one index per pixel: row y at indices + y * stride.
  void Map(const Image& picture, std::uint8_t* indices, int stride);
  /// The index of the entry nearest to `c`.
  std::uint8_t Nearest(Color c);

 private:
  std::vector<Color> palette_;
  std::unordered_map<std::uint32_t, std::uint8_t> seen_;
};

}  // namespace render
