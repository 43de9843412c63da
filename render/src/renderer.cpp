// The OpenGL renderer: every body is one instance of a quad whose fragment shader evaluates the
// shape's signed distance, which gives smooth edges and outlines without multisampling. Worlds
// with bodies made of parts go through the part program (part_program.h) instead, whole.
#include "render/renderer.h"

#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fluid_surface.h"
#include "gl_functions.h"
#include "link_lines.h"
#include "link_program.h"
#include "part_batch.h"
#include "part_program.h"
#include "particle_sprites.h"
#include "shader_build.h"
#include "soft_body_mesh.h"
#include "soft_body_program.h"
#include "sprite_program.h"

namespace render {
namespace {

// The unit quad, as a triangle strip; the vertex shader scales and turns it per body.
constexpr float kQuadCorners[] = {-1.0f, -1.0f, 1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f};

// What the shaders draw, per body.
enum class Kind { kDisc = 0, kDiscWithSpoke = 1, kBox = 2 };

struct Instance {
  float center[2];      // m, relative to the camera centre (subtracted in double, so far-away
                        // scenes keep their precision in float)
  float half_size[2];   // m; a disc has its radius in both
  float rotation[2];    // cos and sin of the body's angle
  std::uint8_t color[4];
  float kind;           // a Kind
};

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 corner;
layout(location = 1) in vec2 center;
layout(location = 2) in vec2 half_size_in;
layout(location = 3) in vec2 rotation;
layout(location = 4) in vec4 color;
layout(location = 5) in float kind_in;

uniform vec2 view_half_size;  // m
uniform float pixel_size;     // m per pixel

out vec2 local;  // m, in the body's own frame
flat out vec2 half_size;
flat out vec3 fill;
flat out float kind;

void main() {
  // Two pixels beyond the shape leave room for its anti-aliased edge.
  local = corner * (half_size_in + 2.0 * pixel_size);
  vec2 offset = vec2(rotation.x * local.x - rotation.y * local.y,
                     rotation.y * local.x + rotation.x * local.y);
  gl_Position = vec4((center + offset) / view_half_size, 0.0, 1.0);
  half_size = half_size_in;
  fill = color.rgb;
  kind = kind_in;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 local;
flat in vec2 half_size;
flat in vec3 fill;
flat in float kind;

uniform float pixel_size;  // m per pixel

out vec4 frag_color;

const float kOutlinePixels = 2.0;
const float kOutlineShade = 0.55;  // the outline is the fill, darker

float SignedDistance() {
  if (kind < 1.5) return length(local) - half_size.x;
  vec2 q = abs(local) - half_size;
  return length(max(q, 0.0)) + min(max(q.x, q.y), 0.0);
}

void main() {
  float d = SignedDistance();
  // Coverage ramps across one pixel at the edge: anti-aliasing with no multisampling.
  float coverage = clamp(0.5 - d / pixel_size, 0.0, 1.0);
  if (coverage == 0.0) discard;
  // Thin bodies keep some fill: the outline takes at most half of the smaller half-size.
  float outline_width = min(kOutlinePixels * pixel_size, 0.5 * min(half_size.x, half_size.y));
  vec3 outline = kOutlineShade * fill;
  vec3 color = mix(fill, outline, clamp(0.5 + (d + outline_width) / pixel_size, 0.0, 1.0));
  if (kind > 0.5 && kind < 1.5) {
    // The spoke runs from the centre to the rim along the body's x axis: it shows the angle.
    vec2 from_spoke = local - vec2(clamp(local.x, 0.0, half_size.x), 0.0);
    float spoke = clamp(0.5 - (length(from_spoke) - 0.5 * outline_width) / pixel_size, 0.0, 1.0);
    color = mix(color, outline, spoke);
  }
  frag_color = vec4(color, coverage);
}
)";

void SetInstanceAttribute(const GlFunctions& fn, GLuint location, GLint size, GLenum type,
                          GLboolean normalized, std::size_t offset) {
  fn.EnableVertexAttribArray(location);
  fn.VertexAttribPointer(location, size, type, normalized, sizeof(Instance),
                         reinterpret_cast<const void*>(offset));
  fn.VertexAttribDivisor(location, 1);
}

bool SizeAllowed(const GlFunctions& fn, int width, int height, std::string& error) {
  GLint max_renderbuffer = 0;
  GLint max_viewport[2] = {};
  fn.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer);
  fn.GetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
  if (width < 1 || height < 1 || width > max_renderbuffer || height > max_renderbuffer ||
      width > max_viewport[0] || height > max_viewport[1]) {
    error = "cannot render " + std::to_string(width) + "x" + std::to_string(height) +
            " pixels: this OpenGL allows 1 to " + std::to_string(max_renderbuffer) +
            " pixels a side";
    return false;
  }
  return true;
}

// Whether any body is made of parts: then the whole world goes through the part program, which
// draws circles and boxes too, so bodies keep their scene order.
bool HasParts(const engine::World& world) {
  for (const engine::BodyId id : world.BodyIds()) {
    if (!world.Parts(id).empty()) return true;
  }
  return false;
}

// Clears the renderer's own framebuffer to the background and sets the blending every program
// draws with. All state is set on every draw, so a window backend may share the context.
void BeginFrame(const GlFunctions& fn, GLuint framebuffer, int width, int height) {
  fn.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  fn.Viewport(0, 0, width, height);
  fn.ClearColor(kBackgroundColor.r / 255.0f, kBackgroundColor.g / 255.0f,
                kBackgroundColor.b / 255.0f, 1.0f);
  fn.Clear(GL_COLOR_BUFFER_BIT);
  fn.Enable(GL_BLEND);
  // Alpha accumulates towards 1 instead of being overwritten by the edge coverage, so the
  // framebuffer stays opaque (a PNG with partial alpha looks washed out in viewers).
  fn.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

void ClearTo(const GlFunctions& fn, Color color) {
  fn.ClearColor(color.r / 255.0f, color.g / 255.0f, color.b / 255.0f, 1.0f);
  fn.Clear(GL_COLOR_BUFFER_BIT);
}

}  // namespace

struct Renderer::Gl {
  GlFunctions fn;
  int width = 0;
  int height = 0;
  GLuint program = 0;
  GLint view_half_size_location = -1;
  GLint pixel_size_location = -1;
  GLuint vertex_array = 0;
  GLuint quad_buffer = 0;
  GLuint instance_buffer = 0;
  GLuint framebuffer = 0;
  GLuint color_buffer = 0;
  std::vector<Instance> instances;     // reused every frame
  PartProgram parts;
  PartBatch part_batch;                // reused every frame
  LinkProgram links;
  LinkLines link_lines;                // reused every frame
  SoftBodyProgram soft_bodies;
  SoftBodyMesh soft_body_mesh;         // reused every frame
  FluidSurface fluid;
  SpriteProgram sprites;
  ParticleSprites particle_sprites;    // reused every frame
  std::vector<std::uint8_t> readback;  // bottom-up rows, as GL returns them

  explicit Gl(const GlFunctions& functions) : fn(functions) {}
  Gl(const Gl&) = delete;
  Gl& operator=(const Gl&) = delete;
  ~Gl() {
    // GL ignores the name 0, so a half-built renderer cleans up the same way.
    fn.DeleteProgram(program);
    parts.Destroy(fn);
    links.Destroy(fn);
    soft_bodies.Destroy(fn);
    fluid.Destroy(fn);
    sprites.Destroy(fn);
    fn.DeleteBuffers(1, &quad_buffer);
    fn.DeleteBuffers(1, &instance_buffer);
    fn.DeleteVertexArrays(1, &vertex_array);
    fn.DeleteFramebuffers(1, &framebuffer);
    fn.DeleteRenderbuffers(1, &color_buffer);
  }
};

std::unique_ptr<Renderer> Renderer::Create(const GlContext& context, int width, int height,
                                           std::string& error) {
  GlFunctions functions;
  if (!LoadGlFunctions(context, functions, error)) return nullptr;
  auto gl = std::make_unique<Gl>(functions);
  const GlFunctions& fn = gl->fn;

  if (!SizeAllowed(fn, width, height, error)) return nullptr;
  gl->width = width;
  gl->height = height;

  if (!BuildProgram(fn, kVertexShader, kFragmentShader, "", gl->program, error)) return nullptr;
  gl->view_half_size_location = fn.GetUniformLocation(gl->program, "view_half_size");
  gl->pixel_size_location = fn.GetUniformLocation(gl->program, "pixel_size");

  fn.GenVertexArrays(1, &gl->vertex_array);
  fn.BindVertexArray(gl->vertex_array);
  fn.GenBuffers(1, &gl->quad_buffer);
  fn.BindBuffer(GL_ARRAY_BUFFER, gl->quad_buffer);
  fn.BufferData(GL_ARRAY_BUFFER, sizeof kQuadCorners, kQuadCorners, GL_STATIC_DRAW);
  fn.EnableVertexAttribArray(0);
  fn.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  fn.GenBuffers(1, &gl->instance_buffer);
  fn.BindBuffer(GL_ARRAY_BUFFER, gl->instance_buffer);
  SetInstanceAttribute(fn, 1, 2, GL_FLOAT, GL_FALSE, offsetof(Instance, center));
  SetInstanceAttribute(fn, 2, 2, GL_FLOAT, GL_FALSE, offsetof(Instance, half_size));
  SetInstanceAttribute(fn, 3, 2, GL_FLOAT, GL_FALSE, offsetof(Instance, rotation));
  // Normalised bytes reach the shader as exactly c / 255, so a body's fill lands in the image
  // as exactly its scene colour.
  SetInstanceAttribute(fn, 4, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Instance, color));
  SetInstanceAttribute(fn, 5, 1, GL_FLOAT, GL_FALSE, offsetof(Instance, kind));

  if (!gl->parts.Create(fn, gl->quad_buffer, error)) return nullptr;
  if (!gl->links.Create(fn, gl->quad_buffer, error)) return nullptr;
  if (!gl->soft_bodies.Create(fn, error)) return nullptr;
  if (!gl->fluid.Create(fn, gl->quad_buffer, error)) return nullptr;
  if (!gl->sprites.Create(fn, gl->quad_buffer, error)) return nullptr;

  fn.GenRenderbuffers(1, &gl->color_buffer);
  fn.BindRenderbuffer(GL_RENDERBUFFER, gl->color_buffer);
  fn.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  fn.GenFramebuffers(1, &gl->framebuffer);
  fn.BindFramebuffer(GL_FRAMEBUFFER, gl->framebuffer);
  fn.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                             gl->color_buffer);
  if (fn.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    error = "cannot render " + std::to_string(width) + "x" + std::to_string(height) +
            " pixels: the OpenGL framebuffer is incomplete";
    return nullptr;
  }
  if (const GLenum code = fn.GetError(); code != GL_NO_ERROR) {
    error = "OpenGL error " + std::to_string(code) + " while setting up the renderer";
    return nullptr;
  }
  return std::unique_ptr<Renderer>(new Renderer(std::move(gl)));
}

Renderer::Renderer(std::unique_ptr<Gl> gl) : gl_(std::move(gl)) {}
Renderer::~Renderer() = default;

int Renderer::Width() const { return gl_->width; }
int Renderer::Height() const { return gl_->height; }

std::string Renderer::Description() const {
  auto text = [this](GLenum name) {
    const GLubyte* s = gl_->fn.GetString(name);
    return s == nullptr ? std::string("?") : std::string(reinterpret_cast<const char*>(s));
  };
  return text(GL_RENDERER) + ", " + text(GL_VERSION);
}

void Renderer::Draw(const engine::World& world, std::span<const Color> colors,
                    const Camera& camera, LinkLayers links, const ParticleStyle& particles) {
  assert(colors.size() == world.BodyCount());
  if (HasParts(world)) {
    DrawWithParts(world, colors, camera);
  } else {
    DrawBodies(world, colors, camera);
  }
  DrawParticleBodies(world, camera, particles);
  DrawLinks(world, camera, links);
  DrawEffects(world, world.Effects(), camera);
}

void Renderer::DrawBodies(const engine::World& world, std::span<const Color> colors,
                          const Camera& camera) {
  Gl& gl = *gl_;
  const GlFunctions& fn = gl.fn;
  // With rotation off the engine does no angular work, so angles are not part of the picture.
  const bool rotation = world.Def().rotation;

  gl.instances.clear();
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& state = world.State(id);
    const engine::Shape& shape = world.Info(id).shape;
    const double angle = rotation ? state.angle : 0.0;
    Instance instance{};
    instance.center[0] = static_cast<float>(state.position.x - camera.center.x);
    instance.center[1] = static_cast<float>(state.position.y - camera.center.y);
    if (shape.type == engine::ShapeType::kCircle) {
      instance.half_size[0] = instance.half_size[1] = static_cast<float>(shape.radius);
      instance.kind = static_cast<float>(rotation ? Kind::kDiscWithSpoke : Kind::kDisc);
    } else {
      instance.half_size[0] = static_cast<float>(shape.half_extents.x);
      instance.half_size[1] = static_cast<float>(shape.half_extents.y);
      instance.kind = static_cast<float>(Kind::kBox);
    }
    instance.rotation[0] = static_cast<float>(std::cos(angle));
    instance.rotation[1] = static_cast<float>(std::sin(angle));
    const Color color = colors[id.index];
    instance.color[0] = color.r;
    instance.color[1] = color.g;
    instance.color[2] = color.b;
    instance.color[3] = 255;
    gl.instances.push_back(instance);
  }

  BeginFrame(fn, gl.framebuffer, gl.width, gl.height);
  fn.UseProgram(gl.program);
  const double pixel_size = camera.width / gl.width;
  fn.Uniform2f(gl.view_half_size_location, static_cast<float>(0.5 * camera.width),
               static_cast<float>(0.5 * pixel_size * gl.height));
  fn.Uniform1f(gl.pixel_size_location, static_cast<float>(pixel_size));
  fn.BindVertexArray(gl.vertex_array);
  fn.BindBuffer(GL_ARRAY_BUFFER, gl.instance_buffer);
  fn.BufferData(GL_ARRAY_BUFFER, gl.instances.size() * sizeof(Instance), gl.instances.data(),
                GL_STREAM_DRAW);
  if (!gl.instances.empty()) {
    fn.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(gl.instances.size()));
  }
}

void Renderer::DrawWithParts(const engine::World& world, std::span<const Color> colors,
                             const Camera& camera) {
  Gl& gl = *gl_;
  const GlFunctions& fn = gl.fn;
  const bool rotation = world.Def().rotation;
  const double pixel_size = camera.width / gl.width;
  const float half_width = static_cast<float>(0.5 * camera.width);
  const float half_height = static_cast<float>(0.5 * pixel_size * gl.height);
  BeginFrame(fn, gl.framebuffer, gl.width, gl.height);
  PartBatch& batch = gl.part_batch;
  batch.Clear();
  // One draw call holds as many bodies as the texture buffer takes; a body too big for it
  // alone is left out (its outline would need more texels than this GL has).
  for (const engine::BodyId id : world.BodyIds()) {
    const std::size_t instances = batch.Instances().size();
    const std::size_t texels = batch.TexelCount();
    batch.Append(world, id, colors[id.index], rotation, camera, pixel_size);
    if (batch.TexelCount() <= gl.parts.MaxTexels()) continue;
    batch.Truncate(instances, texels);
    gl.parts.Draw(fn, batch, half_width, half_height, static_cast<float>(pixel_size), rotation);
    batch.Clear();
    batch.Append(world, id, colors[id.index], rotation, camera, pixel_size);
    if (batch.TexelCount() > gl.parts.MaxTexels()) batch.Clear();
  }
  gl.parts.Draw(fn, batch, half_width, half_height, static_cast<float>(pixel_size), rotation);
}

void Renderer::DrawParticleBodies(const engine::World& world, const Camera& camera,
                                  const ParticleStyle& style) {
  Gl& gl = *gl_;
  const double pixel_size = camera.width / gl.width;
  // A world without soft bodies or fluid makes no GL call here: its pictures stay what they were.
  gl.soft_body_mesh.Build(world, style, camera, pixel_size);
  gl.soft_bodies.Draw(gl.fn, gl.soft_body_mesh, static_cast<float>(0.5 * camera.width),
                      static_cast<float>(0.5 * pixel_size * gl.height),
                      static_cast<float>(pixel_size));
  // The liquid goes over the bodies, part see-through: a body in it looks submerged.
  gl.fluid.Draw(gl.fn, world, style, camera, gl.framebuffer, gl.width, gl.height);
}

void Renderer::DrawEffects(const engine::World& world,
                           std::span<const engine::EffectParticle> effects, const Camera& camera) {
  Gl& gl = *gl_;
  const double pixel_size = camera.width / gl.width;
  gl.particle_sprites.Build(world, effects, camera, pixel_size);
  if (gl.particle_sprites.Alpha().empty() && gl.particle_sprites.Additive().empty()) return;
  // Called on its own, it draws over the last picture, wherever the context was left.
  gl.fn.BindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
  gl.fn.Viewport(0, 0, gl.width, gl.height);
  gl.fn.Enable(GL_BLEND);
  gl.sprites.Draw(gl.fn, gl.particle_sprites, static_cast<float>(0.5 * camera.width),
                  static_cast<float>(0.5 * pixel_size * gl.height));
}

void Renderer::DrawLinks(const engine::World& world, const Camera& camera, LinkLayers links) {
  Gl& gl = *gl_;
  const double pixel_size = camera.width / gl.width;
  gl.link_lines.Build(world, camera, pixel_size, links);
  // A world without links makes no GL call here: its pictures stay what they were.
  gl.links.Draw(gl.fn, gl.link_lines, static_cast<float>(0.5 * camera.width),
                static_cast<float>(0.5 * pixel_size * gl.height), static_cast<float>(pixel_size));
}

void Renderer::ReadImage(Image& image) {
  Gl& gl = *gl_;
  const std::size_t row_bytes = static_cast<std::size_t>(gl.width) * 3;
  gl.readback.resize(row_bytes * gl.height);
  gl.fn.BindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
  gl.fn.PixelStorei(GL_PACK_ALIGNMENT, 1);  // RGB rows are not 4-byte multiples
  gl.fn.ReadPixels(0, 0, gl.width, gl.height, GL_RGB, GL_UNSIGNED_BYTE, gl.readback.data());
  // GL's row 0 is the bottom of the picture; images are top-down.
  image.width = gl.width;
  image.height = gl.height;
  image.rgb.resize(gl.readback.size());
  for (int row = 0; row < gl.height; ++row) {
    std::memcpy(image.rgb.data() + row * row_bytes,
                gl.readback.data() + (gl.height - 1 - row) * row_bytes, row_bytes);
  }
}

bool Renderer::Resize(int width, int height, std::string& error) {
  Gl& gl = *gl_;
  if (width == gl.width && height == gl.height) return true;
  if (!SizeAllowed(gl.fn, width, height, error)) return false;
  // The framebuffer object keeps its attachment; only the storage behind it changes.
  gl.fn.BindRenderbuffer(GL_RENDERBUFFER, gl.color_buffer);
  gl.fn.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  if (const GLenum code = gl.fn.GetError(); code != GL_NO_ERROR) {
    // Back to the old size, so the renderer stays usable.
    gl.fn.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, gl.width, gl.height);
    error = "OpenGL error " + std::to_string(code) + " while resizing to " +
            std::to_string(width) + "x" + std::to_string(height) + " pixels";
    return false;
  }
  gl.width = width;
  gl.height = height;
  return true;
}

void Renderer::Present(int framebuffer_width, int framebuffer_height, const PixelRect& picture,
                       std::span<const FilledRect> overlay, Color border) {
  Gl& gl = *gl_;
  const GlFunctions& fn = gl.fn;
  // Framebuffer 0 is the window's; GL counts its rows from the bottom, PixelRect from the top.
  auto bottom = [&](const PixelRect& r) { return framebuffer_height - r.y - r.height; };
  fn.BindFramebuffer(GL_FRAMEBUFFER, 0);
  fn.Viewport(0, 0, framebuffer_width, framebuffer_height);
  ClearTo(fn, border);
  fn.BindFramebuffer(GL_READ_FRAMEBUFFER, gl.framebuffer);
  const bool same_size = picture.width == gl.width && picture.height == gl.height;
  fn.BlitFramebuffer(0, 0, gl.width, gl.height, picture.x, bottom(picture),
                     picture.x + picture.width, bottom(picture) + picture.height,
                     GL_COLOR_BUFFER_BIT, same_size ? GL_NEAREST : GL_LINEAR);
  fn.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  // The overlay is a handful of rectangles: scissored clears need no shader of their own.
  fn.Enable(GL_SCISSOR_TEST);
  for (const FilledRect& filled : overlay) {
    fn.Scissor(filled.rect.x, bottom(filled.rect), filled.rect.width, filled.rect.height);
    ClearTo(fn, filled.color);
  }
  // Draw sets everything else it needs, but not the scissor test: leave it off.
  fn.Disable(GL_SCISSOR_TEST);
  fn.BindFramebuffer(GL_FRAMEBUFFER, gl.framebuffer);
}

}  // namespace render
