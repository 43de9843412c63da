// The offscreen GL context through OSMesa (Mesa's software renderer, llvmpipe): no display needed.
// <GL/osmesa.h> drags in <GL/gl.h>, which is why this backend stays out of every other file.
#include <GL/osmesa.h>

#include "render/context.h"

namespace render {
namespace {

class OsMesaContext final : public GlContext {
 public:
  explicit OsMesaContext(OSMesaContext context) : context_(context) {}
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  bool MakeCurrent() {
    // The renderer draws into its own framebuffer object; OSMesa still wants a buffer to bind.
    return OSMesaMakeCurrent(context_, token_buffer_, GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE;
  }

  GlProc GetProcAddress(const char* name) const override {
    return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
  }

 private:
  OSMesaContext context_;
  unsigned char token_buffer_[4] = {};
};

}  // namespace

std::unique_ptr<GlContext> CreateOffscreenContext(std::string& error) {
  const int attributes[] = {
      OSMESA_FORMAT, OSMESA_RGBA,
      OSMESA_DEPTH_BITS, 0,
      OSMESA_STENCIL_BITS, 0,
      OSMESA_ACCUM_BITS, 0,
      OSMESA_PROFILE, OSMESA_CORE_PROFILE,
      OSMESA_CONTEXT_MAJOR_VERSION, 3,
      OSMESA_CONTEXT_MINOR_VERSION, 3,
      0,
  };
  OSMesaContext raw = OSMesaCreateContextAttribs(attributes, nullptr);
  if (raw == nullptr) {
    error = "OSMesa could not create an OpenGL 3.3 core context";
    return nullptr;
  }
  auto context = std::make_unique<OsMesaContext>(raw);
  if (!context->MakeCurrent()) {
    error = "OSMesa could not make its OpenGL context current";
    return nullptr;
  }
  return context;
}

}  // namespace render
