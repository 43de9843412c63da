// The part shader: each instance is a quad over one primitive (a convex piece: circle, capsule or
// polygon, rounded or not); its fragments find the distance to it and to its neighbours in the
// same body, keep the pixels where their own primitive is the nearest, and shade the distance to
// the body's outline exactly as the plain shader shades circles and boxes.
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
layout(location = 8) in float only_own_group_in;

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel

flat out vec2 body_origin;
flat out vec2 body_rotation;
flat out vec3 fill;
flat out vec4 record;
flat out float only_own_group;

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
  only_own_group = only_own_group_in;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
flat in vec2 body_origin;
flat in vec2 body_rotation;
flat in vec3 fill;
// Own record's texel; the first texel and length of the list of the body's primitives near it,
// itself included (empty when the body has no other); the body's thickness.
flat in vec4 record;
flat in float only_own_group;  // 1: every primitive near it is a polygon piece of its group

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel
uniform bool spokes;
// Records: (kind, vertices, radius, group of a polygon piece), then a polygon's vertices a texel each (x, y, whether
// the edge to the next is outline), or a circle's centre and spoke tip, a capsule's two ends.
uniform samplerBuffer shapes;

out vec4 frag_color;

const float kOutlinePixels = 2.0;
const float kOutlineShade = 0.55;  // the outline is the fill, darker
const float kCircle = 0.0;
const float kPolygon = 2.0;
const float kFar = 1e30;

float SegmentDistance(vec2 p, vec2 a, vec2 b) {
  vec2 ab = b - a;
  vec2 ap = p - a;
  float t = clamp(dot(ap, ab) / max(dot(ab, ab), 1e-30), 0.0, 1.0);
  return length(ap - t * ab);
}

// A polygon piece, before rounding: its signed distance (the nearest edge gives the distance, an
// even-odd crossing count the side, as Inigo Quilez's sdPolygon), and the distance to the
// nearest of its edges on the outline (kFar if none).
void PieceDistances(vec2 p, int at, int n, out float core, out float outline) {
  float nearest = kFar;
  float nearest_outline = kFar;
  bool inside = false;
  vec4 a = texelFetch(shapes, at + n);
  for (int i = 1; i <= n; ++i) {
    vec4 b = texelFetch(shapes, at + i);
    vec2 e = b.xy - a.xy;
    vec2 w = p - a.xy;
    vec2 q = w - e * clamp(dot(w, e) / dot(e, e), 0.0, 1.0);
    float q2 = dot(q, q);
    nearest = min(nearest, q2);
    if (a.z > 0.5) nearest_outline = min(nearest_outline, q2);
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * e.x / e.y) inside = !inside;
    a = b;
  }
  core = (inside ? -1.0 : 1.0) * sqrt(nearest);
  outline = sqrt(nearest_outline);
}

// A primitive's own signed distance (rounding included); for a polygon piece also `core` and
// `outline` as PieceDistances gives them.
float OwnDistance(vec2 p, int at, vec4 head, out float core, out float outline) {
  if (head.x == kPolygon) {
    PieceDistances(p, at, int(head.y), core, outline);
    return core - head.z;
  }
  vec4 ends = texelFetch(shapes, at + 1);
  core = head.x == kCircle ? length(p - ends.xy) - head.z
                           : SegmentDistance(p, ends.xy, ends.zw) - head.z;
  outline = kFar;
  return core;
}

// A group of polygon pieces' signed distance from what its pieces near the point say: `inside`
// whether one holds it, `outside` the least piece distance, `edge` the distance to the nearest
// outline edge. A point on a cut between two pieces may be held by neither (the crossing test is
// exact only off the boundary), but there the outline is farther than the pieces: inside too.
float GroupDistance(bool inside, float outside, float edge, float rounding) {
  bool held = inside || outside < edge - 1e-3 * pixel_size;
  return (held ? -edge : outside) - rounding;
}

void main() {
  // The body-frame point comes from the pixel and the body alone, never from this quad, so
  // every instance of the body finds the very same distances and exactly one keeps the pixel.
  vec2 r = gl_FragCoord.xy * pixel_size - view_half_size - body_origin;
  vec2 p = vec2(body_rotation.x * r.x + body_rotation.y * r.y,
                -body_rotation.y * r.x + body_rotation.x * r.y);
  int self = int(record.x);
  vec4 self_head = texelFetch(shapes, self);
  float self_core, self_outline;
  float self_own = OwnDistance(p, self, self_head, self_core, self_outline);
  // Nothing of this primitive within half a pixel: either no coverage or another's pixel.
  if (self_own >= 0.5 * pixel_size) discard;

  int first = int(record.y);
  int count = int(record.z);
  // The union's distance d: the least over round primitives and over groups of polygon pieces.
  // A group, gathered from its pieces (listed one after another), is inside when a piece holds
  // the point, then as deep as its nearest outline edge, so where pieces meet never shows.
  // A body of one primitive lists none: the union is the primitive. Deep inside a polygon piece
  // that only pieces of its own group lie near, no other piece holds the point and every outline
  // edge is at least as far as this piece's own edges: the plain fill, with no list to go through.
  float outline_width = min(kOutlinePixels * pixel_size, 0.5 * record.w);
  bool settled = count == 0 ||
                 (only_own_group > 0.5 && self_own <= -(outline_width + 0.5 * pixel_size));
  float d = settled ? self_own : kFar;
  if (settled) count = 0;
  float group = -1.0;
  bool inside = false;
  float outside = kFar;
  float edge = kFar;
  float rounding = 0.0;
  for (int k = 0; k < count; ++k) {
    int at = int(texelFetch(shapes, first + k / 4)[k % 4]);
    vec4 head = at == self ? self_head : texelFetch(shapes, at);
    float core, outline, own;
    if (at == self) {
      core = self_core;
      outline = self_outline;
      own = self_own;
    } else {
      own = OwnDistance(p, at, head, core, outline);
    }
    // The primitive nearest the point draws it; of equals, the first (lists share one order).
    if (own < self_own || (own == self_own && at < self)) discard;
    if (head.x != kPolygon) {
      d = min(d, own);
      continue;
    }
    if (head.w != group) {
      if (group >= 0.0) d = min(d, GroupDistance(inside, outside, edge, rounding));
      group = head.w;
      inside = false;
      outside = kFar;
      edge = kFar;
      rounding = head.z;
    }
    inside = inside || core < 0.0;
    outside = min(outside, core);
    edge = min(edge, outline);
  }
  if (group >= 0.0) d = min(d, GroupDistance(inside, outside, edge, rounding));

  // From here as the plain shader: coverage over one pixel, an outline band inside the edge.
  float coverage = clamp(0.5 - d / pixel_size, 0.0, 1.0);
  if (coverage == 0.0) discard;
  vec3 outline_color = kOutlineShade * fill;
  vec3 color = mix(fill, outline_color, clamp(0.5 + (d + outline_width) / pixel_size, 0.0, 1.0));
  if (spokes && self_head.x == kCircle) {
    // A circle's spoke runs from its centre to the rim along its x axis: it shows the angle.
    vec4 spoke_ends = texelFetch(shapes, self + 1);
    float from_spoke = SegmentDistance(p, spoke_ends.xy, spoke_ends.zw);
    float spoke = clamp(0.5 - (from_spoke - 0.5 * outline_width) / pixel_size, 0.0, 1.0);
    color = mix(color, outline_color, spoke);
  }
  frag_color = vec4(color, coverage);
}
)";

}  // namespace

bool PartProgram::Create(const GlFunctions& fn, GLuint quad_buffer, std::string& error) {
  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "part", program_, error)) return false;
  view_half_size_location_ = fn.GetUniformLocation(program_, "view_half_size");
  pixel_size_location_ = fn.GetUniformLocation(program_, "pixel_size");
  spokes_location_ = fn.GetUniformLocation(program_, "spokes");
  fn.UseProgram(program_);
  fn.Uniform1i(fn.GetUniformLocation(program_, "shapes"), 0);  // texture unit 0

  NewInstancedQuad(fn, quad_buffer, vertex_array_, instance_buffer_);
  SetInstanceAttribute<PartInstance>(fn, 1, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, origin));
  SetInstanceAttribute<PartInstance>(fn, 2, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, rotation));
  SetInstanceAttribute<PartInstance>(fn, 3, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_center));
  SetInstanceAttribute<PartInstance>(fn, 4, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_axis));
  SetInstanceAttribute<PartInstance>(fn, 5, 2, GL_FLOAT, GL_FALSE, offsetof(PartInstance, quad_half));
  // Normalised bytes reach the shader as exactly c / 255: fills are the scene colour exactly.
  SetInstanceAttribute<PartInstance>(fn, 6, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(PartInstance, color));
  SetInstanceAttribute<PartInstance>(fn, 7, 4, GL_FLOAT, GL_FALSE, offsetof(PartInstance, record));
  SetInstanceAttribute<PartInstance>(fn, 8, 1, GL_FLOAT, GL_FALSE, offsetof(PartInstance, only_own_group));

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
