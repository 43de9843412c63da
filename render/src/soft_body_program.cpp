// The soft body shader: the distance to the outline comes interpolated from the vertices (see
// soft_body_mesh.h), so the fragment shader is the body shaders' shading alone.
#include "soft_body_program.h"

#include <cstddef>

#include "shader_build.h"

namespace render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 position;  // m, relative to the camera centre
layout(location = 1) in float edge_distance_in;
layout(location = 2) in float outline_width_in;
layout(location = 3) in vec4 color;

uniform vec2 view_half_size;  // m

out float edge_distance;  // m, negative inside
flat out float outline_width;
flat out vec3 fill;

void main() {
  gl_Position = vec4(position / view_half_size, 0.0, 1.0);
  edge_distance = edge_distance_in;
  outline_width = outline_width_in;
  fill = color.rgb;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in float edge_distance;
flat in float outline_width;
flat in vec3 fill;

uniform float pixel_size;  // m per pixel

out vec4 frag_color;

const float kOutlineShade = 0.55;  // the outline is the fill, darker, as the bodies'

void main() {
  float d = edge_distance;
  // Coverage ramps across one pixel at the edge: anti-aliasing with no multisampling.
  float coverage = clamp(0.5 - d / pixel_size, 0.0, 1.0);
  if (coverage == 0.0) discard;
  vec3 color = mix(fill, kOutlineShade * fill,
                   clamp(0.5 + (d + outline_width) / pixel_size, 0.0, 1.0));
  frag_color = vec4(color, coverage);
}
)";

void SetVertexAttribute(const GlFunctions& fn, GLuint location, GLint size, GLenum type,
                        GLboolean normalized, std::size_t offset) {
  fn.EnableVertexAttribArray(location);
  fn.VertexAttribPointer(location, size, type, normalized, sizeof(SoftBodyVertex),
                         reinterpret_cast<const void*>(offset));
}

}  // namespace

bool SoftBodyProgram::Create(const GlFunctions& fn, std::string& error) {
  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "soft body", program_, error)) return false;
  view_half_size_location_ = fn.GetUniformLocation(program_, "view_half_size");
  pixel_size_location_ = fn.GetUniformLocation(program_, "pixel_size");
  fn.GenVertexArrays(1, &vertex_array_);
  fn.BindVertexArray(vertex_array_);
  fn.GenBuffers(1, &vertex_buffer_);
  fn.BindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  SetVertexAttribute(fn, 0, 2, GL_FLOAT, GL_FALSE, offsetof(SoftBodyVertex, position));
  SetVertexAttribute(fn, 1, 1, GL_FLOAT, GL_FALSE, offsetof(SoftBodyVertex, edge_distance));
  SetVertexAttribute(fn, 2, 1, GL_FLOAT, GL_FALSE, offsetof(SoftBodyVertex, outline_width));
  // Normalised bytes reach the shader as exactly c / 255: the fill is the style's colour exactly.
  SetVertexAttribute(fn, 3, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(SoftBodyVertex, color));
  return true;
}

void SoftBodyProgram::Destroy(const GlFunctions& fn) {
  fn.DeleteProgram(program_);
  fn.DeleteBuffers(1, &vertex_buffer_);
  fn.DeleteVertexArrays(1, &vertex_array_);
}

void SoftBodyProgram::Draw(const GlFunctions& fn, const SoftBodyMesh& mesh, float view_half_width,
                           float view_half_height, float pixel_size) {
  const std::vector<SoftBodyVertex>& vertices = mesh.Vertices();
  if (vertices.empty()) return;
  fn.UseProgram(program_);
  fn.Uniform2f(view_half_size_location_, view_half_width, view_half_height);
  fn.Uniform1f(pixel_size_location_, pixel_size);
  fn.BindVertexArray(vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  fn.BufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(SoftBodyVertex), vertices.data(),
                GL_STREAM_DRAW);
  fn.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
}

}  // namespace render
