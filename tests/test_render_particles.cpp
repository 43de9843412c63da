// Soft bodies, fluid and effect particles in the picture (render/src/soft_body_mesh.h,
// fluid_surface.h, particle_sprites.h): a soft body is its fill inside its surface (the rim
// grown by a particle radius) with the bodies' darker outline, background beyond; fluid a
// solid liquid over its block with no holes between the particles; effect sprites add their
// colour × alpha (additive) or cover by their alpha; the same world gives the same bytes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/world.h"
#include "offscreen_gl.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/particle_style.h"
#include "render/renderer.h"
#include "world_builders.h"

using render::Color;
using render::Image;

namespace {

// 200x150 pixels of a 20 m wide view centred on the origin: 0.1 m per pixel, so world (x, y)
// lies at pixel (100 + 10x, 75 − 10y), and pixel (i, j)'s centre at world
// ((i + 0.5 − 100) / 10, (75 − j − 0.5) / 10).
constexpr int kWidth = 200;
constexpr int kHeight = 150;
const render::Camera kCamera{{0.0, 0.0}, 20.0};

constexpr Color kBlack{0, 0, 0};
constexpr Color kGrey{100, 100, 100};

using Gl = testing::OffscreenGl;

Image Draw(Gl& gl, const engine::World& world, const std::vector<Color>& colors,
           const render::ParticleStyle& style = {}) {
  gl.renderer->Draw(world, colors, kCamera, {}, style);
  Image image;
  gl.renderer->ReadImage(image);
  return image;
}

// Draws the world, then `effects` over it.
Image DrawWithEffects(Gl& gl, const engine::World& world, const std::vector<Color>& colors,
                      const std::vector<engine::EffectParticle>& effects) {
  gl.renderer->Draw(world, colors, kCamera);
  gl.renderer->DrawEffects(world, effects, kCamera);
  Image image;
  gl.renderer->ReadImage(image);
  return image;
}

int Difference(Color a, Color b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

std::string Show(Color c) {
  char text[24];
  std::snprintf(text, sizeof text, "(%d, %d, %d)", c.r, c.g, c.b);
  return text;
}

// The pixel whose centre is nearest world point p.
Color At(const Image& image, engine::Vec2 p) {
  const engine::Vec2 pixel = render::WorldToPixel(kCamera, kWidth, kHeight, p);
  return image.At(static_cast<int>(std::floor(pixel.x)), static_cast<int>(std::floor(pixel.y)));
}

// The world point at pixel (i, j)'s centre.
engine::Vec2 Center(int i, int j) {
  return render::PixelToWorld(kCamera, kWidth, kHeight, i + 0.5, j + 0.5);
}

// `over` laid on `under` by `alpha`, as the blending does it in 8 bits.
Color Over(Color over, double alpha, Color under) {
  auto mix = [alpha](int a, int b) {
    return static_cast<std::uint8_t>(std::lround(alpha * a + (1.0 - alpha) * b));
  };
  return {mix(over.r, under.r), mix(over.g, under.g), mix(over.b, under.b)};
}

Color Shade(Color c, double factor) {
  auto f = [factor](int v) { return static_cast<std::uint8_t>(std::lround(factor * v)); };
  return {f(c.r), f(c.g), f(c.b)};
}

engine::SoftBodyDef SoftCircle(engine::Vec2 center, double radius, double spacing) {
  engine::SoftBodyDef def;
  def.shape.type = engine::ShapeType::kCircle;
  def.shape.radius = radius;
  def.position = center;
  def.spacing = spacing;
  return def;
}

engine::SoftBodyDef SoftBox(engine::Vec2 center, engine::Vec2 size, double spacing) {
  engine::SoftBodyDef def;
  def.shape.type = engine::ShapeType::kBox;
  def.shape.half_extents = 0.5 * size;
  def.position = center;
  def.spacing = spacing;
  return def;
}

engine::FluidDef FluidBlock(engine::Vec2 lower, engine::Vec2 upper, double spacing) {
  engine::FluidDef def;
  def.region = {lower, upper};
  def.spacing = spacing;
  return def;
}

// An emitter that never emits (rate 0), so the world's own effects stay empty: the test hands
// its particles to DrawEffects.
engine::EmitterId QuietEmitter(engine::World& world, engine::EffectBlend blend, engine::Rgba start,
                               engine::Rgba end, double size_start, double size_end) {
  engine::EmitterDef def;
  def.rate = 0.0;
  def.blend = blend;
  def.color_start = start;
  def.color_end = end;
  def.size_start = size_start;
  def.size_end = size_end;
  return world.CreateEmitter(def);
}

engine::EffectParticle Particle(engine::EmitterId emitter, engine::Vec2 position, double age = 0.0,
                                double lifetime = 1.0) {
  engine::EffectParticle particle;
  particle.position = position;
  particle.age = age;
  particle.lifetime = lifetime;
  particle.emitter = emitter;
  return particle;
}

}  // namespace

TEST_CASE("A soft ball is its fill inside its surface, outlined darker, background beyond it") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  // The rim's 60 particles sit on a 1.9 m circle, 0.1 m (one radius) inside the 2 m surface;
  // grown by that radius, the rim's polygon lies between 1.997 m and 2.0002 m from the centre.
  const engine::Vec2 center{0.05, 0.05};
  world.CreateSoftBody(SoftCircle(center, 2.0, 0.2));
  constexpr Color kFill{40, 160, 90};
  render::ParticleStyle style;
  style.soft_bodies = {kFill};
  const Image image = Draw(gl, world, {}, style);
  CHECK(At(image, center) == kFill);
  // Every pixel by the distance of its centre from the ball's: the fill up to 2.5 pixels
  // inside the surface, the outline (0.55 of the fill) from 2 pixels in to half a pixel in,
  // the background from half a pixel out.
  int wrong_fill = 0;
  int wrong_outline = 0;
  int wrong_background = 0;
  const Color outline = Shade(kFill, 0.55);
  for (int j = 0; j < kHeight; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      const double r = engine::Length(Center(i, j) - center);
      const Color c = image.At(i, j);
      if (r < 1.74 && c != kFill) ++wrong_fill;
      if (r > 1.85 && r < 1.94 && Difference(c, outline) > 1) ++wrong_outline;
      if (r > 2.06 && c != render::kBackgroundColor) ++wrong_background;
    }
  }
  CHECK(wrong_fill == 0);
  CHECK(wrong_outline == 0);
  CHECK(wrong_background == 0);
}

TEST_CASE("A soft box fills its lattice grown by a particle radius; slots past the style get its default") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  // 4 x 2 m and 2 x 2 m, their lattices' outer particles 0.1 m in from those sides.
  world.CreateSoftBody(SoftBox({-4.0, 0.0}, {4.0, 2.0}, 0.2));
  world.CreateSoftBody(SoftBox({4.0, 0.0}, {2.0, 2.0}, 0.2));
  constexpr Color kFill{200, 120, 20};
  constexpr Color kDefault{30, 60, 200};
  render::ParticleStyle style;
  style.soft_bodies = {kFill};
  style.soft_body_default = kDefault;
  const Image image = Draw(gl, world, {}, style);
  CHECK(At(image, {-4.0, 0.0}) == kFill);
  CHECK(At(image, {4.0, 0.0}) == kDefault);
  // Just inside each side: the outline; 0.25 m beyond: background.
  for (const engine::Vec2 side : {engine::Vec2{2.0, 0.0}, engine::Vec2{-2.0, 0.0},
                                  engine::Vec2{0.0, 1.0}, engine::Vec2{0.0, -1.0}}) {
    const engine::Vec2 out = side / engine::Length(side);
    const engine::Vec2 edge = engine::Vec2{-4.0, 0.0} + side;
    INFO("side " << side.x << ", " << side.y);
    CHECK(Difference(At(image, edge - 0.1 * out), Shade(kFill, 0.55)) <= 3);
    CHECK(At(image, edge - 0.5 * out) == kFill);
    CHECK(At(image, edge + 0.25 * out) == render::kBackgroundColor);
  }
  CHECK(At(image, {5.25, 0.0}) == render::kBackgroundColor);
  CHECK(At(image, {2.75, 0.0}) == render::kBackgroundColor);
}

TEST_CASE("A soft body is drawn over the rigid bodies") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {12.0, 8.0})));
  world.CreateSoftBody(SoftCircle({0.0, 0.0}, 1.5, 0.2));
  const Image image = Draw(gl, world, {kGrey});
  CHECK(At(image, {0.0, 0.0}) == render::kSoftBodyColor);
  CHECK(At(image, {3.0, 0.0}) == kGrey);
}

TEST_CASE("A fluid block is solid liquid over its region, with no holes, and background well outside it") {
  // Spacings of 1, 3 and 10 pixels: the kernel closes the lattice at every zoom.
  const double spacing = GENERATE(0.1, 0.3, 1.0);
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  const engine::Vec2 lower{-6.0, -4.0};
  const engine::Vec2 upper{6.0, 3.0};
  world.AddFluid(FluidBlock(lower, upper, spacing));
  const Image image = Draw(gl, world, {});
  const Color liquid = Over(render::kFluidColor, render::kFluidOpacity, render::kBackgroundColor);
  INFO("spacing " << spacing << " m, liquid " << Show(liquid));
  // Every pixel whose centre lies 4 pixels or more inside the region is liquid (the lighter
  // rim lies within 3 pixels of the surface); every pixel 0.5 m or more outside it and the
  // drops' reach is background.
  int holes = 0;
  int stray = 0;
  const double inset = 0.4;
  const double outset = 0.5 + spacing;
  for (int j = 0; j < kHeight; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      const engine::Vec2 p = Center(i, j);
      const bool inside = p.x > lower.x + inset && p.x < upper.x - inset &&
                          p.y > lower.y + inset && p.y < upper.y - inset;
      const bool outside = p.x < lower.x - outset || p.x > upper.x + outset ||
                           p.y < lower.y - outset || p.y > upper.y + outset;
      if (inside && Difference(image.At(i, j), liquid) > 1) ++holes;
      if (outside && image.At(i, j) != render::kBackgroundColor) ++stray;
    }
  }
  CHECK(holes == 0);
  CHECK(stray == 0);
  // The surface lies near the region's sides (half a spacing beyond the outer particles):
  // mostly liquid a pixel and a half inside, background a pixel and a half beyond.
  const engine::Vec2 side{upper.x, 0.05};
  CHECK(Difference(At(image, side - engine::Vec2{0.15, 0.0}), liquid) <
        Difference(At(image, side - engine::Vec2{0.15, 0.0}), render::kBackgroundColor));
  CHECK(Difference(At(image, side + engine::Vec2{0.15 + 0.2 * spacing, 0.0}),
                   render::kBackgroundColor) <= 2);
}

TEST_CASE("Fluid is laid over the bodies by the style's colour and opacity") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {2.0, 2.0})));
  world.AddFluid(FluidBlock({-5.0, -3.0}, {5.0, 3.0}, 0.1));
  render::ParticleStyle style;
  style.fluid = {200, 30, 30};
  style.fluid_opacity = 0.4f;
  const Image image = Draw(gl, world, {kGrey}, style);
  CHECK(Difference(At(image, {0.0, 0.0}), Over(style.fluid, 0.4, kGrey)) <= 1);
  CHECK(Difference(At(image, {3.0, 0.0}), Over(style.fluid, 0.4, render::kBackgroundColor)) <= 1);
}

TEST_CASE("Fluid keeps drawing at the new size after a resize") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.AddFluid(FluidBlock({-2.0, -2.0}, {2.0, 2.0}, 0.1));
  const Color liquid = Over(render::kFluidColor, render::kFluidOpacity, render::kBackgroundColor);
  CHECK(Difference(At(Draw(gl, world, {}), {0.0, 0.0}), liquid) <= 1);
  std::string error;
  REQUIRE(gl.renderer->Resize(2 * kWidth, 2 * kHeight, error));
  gl.renderer->Draw(world, {}, kCamera);
  Image image;
  gl.renderer->ReadImage(image);
  REQUIRE(image.width == 2 * kWidth);
  CHECK(Difference(image.At(kWidth, kHeight), liquid) <= 1);
  CHECK(Difference(image.At(kWidth + 30, kHeight + 30), liquid) <= 1);
  CHECK(image.At(kWidth + 45, kHeight) == render::kBackgroundColor);
}

TEST_CASE("An additive sprite adds its colour × alpha at its centre; two add up") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {16.0, 12.0})));
  const engine::EmitterId fire = QuietEmitter(world, engine::EffectBlend::kAdditive,
                                              {1.0f, 0.5f, 0.25f, 0.4f}, {1.0f, 1.0f, 1.0f, 0.0f},
                                              1.0, 1.0);
  // Pixel (100, 74)'s centre: the sprite's peak lands on it exactly.
  const engine::Vec2 center = Center(100, 74);
  const std::vector<Color> colors{kBlack};
  const Image one = DrawWithEffects(gl, world, colors, {Particle(fire, center)});
  // The colour goes in as bytes (255, 128, 64), alpha 102: 255·0.4, 128·0.4, 64·0.4.
  const Color expected{102, 51, 26};
  INFO("one " << Show(one.At(100, 74)) << ", expected " << Show(expected));
  CHECK(Difference(one.At(100, 74), expected) <= 1);
  // Softer away from the centre, nothing beyond its 0.5 m radius.
  CHECK(one.At(104, 74).r < one.At(102, 74).r);
  CHECK(one.At(102, 74).r < one.At(100, 74).r);
  CHECK(one.At(106, 74) == kBlack);
  const Image two = DrawWithEffects(gl, world, colors, {Particle(fire, center), Particle(fire, center)});
  INFO("two " << Show(two.At(100, 74)));
  CHECK(Difference(two.At(100, 74), Color{204, 102, 51}) <= 2);
}

TEST_CASE("An alpha sprite covers what is behind it by its alpha; additive sprites go over it") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {16.0, 12.0})));
  const engine::EmitterId smoke = QuietEmitter(world, engine::EffectBlend::kAlpha,
                                               {0.0f, 0.0f, 1.0f, 0.5f}, {0.0f, 0.0f, 1.0f, 0.5f},
                                               1.0, 1.0);
  const engine::EmitterId fire = QuietEmitter(world, engine::EffectBlend::kAdditive,
                                              {0.4f, 0.0f, 0.0f, 1.0f}, {0.4f, 0.0f, 0.0f, 1.0f},
                                              1.0, 1.0);
  const engine::Vec2 center = Center(100, 74);
  const Image image = DrawWithEffects(gl, world, {kGrey}, {Particle(smoke, center)});
  CHECK(Difference(image.At(100, 74), Over(Color{0, 0, 255}, 128.0 / 255.0, kGrey)) <= 1);
  CHECK(image.At(106, 74) == kGrey);
  // The additive particle comes first in the list but is laid over the smoke.
  const Image both = DrawWithEffects(gl, world, {kGrey}, {Particle(fire, center), Particle(smoke, center)});
  const Color smoked = Over(Color{0, 0, 255}, 128.0 / 255.0, kGrey);
  CHECK(Difference(both.At(100, 74), Color{static_cast<std::uint8_t>(smoked.r + 102), smoked.g, smoked.b}) <= 1);
}

TEST_CASE("A sprite's size and colour run from its emitter's start to its end over its life") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {16.0, 12.0})));
  // Diameter 0.4 m → 2.0 m, red → green, alpha 1 → 0.
  const engine::EmitterId emitter = QuietEmitter(world, engine::EffectBlend::kAdditive,
                                                 {1.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 0.0f},
                                                 0.4, 2.0);
  const engine::Vec2 center = Center(100, 74);
  // Half-way through its 2 s life: diameter 1.2 m, colour (0.5, 0.5, 0), alpha 0.5.
  const Image image = DrawWithEffects(gl, world, {kBlack}, {Particle(emitter, center, 1.0, 2.0)});
  // Bytes (128, 128, 0) at alpha 128: 64 each.
  CHECK(Difference(image.At(100, 74), Color{64, 64, 0}) <= 1);
  CHECK(image.At(105, 74) != kBlack);   // 0.5 m out, inside the 0.6 m radius
  CHECK(image.At(107, 74) == kBlack);   // 0.7 m out
  // Past its life it stays at its end: transparent.
  const Image dead = DrawWithEffects(gl, world, {kBlack}, {Particle(emitter, center, 3.0, 2.0)});
  CHECK(dead.At(100, 74) == kBlack);
}

TEST_CASE("A sprite whose emitter is gone is not drawn") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {16.0, 12.0})));
  const engine::EmitterId gone = QuietEmitter(world, engine::EffectBlend::kAdditive,
                                              {1.0f, 1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f, 1.0f},
                                              1.0, 1.0);
  world.DestroyEmitter(gone);
  // Its slot taken by a new emitter: the old particle's id is stale all the same.
  QuietEmitter(world, engine::EffectBlend::kAdditive, {1.0f, 1.0f, 1.0f, 1.0f},
               {1.0f, 1.0f, 1.0f, 1.0f}, 1.0, 1.0);
  const Image image = DrawWithEffects(gl, world, {kBlack}, {Particle(gone, Center(100, 74))});
  CHECK(image.At(100, 74) == kBlack);
}

TEST_CASE("A world of soft bodies, fluid and sprites draws the same bytes every time") {
  engine::World world{engine::WorldDef{}};  // under gravity
  world.CreateBody(testing::Static(testing::Box({0.0, -5.0}, {18.0, 1.0})));
  world.CreateSoftBody(SoftCircle({-4.0, 1.0}, 1.5, 0.15));
  world.CreateSoftBody(SoftBox({4.0, 1.0}, {3.0, 2.0}, 0.25));
  world.AddFluid(FluidBlock({-8.0, -4.5}, {8.0, -1.0}, 0.1));
  const engine::EmitterId fire = QuietEmitter(world, engine::EffectBlend::kAdditive,
                                              {1.0f, 0.6f, 0.1f, 0.8f}, {1.0f, 0.1f, 0.0f, 0.0f},
                                              0.3, 1.0);
  const engine::EmitterId smoke = QuietEmitter(world, engine::EffectBlend::kAlpha,
                                               {0.3f, 0.3f, 0.3f, 0.6f}, {0.5f, 0.5f, 0.5f, 0.0f},
                                               0.5, 2.0);
  std::vector<engine::EffectParticle> effects;
  for (int k = 0; k < 2000; ++k) {
    const double t = 0.37 * k;
    effects.push_back(Particle(k % 3 == 0 ? smoke : fire,
                               {7.0 * std::sin(t), 5.0 * std::cos(1.3 * t)}, 0.001 * k, 2.5));
  }
  // A few steps, so the soft bodies and fluid have moved off their lattices.
  for (int step = 0; step < 10; ++step) world.Step();
  const std::vector<Color> colors{kGrey};
  Gl first = testing::MakeOffscreenGl(kWidth, kHeight);
  const Image a = DrawWithEffects(first, world, colors, effects);
  CHECK(DrawWithEffects(first, world, colors, effects).rgb == a.rgb);
  Gl second = testing::MakeOffscreenGl(kWidth, kHeight);
  CHECK(DrawWithEffects(second, world, colors, effects).rgb == a.rgb);
}

TEST_CASE("The fitted camera frames soft bodies and fluid as well as bodies") {
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Box({0.0, 0.0}, {2.0, 2.0}));
  world.CreateSoftBody(SoftBox({10.0, 0.0}, {2.0, 2.0}, 0.2));
  world.AddFluid(FluidBlock({-11.0, -1.0}, {-9.0, 1.0}, 0.2));
  const render::Camera camera = render::FitCamera(world, 800, 600);
  // From x = −11 to 11 (the lattices' discs reach the blocks' sides): 22 m, a tenth more
  // each side.
  CHECK(camera.center.x == Approx(0.0).margin(1e-12));
  CHECK(camera.center.y == Approx(0.0).margin(1e-12));
  CHECK(camera.width == Approx(22.0 * 1.2));
  // Fluid alone is framed too, not left to the default camera.
  engine::World fluid_only(testing::Still(false));
  fluid_only.AddFluid(FluidBlock({4.0, 4.0}, {6.0, 5.0}, 0.1));
  const render::Camera fluid_camera = render::FitCamera(fluid_only, 800, 600);
  CHECK(fluid_camera.center.x == Approx(5.0));
  CHECK(fluid_camera.center.y == Approx(4.5));
  CHECK(fluid_camera.width == Approx(2.0 * 1.2));
}

TEST_CASE("A frame after one with particles is the frame a fresh renderer draws") {
  // Whatever state the particle passes leave (blending, scissor, framebuffer, texture) must not
  // reach the next picture.
  engine::World particles(testing::Still(false));
  particles.CreateSoftBody(SoftCircle({-4.0, 0.0}, 1.5, 0.2));
  particles.AddFluid(FluidBlock({0.0, -3.0}, {6.0, 3.0}, 0.1));
  const engine::EmitterId fire = QuietEmitter(particles, engine::EffectBlend::kAdditive,
                                              {1.0f, 0.5f, 0.0f, 1.0f}, {1.0f, 0.5f, 0.0f, 1.0f},
                                              1.0, 1.0);
  engine::World plain(testing::Still(true));
  plain.CreateBody(testing::Circle({-3.0, 0.0}, 2.0));
  plain.CreateBody(testing::Box({3.0, 1.0}, {4.0, 2.0}));
  const std::vector<Color> colors{render::PaletteColor(0), render::PaletteColor(1)};
  Gl fresh = testing::MakeOffscreenGl(kWidth, kHeight);
  const Image expected = Draw(fresh, plain, colors);
  Gl used = testing::MakeOffscreenGl(kWidth, kHeight);
  DrawWithEffects(used, particles, {}, {Particle(fire, {0.0, 0.0})});
  CHECK(Draw(used, plain, colors).rgb == expected.rgb);
}
