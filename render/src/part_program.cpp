// The part shader: each instance is a quad over one primitive; its fragments find the distance to
// the primitive (circle, capsule, or any simple polygon, rounded or not) and to its neighbours in
// the same body, keep the pixels where their own primitive is the nearest, and shade the distance
// to that union exactly as the plain shader shades circles and boxes.
#include "part_program.h"

#include <algorithm>
#include <cstddef>

#include "shader_build.h"

namespace render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 origin;
layout(location = 2) in vec2 rotation;
layout(location = 3) in vec2 quad_center;
layout(location = 4) in vec2 quad_axis;
layout(location = 5) in vec2 quad_half;
layout(location = 6) in vec4 color;
layout(location = 7) in vec4 record_in;

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel

flat out vec2 body_origin;
flat out vec2 body_rotation;
flat out vec3 fill;
flat out vec4 record;

vec2 Turn(vec2 r, vec2 v) { return vec2(r.x * v.x - r.y * v.y, r.y * v.x + r.x * v.y); }

void main() {
  // Two pixels beyond the primitive leave room for its anti-aliased edge.
  vec2 local = corner * (quad_half + 2.0 * pixel_size);
  vec2 body = quad_center + Turn(quad_axis, local);
  gl_Position = vec4((origin + Turn(rotation, body)) / view_half_size, 0.0, 1.0);
  body_origin = origin;
  body_rotation = rotation;
  fill = color.rgb;
  record = record_in;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
flat in vec2 body_origin;
flat in vec2 body_rotation;
flat in vec3 fill;
flat in vec4 record;  // own record's texel, first neighbour texel, neighbours, body thickness

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel
uniform bool spokes;
uniform samplerBuffer shapes;  // records: (kind, vertices, radius, 0), then vertices two a texel

out vec4 frag_color;

const float kOutlinePixels = 2.0;
const float kOutlineShade = 0.55;  // the outline is the fill, darker
const float kCircle = 0.0;
const float kPolygon = 2.0;

vec2 Vertex(int at, int k) {
  vec4 t = texelFetch(shapes, at + 1 + k / 2);
  return (k & 1) == 0 ? t.xy : t.zw;
}

float SegmentDistance(vec2 p, vec2 a, vec2 b) {
  vec2 ab = b - a;
  vec2 ap = p - a;
  float t = clamp(dot(ap, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
  return length(ap - t * ab);
}

// The exact signed distance to a simple polygon, either winding, convex or not: the nearest edge
// gives the distance, an even-odd crossing count the side (after Inigo Quilez's sdPolygon).
float PolygonDistance(vec2 p, int at, int n) {
  float nearest = 1e30;
  bool inside = false;
  vec2 a = Vertex(at, n - 1);
  vec4 two;  // a texel holds two vertices
  for (int i = 0; i < n; ++i) {
    if ((i & 1) == 0) two = texelFetch(shapes, at + 1 + i / 2);
    vec2 b = (i & 1) == 0 ? two.xy : two.zw;
    vec2 e = b - a;
    vec2 w = p - a;
    vec2 q = w - e * clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
    nearest = min(nearest, dot(q, q));
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * e.x / e.y) inside = !inside;
    a = b;
  }
  return (inside ? -1.0 : 1.0) * sqrt(nearest);
}

float Distance(vec2 p, int at) {
  vec4 head = texelFetch(shapes, at);
  if (head.x == kPolygon) return PolygonDistance(p, at, int(head.y)) - head.z;
  vec4 ends = texelFetch(shapes, at + 1);
  if (head.x == kCircle) return length(p - ends.xy) - head.z;
  return SegmentDistance(p, ends.xy, ends.zw) - head.z;
}

void main() {
  // The body-frame point comes from the pixel and the body alone, never from this quad, so
  // every instance of the body finds the very same distances and exactly one keeps the pixel.
  vec2 r = gl_FragCoord.xy * pixel_size - view_half_size - body_origin;
  vec2 p = vec2(body_rotation.x * r.x + body_rotation.y * r.y,
                -body_rotation.y * r.x + body_rotation.x * r.y);
  int self = int(record.x);
  float d = Distance(p, self);
  if (d >= 0.5 * pixel_size) discard;
  int first = int(record.y);
  int count = int(record.z);
  for (int k = 0; k < count; ++k) {
    int other = int(texelFetch(shapes, first + k / 4)[k % 4]);
    float d_other = Distance(p, other);
    // The nearest primitive draws the pixel; of equals, the first.
    if (d_other < d || (d_other == d && other < self)) discard;
  }
  // From here as the plain shader: coverage over one pixel, an outline band inside the edge.
  float coverage = clamp(0.5 - d / pixel_size, 0.0, 1.0);
  float outline_width = min(kOutlinePixels * pixel_size, 0.5 * record.w);
  vec3 outline = kOutlineShade * fill;
  vec3 color = mix(fill, outline, clamp(0.5 + (d + outline_width) / pixel_size, 0.0, 1.0));
  if (spokes && texelFetch(shapes, self).x == kCircle) {
    // A circle's spoke runs from its centre to the rim along its x axis: it shows the angle.
    vec4 spoke_ends = texelFetch(shapes, self + 1);
    float from_spoke = SegmentDistance(p, spoke_ends.xy, spoke_ends.zw);
    float spoke = clamp(0.5 - (from_spoke - 0.5 * outline_width) / pixel_size, 0.0, 1.0);
    color = mix(color, outline, spoke);
  }
  frag_color = vec4(color, coverage);
}
)";

void SetAttribute(const GlFunctions& fn, GLuint location, GLint size, GLenum type,
                  GLboolean normalized, std::size_t offset) {
  fn.EnableVertexAttribArray(location);
  fn.VertexAttribPointer(location, size, type, normalized, sizeof(PartInstance),
                         reinterpret_cast<const void*>(offset));
  fn.VertexAttribDivisor(location, 1);
}

}  // namespace

bool PartProgram::Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error) {
  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "part", program_, error)) return false;
  view_half_size_location_ = fn.GetUniformLocation(program_, "view_half_size");
  pixel_size_location_ = fn.GetUniformLocation(program_, "pixel_size");
  spokes_location_ = fn.GetUniformLocation(program_, "spokes");
  fn.UseProgram(program_);
  fn.Uniform1i(fn.GetUniformLocation(program_, "shapes"), 0);  // texture unit 0

  fn.GenVertexArrays(1, &vertex_array_);
  fn.BindVertexArray(vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, quad_buffer);
  fn.EnableVertexAttribArray(0);
  fn.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  fn.GenBuffers(1, &instance_buffer_);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  SetAttribute(fn, 1, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, origin));
  SetAttribute(fn, 2, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, rotation));
  SetAttribute(fn, 3, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_center));
  SetAttribute(fn, 4, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_axis));
  SetAttribute(fn, 5, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_half));
  // Normalised bytes reach the shader as exactly c / 255: fills are the scene colour exactly.
  SetAttribute(fn, 6, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(PartInstance, color));
  SetAttribute(fn, 7, 4, GL_FLOAT, GL_FALSE, offsetof(PartInstance, record));

  fn.GenBuffers(1, &texel_buffer_);
  fn.BindBuffer(GL_TEXTURE_BUFFER, texel_buffer_);
  fn.GenTextures(1, &texture_);
  fn.BindTexture(GL_TEXTURE_BUFFER, texture_);
  fn.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, texel_buffer_);
  GLint max_texels = 0;
  fn.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  // Texel indices travel as floats, exact up to 2^24.
  max_texels_ = std::min<std::size_t>(static_cast<std::size_t>(std::max(max_texels, 0)),
                                      std::size_t{1} << 24);
  return true;
}

void PartProgram::Destroy(const GlFunctions& fn) {
  fn.DeleteProgram(program_);
  fn.DeleteBuffers(1, &instance_buffer_);
  fn.DeleteBuffers(1, &texel_buffer_);
  fn.DeleteTextures(1, &texture_);
  fn.DeleteVertexArrays(1, &vertex_array_);
}

void PartProgram::Draw(const GlFunctions& fn, const PartBatch& batch, float view_half_width,
                       float view_half_height, float pixel_size, bool spokes) {
  const std::vector<PartInstance>& instances = batch.Instances();
  if (instances.empty()) return;
  fn.UseProgram(program_);
  fn.Uniform2f(view_half_size_location_, view_half_width, view_half_height);
  fn.Uniform1f(pixel_size_location_, pixel_size);
  fn.Uniform1i(spokes_location_, spokes ? 1 : 0);
  fn.BindBuffer(GL_TEXTURE_BUFFER, texel_buffer_);
  fn.BufferData(GL_TEXTURE_BUFFER, batch.Texels().size() * sizeof(float), batch.Texels().data(),
                GL_STREAM_DRAW);
  fn.ActiveTexture(GL_TEXTURE0);
  fn.BindTexture(GL_TEXTURE_BUFFER, texture_);
  fn.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, texel_buffer_);
  fn.BindVertexArray(vertex_array_);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer_);
  fn.BufferData(GL_ARRAY_BUFFER, instances.size() * sizeof(PartInstance), instances.data(),
                GL_STREAM_DRAW);
  fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(instances.size()));
}

}  // namespace render
