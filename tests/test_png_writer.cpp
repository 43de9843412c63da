// The PNG encoders: lossless RGB that stb_image decodes back exactly, the fast settings really
// in the file (filter "none" on every row, zlib's fastest level), and safe on several threads.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <future>
#include <string>
#include <vector>

#include "render/image.h"
#include "render/png_writer.h"

using render::PngEncoding;

namespace {

// Odd sizes, so rows are not multiples of 4 bytes; content with gradients, edges and noise.
render::Image TestImage(int width = 37, int height = 23) {
  render::Image image{width, height, {}};
  std::uint32_t noise = 12345;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      noise = noise * 1664525u + 1013904223u;
      image.rgb.push_back(static_cast<std::uint8_t>(x * 7));
      image.rgb.push_back(static_cast<std::uint8_t>(x + y > 30 ? 250 : 10));
      image.rgb.push_back(static_cast<std::uint8_t>(noise >> 24));
    }
  }
  return image;
}

std::vector<std::uint8_t> Decode(const std::vector<std::uint8_t>& png, int& w, int& h, int& n) {
  stbi_uc* pixels = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &n, 0);
  REQUIRE(pixels != nullptr);
  std::vector<std::uint8_t> out(pixels, pixels + static_cast<std::size_t>(w) * h * n);
  stbi_image_free(pixels);
  return out;
}

std::uint32_t BigEndian32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

struct PngParts {
  int color_type = -1;
  std::vector<std::uint8_t> zlib_stream;  // the IDAT chunks joined
};

PngParts Parse(const std::vector<std::uint8_t>& png) {
  static const std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  REQUIRE(png.size() > 8);
  REQUIRE(std::memcmp(png.data(), kSignature, 8) == 0);
  PngParts parts;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    const std::uint32_t length = BigEndian32(&png[at]);
    const std::string type(reinterpret_cast<const char*>(&png[at + 4]), 4);
    const std::uint8_t* data = &png[at + 8];
    if (type == "IHDR") parts.color_type = data[9];
    if (type == "IDAT") parts.zlib_stream.insert(parts.zlib_stream.end(), data, data + length);
    at += 12 + length;
  }
  return parts;
}

}  // namespace

TEST_CASE("png: both encodings give RGB files that decode to the same pixels", "[png]") {
  const render::Image image = TestImage();
  for (PngEncoding encoding : {PngEncoding::kFast, PngEncoding::kStbDefault}) {
    INFO("encoding " << static_cast<int>(encoding));
    const std::vector<std::uint8_t> png = render::EncodePng(image, encoding);
    CHECK(Parse(png).color_type == 2);  // truecolour, no alpha channel to wash colours out
    int w = 0, h = 0, n = 0;
    const std::vector<std::uint8_t> decoded = Decode(png, w, h, n);
    CHECK(w == image.width);
    CHECK(h == image.height);
    CHECK(n == 3);
    CHECK(decoded == image.rgb);
  }
}

TEST_CASE("png: the fast encoding uses filter none and zlib's fastest level", "[png]") {
  const render::Image image = TestImage();
  const PngParts parts = Parse(render::EncodePng(image, PngEncoding::kFast));
  REQUIRE(parts.zlib_stream.size() > 2);
  // zlib header: FLEVEL (the top two bits of the second byte) is 0 for the fastest levels.
  CHECK((parts.zlib_stream[1] >> 6) == 0);
  const std::size_t row_bytes = 1 + static_cast<std::size_t>(image.width) * 3;
  std::vector<std::uint8_t> raw(row_bytes * image.height);
  uLongf raw_size = raw.size();
  REQUIRE(uncompress(raw.data(), &raw_size, parts.zlib_stream.data(), parts.zlib_stream.size()) ==
          Z_OK);
  REQUIRE(raw_size == raw.size());
  for (int row = 0; row < image.height; ++row) {
    INFO("row " << row);
    CHECK(raw[row * row_bytes] == 0);  // the filter type byte: 0 = none
  }
  // With filter none the rows are the pixels themselves.
  CHECK(std::memcmp(&raw[1], image.rgb.data(), image.width * 3) == 0);
}

TEST_CASE("png: the stb default encoding is stb's own (filters chosen per row)", "[png]") {
  // A horizontal gradient: stb's per-row filter choice picks "sub" or better, never plain none.
  render::Image image{64, 8, {}};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) image.rgb.push_back(static_cast<std::uint8_t>(4 * x + c));
    }
  }
  const PngParts parts = Parse(render::EncodePng(image, PngEncoding::kStbDefault));
  const std::size_t row_bytes = 1 + static_cast<std::size_t>(image.width) * 3;
  std::vector<std::uint8_t> raw(row_bytes * image.height);
  uLongf raw_size = raw.size();
  REQUIRE(uncompress(raw.data(), &raw_size, parts.zlib_stream.data(), parts.zlib_stream.size()) ==
          Z_OK);
  CHECK(raw[0] != 0);
}

TEST_CASE("png: encoding is deterministic on several threads at once", "[png]") {
  const render::Image image = TestImage(301, 97);
  const std::vector<std::uint8_t> expected = render::EncodePng(image);
  std::vector<std::future<std::vector<std::uint8_t>>> results;
  for (int i = 0; i < 4; ++i) {
    results.push_back(std::async(std::launch::async, [&image] {
      std::vector<std::uint8_t> last;
      for (int k = 0; k < 10; ++k) last = render::EncodePng(image);
      return last;
    }));
  }
  for (auto& result : results) CHECK(result.get() == expected);
}
