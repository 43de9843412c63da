// Draws a world through a camera with OpenGL 3.3 core into an offscreen framebuffer and reads
// the picture back. Balls are anti-aliased discs (a spoke shows the angle when rotation is on),
// boxes filled rectangles; both outlined. No GL header here: the GL state lives in renderer.cpp.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"

namespace render {

class Renderer {
 public:
  /// A renderer drawing `width` × `height` pixel images. `context` must be current on this
  /// thread and outlive the renderer. Returns nullptr and sets `error` when the context lacks
  /// an entry point, a shader fails to build or the size exceeds what GL allows.
  static std::unique_ptr<Renderer> Create(const GlContext& context, int width, int height,
                                          std::string& error);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  int Width() const;
  int Height() const;
  /// What GL says it is, e.g. "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
  std::string Description() const;

  /// Draws every body in scene order (later bodies on top) over the background; `colors[i]` is
  /// the colour of body i. Precondition: colors.size() == world.BodyCount().
  void Draw(const engine::World& world, std::span<const Color> colors, const Camera& camera);

  /// The last drawn picture, rows top-down; reuses `image`'s storage.
  void ReadImage(Image& image);

 private:
  struct Gl;  // the function table and the GL objects
  explicit Renderer(std::unique_ptr<Gl> gl);
  std::unique_ptr<Gl> gl_;
};

}  // namespace render
