// Fluid as a liquid surface, not dots: every particle adds a smooth bump (a kernel) to a field
// in an offscreen floating-point texture the size of the picture, then one pass over the
// fluid's bounding box colours the pixels where the field is above a threshold, with an edge
// anti-aliased over about a pixel and a lighter rim just inside it. Drawn over the bodies, so
// a body in the liquid looks submerged.
#pragma once

#include <string>
#include <vector>

#include "engine/world.h"
#include "gl_functions.h"
#include "render/camera.h"
#include "render/particle_style.h"

namespace render {

/// The kernel reaches this many spacings. On a square lattice at the fluid's spacing the field
/// then lies between 1.95 and 2.08 everywhere inside (no holes, no ripples).
inline constexpr double kFluidKernelSpacings = 1.6;
/// A lone particle (a drop flung off the surface) shows as a disc of this many spacings'
/// radius: the threshold is the kernel's value there, 0.735, 37% of the inside value, which
/// puts a resting block's surface 0.16 to 0.19 spacings beyond where its region ended. (At
/// half the inside value it would sit exactly there, but a lone drop would vanish.)
inline constexpr double kFluidDropSpacings = 0.5;
/// When the camera is so far out that the kernel would shrink below this many pixels, it is
/// widened to it (its height cut to keep its integral), so the surface stays solid.
inline constexpr double kFluidMinKernelPixels = 1.5;
/// The lighter rim inside the surface: how wide, and how far towards white.
inline constexpr double kFluidRimPixels = 2.0;
inline constexpr double kFluidRimLightening = 0.35;

class FluidSurface {
 public:
  /// Builds the programs and buffers (the unit quad comes from `quad_buffer`) and checks that
  /// this GL can render into the field's format. False with `error` set when something fails.
  bool Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error);
  /// Frees what Create and Draw made (GL ignores names never made).
  void Destroy(const GlFunctions& fn);

  /// Draws the world's fluid over `target` (`width` × `height`, the picture), coloured by
  /// `style`; leaves `target` bound with the usual alpha blending. Nothing, not even a state
  /// change, for a world with no fluid in view.
  void Draw(const GlFunctions& fn, const engine::World& world, const ParticleStyle& style,
            const Camera& camera, GLuint target, int width, int height);

 private:
  // Pixels [x0, x1) × [y0, y1), counted from the bottom as GL does.
  struct PixelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };

  // The particles in view as camera-relative centres, and the pixels their kernels reach.
  PixelBox Collect(const engine::World& world, const Camera& camera, double kernel,
                   double pixel_size, int width, int height);
  // Makes the field texture width × height; false when GL cannot.
  bool FitField(const GlFunctions& fn, int width, int height);
  void Splat(const GlFunctions& fn, const PixelBox& box, int width, int height,
             float view_half_width, float view_half_height, double kernel, double amplitude);
  void Shade(const GlFunctions& fn, const ParticleStyle& style, const PixelBox& box,
             double threshold, int width, int height);

  GLuint splat_program_ = 0;
  GLint splat_view_half_size_location_ = -1;
  GLint splat_radius_location_ = -1;
  GLint splat_amplitude_location_ = -1;
  GLuint shade_program_ = 0;
  GLint shade_rect_location_ = -1;
  GLint shade_threshold_location_ = -1;
  GLint shade_liquid_location_ = -1;
  GLint shade_rim_location_ = -1;
  GLuint splat_vertex_array_ = 0;
  GLuint shade_vertex_array_ = 0;
  GLuint instance_buffer_ = 0;
  GLuint field_texture_ = 0;
  GLuint field_framebuffer_ = 0;
  int field_width_ = 0;
  int field_height_ = 0;
  std::vector<float> centers_;  // x, y per particle in view, m relative to the camera centre
};

}  // namespace render
