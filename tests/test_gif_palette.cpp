// The GIF palette (render/gif_palette.h): exact for the colours that matter, at most 256
// entries, deterministic, and each colour mapped to its nearest entry.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/gif_palette.h"

using render::Color;

namespace {

render::Image Picture(int width, int height, const std::vector<Color>& pixels) {
  render::Image image{width, height, {}};
  for (const Color& c : pixels) image.rgb.insert(image.rgb.end(), {c.r, c.g, c.b});
  return image;
}

// A gradient of 64 × 64 distinct colours, with a large flat patch of one colour.
render::Image ManyColours() {
  std::vector<Color> pixels;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool patch = x < 32 && y < 32;
      pixels.push_back(patch ? Color{10, 200, 30}
                             : Color{static_cast<std::uint8_t>(4 * x), static_cast<std::uint8_t>(4 * y),
                                     static_cast<std::uint8_t>(255 - 2 * x)});
    }
  }
  return Picture(64, 64, pixels);
}

int Distance(Color a, Color b) {
  const int dr = a.r - b.r, dg = a.g - b.g, db = a.b - b.b;
  return dr * dr + dg * dg + db * db;
}

}  // namespace

TEST_CASE("gif palette: a picture of a few colours gets each exactly, and maps onto itself", "[gif]") {
  const std::vector<Color> colours = {{244, 241, 234}, {74, 79, 88}, {228, 87, 46}, {0, 0, 0}};
  std::vector<Color> pixels;
  for (int i = 0; i < 40; ++i) pixels.push_back(colours[i % 4]);
  const render::Image image = Picture(8, 5, pixels);
  const std::vector<Color> palette = render::BuildGifPalette(image, {});
  CHECK(palette.size() == 4);
  for (Color c : colours) CHECK(std::find(palette.begin(), palette.end(), c) != palette.end());
  render::PaletteMapper mapper(palette);
  std::vector<std::uint8_t> indices(40);
  mapper.Map(image, indices.data(), 8);
  for (std::size_t i = 0; i < 40; ++i) CHECK(palette[indices[i]] == pixels[i]);
}

TEST_CASE("gif palette: kept colours first, common colours exact, never more than 256", "[gif]") {
  const render::Image image = ManyColours();  // 3073 distinct colours
  const std::vector<Color> keep = {{1, 2, 3}, {250, 250, 250}, {1, 2, 3}};
  const std::vector<Color> palette = render::BuildGifPalette(image, keep);
  CHECK(palette.size() == 256);
  CHECK(palette[0] == Color{1, 2, 3});
  CHECK(palette[1] == Color{250, 250, 250});  // the duplicate dropped
  CHECK(palette[2] == Color{10, 200, 30});    // a quarter of the picture: exact, next
  for (std::size_t i = 0; i < palette.size(); ++i) {
    for (std::size_t j = i + 1; j < palette.size(); ++j) CHECK_FALSE(palette[i] == palette[j]);
  }
  CHECK(render::BuildGifPalette(image, keep) == palette);  // deterministic
}

TEST_CASE("gif palette: every colour maps to its nearest entry, and a good palette keeps them close",
          "[gif]") {
  const render::Image image = ManyColours();
  const std::vector<Color> palette = render::BuildGifPalette(image, {});
  render::PaletteMapper mapper(palette);
  std::vector<std::uint8_t> indices(64 * 64);
  mapper.Map(image, indices.data(), 64);
  double total = 0.0;
  for (int i = 0; i < 64 * 64; ++i) {
    const Color c = image.At(i % 64, i / 64);
    int best = 1 << 30;
    for (Color p : palette) best = std::min(best, Distance(c, p));
    CHECK(Distance(c, palette[indices[i]]) == best);  // brute force agrees
    total += best;
  }
  // 3072 gradient colours on a 4-level grid in 255 entries: about 12 colours an entry, so a
  // median cut's boxes span a few grid steps and the error stays within 4 levels a channel
  // (28 measured; a cut that left big boxes unsplit would exceed this).
  INFO("mean squared distance " << total / (64 * 64));
  CHECK(total / (64 * 64) < 3 * 4.0 * 4.0);
}
