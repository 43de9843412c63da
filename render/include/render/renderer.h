// Draws a world through a camera with OpenGL 3.3 core into an offscreen framebuffer and reads
// the picture back. Balls are anti-aliased discs (a spoke shows the angle when rotation is on),
// boxes filled rectangles, polygons (concave or rounded too) and capsules filled shapes, segment
// polylines bands of a few pixels; each body outlined once around all its parts. Springs and
// joints are thin lines over the bodies. No GL header here: the GL state lives in renderer.cpp,
// part_program.cpp and link_program.cpp.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"
#include "render/rect.h"

namespace render {

/// Which of the world's links (springs and joints) Renderer::Draw shows over the bodies.
struct LinkLayers {
  bool springs = true;
  bool joints = true;
};

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

  /// Draws every body in scene order (later bodies on top) over the background, then the
  /// springs and joints `links` selects over them; `colors[i]` is the colour of body i. A world
  /// with no springs or joints is drawn exactly as it was before links were drawn at all.
  /// Precondition: colors.size() == world.BodyCount().
  void Draw(const engine::World& world, std::span<const Color> colors, const Camera& camera,
            LinkLayers links = {});

  /// The last drawn picture, rows top-down; reuses `image`'s storage.
  void ReadImage(Image& image);

  /// Draws `width` × `height` pixel images from now on (the camera keeps its width in metres).
  /// False, with `error` set and the size unchanged, when GL does not allow that size.
  bool Resize(int width, int height, std::string& error);

  /// For a window: fills the context's default framebuffer (`framebuffer_width` ×
  /// `framebuffer_height`) with `border`, copies the last drawn picture into `picture`
  /// (scaled when the sizes differ), then fills `overlay` in order on top. The picture itself,
  /// and so ReadImage, never holds the overlay.
  void Present(int framebuffer_width, int framebuffer_height, const PixelRect& picture,
               std::span<const FilledRect> overlay, Color border);

 private:
  struct Gl;  // the function table and the GL objects
  explicit Renderer(std::unique_ptr<Gl> gl);
  // The bodies of a world with none made of parts, through the plain circle-and-box program.
  void DrawBodies(const engine::World& world, std::span<const Color> colors,
                  const Camera& camera);
  // Draw for a world with bodies made of parts: every body through the part program.
  void DrawWithParts(const engine::World& world, std::span<const Color> colors,
                     const Camera& camera);
  // The springs and joints over what the body pass drew.
  void DrawLinks(const engine::World& world, const Camera& camera, LinkLayers links);
  std::unique_ptr<Gl> gl_;
};

}  // namespace render
