// Draws a world through a camera with OpenGL 3.3 core into an offscreen framebuffer and reads
// the picture back. Balls are anti-aliased discs (a spoke shows the angle when rotation is on),
// boxes filled rectangles, polygons (concave or rounded too) and capsules filled shapes, segment
// polylines bands of a few pixels; each body outlined once around all its parts. Soft bodies are
// filled and outlined the same way over the rigid bodies, fluid a liquid surface over both,
// springs and joints thin lines over that, and effect particles soft sprites over everything
// (docs/rendering.md). No GL header here: the GL state lives in renderer.cpp and the
// *_program.cpp and fluid_surface.cpp files.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"
#include "render/particle_style.h"
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

  /// Draws every body in scene order (later bodies on top) over the background, the soft
  /// bodies in slot order over them, the fluid over those, then the springs and joints `links`
  /// selects, then the effect particles (DrawEffects with world.Effects()). `colors[i]` is the
  /// colour of body i; `particles` colours the soft bodies and the fluid. A world with no
  /// springs, joints or particles is drawn exactly as it was before those were drawn at all.
  /// Precondition: colors.size() == world.BodyCount().
  void Draw(const engine::World& world, std::span<const Color> colors, const Camera& camera,
            LinkLayers links = {}, const ParticleStyle& particles = {});

  /// Draws `effects` as soft round sprites over the last drawn picture, each sized and
  /// coloured by its emitter in `world` at its age: the alpha-blended ones (smoke) first,
  /// the additive ones (fire, sparks) over them. A particle whose emitter has been destroyed
  /// is not drawn. Draw ends with this for world.Effects(); a tool or test may hand its own.
  void DrawEffects(const engine::World& world, std::span<const engine::EffectParticle> effects,
                   const Camera& camera);

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
  // The soft bodies and the fluid over what the body pass drew.
  void DrawParticleBodies(const engine::World& world, const Camera& camera,
                          const ParticleStyle& style);
  // The springs and joints over what the body pass drew.
  void DrawLinks(const engine::World& world, const Camera& camera, LinkLayers links);
  std::unique_ptr<Gl> gl_;
};

}  // namespace render
