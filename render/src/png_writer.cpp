// The fast PNG encoder: a private copy of stb_image_write from Debian's libstb (static, so it
// cannot clash with the library's), with zlib's deflate at level 1 in place of stb's own.
#include "render/png_writer.h"

#include <zlib.h>

#include <cstdlib>

namespace {

// stb's hook for a zlib-style compressor: it frees the result with STBIW_FREE (free).
unsigned char* ZlibCompress(unsigned char* data, int length, int* out_length, int /*quality*/) {
  uLongf capacity = compressBound(static_cast<uLong>(length));
  auto* out = static_cast<unsigned char*>(std::malloc(capacity));
  if (out == nullptr) return nullptr;
  // Level 1 is the fastest, and flat-coloured frames leave little for higher levels to gain.
  if (compress2(out, &capacity, data, static_cast<uLong>(length), 1) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *out_length = static_cast<int>(capacity);
  return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS ZlibCompress
#define STBI_WRITE_NO_STDIO
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace render {

// Defined in png_stb_default.cpp, which calls Debian's libstb with its stock settings.
std::vector<std::uint8_t> EncodePngStbDefault(const Image& image);

namespace {

void AppendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> EncodePng(const Image& image, PngEncoding encoding) {
  if (encoding == PngEncoding::kStbDefault) return EncodePngStbDefault(image);
  // stb reads the filter choice from a global of this copy: set it once, before any thread
  // encodes (a function-local static is initialised exactly once, thread-safely).
  static const bool filter_none = [] {
    stbi_write_force_png_filter = 0;
    return true;
  }();
  (void)filter_none;
  std::vector<std::uint8_t> png;
  if (!stbi_write_png_to_func(AppendBytes, &png, image.width, image.height, 3, image.rgb.data(),
                              image.width * 3)) {
    png.clear();
  }
  return png;
}

}  // namespace render
