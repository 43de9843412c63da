// stb's PNG encoder with its stock settings, called in Debian's libstb: the baseline the render
// benchmark measures the fast encoder against.
#include <stb/stb_image_write.h>

#include "render/png_writer.h"

namespace render {

std::vector<std::uint8_t> EncodePngStbDefault(const Image& image) {
  std::vector<std::uint8_t> png;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, image.rgb.data(),
                              image.width * 3)) {
    png.clear();
  }
  return png;
}

}  // namespace render
