// The sprite shader: alpha falls from the centre to the rim as (1 − r²)², which is 1 with a
// flat top at the centre (a sprite's centre shows its colour exactly) and reaches 0 with a
// flat foot at the rim, so sprites need no anti-aliased edge.
#include "sprite_program.h"

#include <cstddef>

#include "shader_build.h"

namespace render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 center;
layout(location = 2) in float radius;
layout(location = 3) in vec4 color_in;

uniform vec2 view_half_size;  // m

out vec2 local;  // in radii from the centre
flat out vec4 color;

void main() {
  local = corner;
  gl_Position = vec4((center + corner * radius) / view_half_size, 0.0, 1.0);
  color = color_in;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 local;
flat in vec4 color;

out vec4 frag_color;

void main() {
  float r2 = dot(local, local);
  if (r2 >= 1.0) discard;
  float falloff = (1.0 - r2) * (1.0 - r2);
  frag_color = vec4(color.rgb, color.a * falloff);
}
)";

}  // namespace

bool SpriteProgram::Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error) {
  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "sprite", program_, error)) return false;
  view_half_size_location_ = fn.GetUniformLocation(program_, "view_half_size");
  NewInstancedQuad(fn, quad_buffer, vertex_array_, instance_buffer_);
  SetInstanceAttribute<SpriteInstance>(fn, 1, 2, GL_FLOAT, GL_FALSE, offsetof(SpriteInstance, center));
  SetInstanceAttribute<SpriteInstance>(fn, 2, 1, GL_FLOAT, GL_FALSE, offsetof(SpriteInstance, radius));
  SetInstanceAttribute<SpriteInstance>(fn, 3, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(SpriteInstance, color));
  return true;
}

void SpriteProgram::Destroy(const GlFunctions& fn) {
  fn.DeleteProgram(program_);
  fn.DeleteBuffers(1, &instance_buffer_);
  fn.DeleteVertexArrays(1, &vertex_array_);
}

void SpriteProgram::Draw(const GlFunctions& fn, const ParticleSprites& sprites,
                         float view_half_width, float view_half_height) {
  if (sprites.Alpha().empty() && sprites.Additive().empty()) return;
  fn.UseProgram(program_);
  fn.Uniform2f(view_half_size_location_, view_half_width, view_half_height);
  fn.BindVertexArray(vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  // Smoke covers what is behind it by its alpha; the framebuffer's own alpha stays opaque.
  fn.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  DrawGroup(fn, sprites.Alpha());
  // Light adds up (fire, sparks): colour × alpha onto what is there, the alpha untouched. The
  // additive sprites go last, so smoke never dims a flame's glow.
  fn.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE, GL_ZERO, GL_ONE);
  DrawGroup(fn, sprites.Additive());
  fn.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

void SpriteProgram::DrawGroup(const GlFunctions& fn, const std::vector<SpriteInstance>& group) {
  if (group.empty()) return;
  // GL 3.3 has no base instance, so each group is uploaded on its own (the buffer orphaned).
  fn.BufferData(GL_ARRAY_BUFFER, group.size() * sizeof(SpriteInstance), group.data(),
                GL_STREAM_DRAW);
  fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(group.size()));
}

}  // namespace render
