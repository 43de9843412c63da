// The liquid: a field summed from the particles' kernels (the "metaball" idea; with the kernel
// of Müller, Charypar and Gross 2003's poly6, (1 − r²/R²)³, smooth where it reaches 0), then
// thresholded. The field is 16-bit float: GL 3.3 must render and blend into R16F, and half
// precision resolves the threshold to a thousandth of the field's inside value.
#include "fluid_surface.h"

#include <algorithm>
#include <cmath>

#include "shader_build.h"

namespace render {
namespace {

// One instance of the splat pass: a particle's centre (centers_ holds them as float pairs).
struct SplatCenter {
  float x, y;
};

constexpr const char* kSplatVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 center;

uniform vec2 view_half_size;  // m
uniform float radius;         // m: the kernel's reach

out vec2 local;  // in kernel radii from the particle

void main() {
  local = corner;
  gl_Position = vec4((center + corner * radius) / view_half_size, 0.0, 1.0);
}
)";

constexpr const char* kSplatFragmentShader = R"(#version 330 core
in vec2 local;

uniform float amplitude;

out vec4 value;

void main() {
  float q = dot(local, local);
  if (q >= 1.0) discard;
  float w = 1.0 - q;
  value = vec4(amplitude * w * w * w, 0.0, 0.0, 0.0);
}
)";

constexpr const char* kShadeVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;

uniform vec4 rect;  // the fluid's box: centre and half size, in clip coordinates

void main() { gl_Position = vec4(rect.xy + corner * rect.zw, 0.0, 1.0); }
)";

constexpr const char* kShadeFragmentShader = R"(#version 330 core
uniform sampler2D field;
uniform float threshold;
uniform vec4 liquid;  // colour and opacity
uniform vec3 rim;
uniform float rim_pixels;

out vec4 frag_color;

float At(ivec2 p) {
  return texelFetch(field, clamp(p, ivec2(0), textureSize(field, 0) - 1), 0).r;
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float f = At(p);
  // The field's slope per pixel by central differences: the height above the threshold over
  // it is how many pixels inside the surface this pixel lies, wherever it is near.
  vec2 slope = 0.5 * vec2(At(p + ivec2(1, 0)) - At(p - ivec2(1, 0)),
                          At(p + ivec2(0, 1)) - At(p - ivec2(0, 1)));
  float depth = (f - threshold) / max(length(slope), 1e-6);
  float coverage = smoothstep(-0.75, 0.75, depth);
  if (coverage == 0.0) discard;
  vec3 color = mix(rim, liquid.rgb, smoothstep(0.5 * rim_pixels, 1.5 * rim_pixels, depth));
  frag_color = vec4(color, liquid.a * coverage);
}
)";

// The usual blending: straight alpha over, the framebuffer's alpha kept opaque.
void BlendOver(const GlFunctions& fn) {
  fn.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

}  // namespace

bool FluidSurface::Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error) {
  if (!BuildProgram(fn, kSplatVertexShader, kSplatFragmentShader, "fluid splat", splat_program_,
                    error) ||
      !BuildProgram(fn, kShadeVertexShader, kShadeFragmentShader, "fluid surface",
                    shade_program_, error)) {
    return false;
  }
  splat_view_half_size_location_ = fn.GetUniformLocation(splat_program_, "view_half_size");
  splat_radius_location_ = fn.GetUniformLocation(splat_program_, "radius");
  splat_amplitude_location_ = fn.GetUniformLocation(splat_program_, "amplitude");
  shade_rect_location_ = fn.GetUniformLocation(shade_program_, "rect");
  shade_threshold_location_ = fn.GetUniformLocation(shade_program_, "threshold");
  shade_liquid_location_ = fn.GetUniformLocation(shade_program_, "liquid");
  shade_rim_location_ = fn.GetUniformLocation(shade_program_, "rim");
  fn.UseProgram(shade_program_);
  fn.Uniform1i(fn.GetUniformLocation(shade_program_, "field"), 0);  // texture unit 0
  fn.Uniform1f(fn.GetUniformLocation(shade_program_, "rim_pixels"),
               static_cast<float>(kFluidRimPixels));

  NewInstancedQuad(fn, quad_buffer, splat_vertex_array_, instance_buffer_);
  SetInstanceAttribute<SplatCenter>(fn, 1, 2, GL_FLOAT, GL_FALSE, 0);
  shade_vertex_array_ = NewQuadArray(fn, quad_buffer);

  fn.GenTextures(1, &field_texture_);
  fn.GenFramebuffers(1, &field_framebuffer_);
  // A one-pixel field now proves the format renderable; the real one is made at the first draw
  // with fluid, so pictures without fluid cost no memory for it.
  if (!FitField(fn, 1, 1)) {
    error = "this OpenGL cannot render into a 16-bit float texture (R16F), which fluid needs";
    return false;
  }
  return true;
}

void FluidSurface::Destroy(const GlFunctions& fn) {
  fn.DeleteProgram(splat_program_);
  fn.DeleteProgram(shade_program_);
  fn.DeleteBuffers(1, &instance_buffer_);
  fn.DeleteVertexArrays(1, &splat_vertex_array_);
  fn.DeleteVertexArrays(1, &shade_vertex_array_);
  fn.DeleteFramebuffers(1, &field_framebuffer_);
  fn.DeleteTextures(1, &field_texture_);
}

bool FluidSurface::FitField(const GlFunctions& fn, int width, int height) {
  if (width == field_width_ && height == field_height_) return true;
  fn.BindTexture(GL_TEXTURE_2D, field_texture_);
  fn.TexImage2D(GL_TEXTURE_2D, 0, GL_R16F, width, height, 0, GL_RED, GL_FLOAT, nullptr);
  // texelFetch needs a complete texture: one level, so no mipmapped filter.
  fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  fn.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  fn.BindFramebuffer(GL_FRAMEBUFFER, field_framebuffer_);
  fn.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, field_texture_, 0);
  const bool ok = fn.GetError() == GL_NO_ERROR &&
                  fn.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  field_width_ = ok ? width : 0;
  field_height_ = ok ? height : 0;
  return ok;
}

FluidSurface::PixelBox FluidSurface::Collect(const engine::World& world, const Camera& camera,
                                             double kernel, double pixel_size, int width,
                                             int height) {
  centers_.clear();
  // The kernel's reach in pixels, and a pixel more for the shading's neighbour reads.
  const double reach = kernel / pixel_size + 2.0;
  double low_x = width, low_y = height, high_x = 0.0, high_y = 0.0;
  for (const engine::Vec2 p : world.FluidPositions()) {
    const double x = p.x - camera.center.x;
    const double y = p.y - camera.center.y;
    const double px = x / pixel_size + 0.5 * width;  // from the left, as GL counts
    const double py = y / pixel_size + 0.5 * height;  // from the bottom
    if (px + reach < 0.0 || px - reach > width || py + reach < 0.0 || py - reach > height) continue;
    centers_.push_back(static_cast<float>(x));
    centers_.push_back(static_cast<float>(y));
    low_x = std::min(low_x, px - reach);
    low_y = std::min(low_y, py - reach);
    high_x = std::max(high_x, px + reach);
    high_y = std::max(high_y, py + reach);
  }
  if (centers_.empty()) return {};
  return {std::max(0, static_cast<int>(std::floor(low_x))),
          std::max(0, static_cast<int>(std::floor(low_y))),
          std::min(width, static_cast<int>(std::ceil(high_x))),
          std::min(height, static_cast<int>(std::ceil(high_y)))};
}

void FluidSurface::Draw(const GlFunctions& fn, const engine::World& world,
                        const ParticleStyle& style, const Camera& camera, GLuint target,
                        int width, int height) {
  const double spacing = world.FluidSpacing();
  if (world.FluidPositions().empty() || !(spacing > 0.0)) return;
  const double pixel_size = camera.width / width;
  const double radius = kFluidKernelSpacings * spacing;
  const double kernel = std::max(radius, kFluidMinKernelPixels * pixel_size);
  const PixelBox box = Collect(world, camera, kernel, pixel_size, width, height);
  if (box.x1 <= box.x0 || box.y1 <= box.y0) return;
  // A field the picture's size cannot be had (out of memory): no liquid rather than garbage.
  if (!FitField(fn, width, height)) {
    fn.BindFramebuffer(GL_FRAMEBUFFER, target);
    return;
  }
  const double drop = kFluidDropSpacings / kFluidKernelSpacings;
  const double threshold = std::pow(1.0 - drop * drop, 3.0);
  // The same integral as the kernel of `radius` when it is widened.
  const double amplitude = (radius / kernel) * (radius / kernel);
  fn.Enable(GL_SCISSOR_TEST);
  Splat(fn, box, width, height, static_cast<float>(0.5 * camera.width),
        static_cast<float>(0.5 * pixel_size * height), kernel, amplitude);
  fn.BindFramebuffer(GL_FRAMEBUFFER, target);
  fn.Scissor(box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0);
  Shade(fn, style, box, threshold, width, height);
  fn.Disable(GL_SCISSOR_TEST);
}

void FluidSurface::Splat(const GlFunctions& fn, const PixelBox& box, int width, int height,
                         float view_half_width, float view_half_height, double kernel,
                         double amplitude) {
  // Only the fluid's box is cleared and drawn, and a pixel round it, which the shading reads
  // as neighbours: the rest of the field may hold an earlier picture's fluid.
  const int x0 = std::max(box.x0 - 1, 0);
  const int y0 = std::max(box.y0 - 1, 0);
  fn.Scissor(x0, y0, std::min(box.x1 + 1, width) - x0, std::min(box.y1 + 1, height) - y0);
  fn.BindFramebuffer(GL_FRAMEBUFFER, field_framebuffer_);
  fn.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  fn.Clear(GL_COLOR_BUFFER_BIT);
  fn.BlendFuncSeparate(GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  fn.UseProgram(splat_program_);
  fn.Uniform2f(splat_view_half_size_location_, view_half_width, view_half_height);
  fn.Uniform1f(splat_radius_location_, static_cast<float>(kernel));
  fn.Uniform1f(splat_amplitude_location_, static_cast<float>(amplitude));
  fn.BindVertexArray(splat_vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  fn.BufferData(GL_ARRAY_BUFFER, centers_.size() * sizeof(float), centers_.data(), GL_STREAM_DRAW);
  fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(centers_.size() / 2));
}

void FluidSurface::Shade(const GlFunctions& fn, const ParticleStyle& style, const PixelBox& box,
                         double threshold, int width, int height) {
  BlendOver(fn);
  fn.UseProgram(shade_program_);
  // The box in clip coordinates (−1 to 1 across the picture).
  const double half_x = static_cast<double>(box.x1 - box.x0) / width;
  const double half_y = static_cast<double>(box.y1 - box.y0) / height;
  fn.Uniform4f(shade_rect_location_, static_cast<float>(2.0 * box.x0 / width - 1.0 + half_x),
               static_cast<float>(2.0 * box.y0 / height - 1.0 + half_y),
               static_cast<float>(half_x), static_cast<float>(half_y));
  fn.Uniform1f(shade_threshold_location_, static_cast<float>(threshold));
  const Color c = style.fluid;
  fn.Uniform4f(shade_liquid_location_, c.r / 255.0f, c.g / 255.0f, c.b / 255.0f,
               std::clamp(style.fluid_opacity, 0.0f, 1.0f));
  auto lighten = [](std::uint8_t v) {
    return static_cast<float>((v + kFluidRimLightening * (255.0 - v)) / 255.0);
  };
  fn.Uniform3f(shade_rim_location_, lighten(c.r), lighten(c.g), lighten(c.b));
  fn.ActiveTexture(GL_TEXTURE0);
  fn.BindTexture(GL_TEXTURE_2D, field_texture_);
  fn.BindVertexArray(shade_vertex_array_);
  fn.DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

}  // namespace render
