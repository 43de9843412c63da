// The link shader: a capsule's signed distance (a dot is a capsule of no length), coverage
// ramped over one pixel as the body shaders do, no multisampling.
#include "link_program.h"

#include <cstddef>

#include "shader_build.h"

namespace render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 a_in;
layout(location = 2) in vec2 b_in;
layout(location = 3) in float radius_in;
layout(location = 4) in vec4 color_in;

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel
uniform float grow;           // m added to every radius (the rim pass)

out vec2 point;  // m, relative to the camera centre
flat out vec2 a;
flat out vec2 b;
flat out float radius;
flat out vec3 color;

void main() {
  radius = radius_in + grow;
  vec2 ab = b_in - a_in;
  float length_ab = length(ab);
  vec2 axis = length_ab > 0.0 ? ab / length_ab : vec2(1.0, 0.0);
  // Two pixels beyond the capsule leave room for its anti-aliased edge.
  vec2 half_size = vec2(0.5 * length_ab, 0.0) + vec2(radius + 2.0 * pixel_size);
  vec2 local = corner * half_size;
  point = 0.5 * (a_in + b_in) + axis * local.x + vec2(-axis.y, axis.x) * local.y;
  gl_Position = vec4(point / view_half_size, 0.0, 1.0);
  a = a_in;
  b = b_in;
  color = color_in.rgb;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 point;
flat in vec2 a;
flat in vec2 b;
flat in float radius;
flat in vec3 color;

uniform float pixel_size;  // m per pixel
uniform bool halo;
uniform vec3 halo_color;

out vec4 frag_color;

void main() {
  vec2 ab = b - a;
  vec2 ap = point - a;
  float t = clamp(dot(ap, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
  float d = length(ap - t * ab) - radius;
  float coverage = clamp(0.5 - d / pixel_size, 0.0, 1.0);
  if (coverage == 0.0) discard;
  frag_color = vec4(halo ? halo_color : color, coverage);
}
)";

}  // namespace

bool LinkProgram::Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error) {
  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "link", program_, error)) return false;
  view_half_size_location_ = fn.GetUniformLocation(program_, "view_half_size");
  pixel_size_location_ = fn.GetUniformLocation(program_, "pixel_size");
  grow_location_ = fn.GetUniformLocation(program_, "grow");
  halo_location_ = fn.GetUniformLocation(program_, "halo");
  halo_color_location_ = fn.GetUniformLocation(program_, "halo_color");

  NewInstancedQuad(fn, quad_buffer, vertex_array_, instance_buffer_);
  SetInstanceAttribute<LinkInstance>(fn, 1, 2, GL_FLOAT, GL_FALSE, offsetof(LinkInstance, a));
  SetInstanceAttribute<LinkInstance>(fn, 2, 2, GL_FLOAT, GL_FALSE, offsetof(LinkInstance, b));
  SetInstanceAttribute<LinkInstance>(fn, 3, 1, GL_FLOAT, GL_FALSE, offsetof(LinkInstance, radius));
  // Normalised bytes reach the shader as exactly c / 255: lines are their colour exactly.
  SetInstanceAttribute<LinkInstance>(fn, 4, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(LinkInstance, color));
  return true;
}

void LinkProgram::Destroy(const GlFunctions& fn) {
  fn.DeleteProgram(program_);
  fn.DeleteBuffers(1, &instance_buffer_);
  fn.DeleteVertexArrays(1, &vertex_array_);
}

void LinkProgram::Draw(const GlFunctions& fn, const LinkLines& lines, float view_half_width,
                       float view_half_height, float pixel_size) {
  const std::vector<LinkInstance>& instances = lines.Instances();
  if (instances.empty()) return;
  fn.UseProgram(program_);
  fn.Uniform2f(view_half_size_location_, view_half_width, view_half_height);
  fn.Uniform1f(pixel_size_location_, pixel_size);
  fn.BindVertexArray(vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  fn.BufferData(GL_ARRAY_BUFFER, instances.size() * sizeof(LinkInstance), instances.data(),
                GL_STREAM_DRAW);
  const auto count = static_cast<GLsizei>(instances.size());
  // Every rim first, then every line over them: a later segment's rim never covers an earlier
  // segment's line where the two meet.
  fn.Uniform1i(halo_location_, 1);
  fn.Uniform1f(grow_location_, static_cast<float>(kLinkHaloPixels * pixel_size));
  fn.Uniform3f(halo_color_location_, kLinkHaloColor.r / 255.0f, kLinkHaloColor.g / 255.0f,
               kLinkHaloColor.b / 255.0f);
  fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
  fn.Uniform1i(halo_location_, 0);
  fn.Uniform1f(grow_location_, 0.0f);
  fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, count);
}

}  // namespace render
