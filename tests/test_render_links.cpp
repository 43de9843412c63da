// Springs and joints in the picture (render/src/link_lines.h): a spring is a zig-zag between its
// ends, a joint lines through its anchors with a dot on each, a grab a line to its target; a
// world with neither draws the very bytes it drew before links were drawn at all.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/world.h"
#include "offscreen_gl.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/renderer.h"
#include "run_program.h"
#include "shape_builders.h"
#include "world_builders.h"

using render::Color;
using render::Image;

namespace {

constexpr Color kBody{200, 40, 30};
constexpr Color kCeiling{90, 96, 107};

// 200x150 pixels of a 20 m wide view centred on the origin: 0.1 m per pixel, so world (x, y)
// lies at pixel (100 + 10x, 75 − 10y).
constexpr int kWidth = 200;
constexpr int kHeight = 150;
const render::Camera kCamera{{0.0, 0.0}, 20.0};

using Gl = testing::OffscreenGl;

Image Draw(Gl& gl, const engine::World& world, const std::vector<Color>& colors,
           render::LinkLayers links = {}) {
  gl.renderer->Draw(world, colors, kCamera, links);
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

// The pixel nearest `color` within `reach` pixels of (x, y), by Difference.
int NearestWithin(const Image& image, int x, int y, int reach, Color color) {
  int best = 255;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      best = std::min(best, Difference(image.At(x + dx, y + dy), color));
    }
  }
  return best;
}

// The pixel where world point p lands.
int PixelX(double x) { return static_cast<int>(100.0 + 10.0 * x); }
int PixelY(double y) { return static_cast<int>(75.0 - 10.0 * y); }

// A box hanging 8 m below a ceiling on a spring: its top (0, −2.5) to the world point (0, 5.5).
engine::World SpringWorld() {
  engine::World world(testing::Still(false));
  world.CreateBody(testing::Static(testing::Box({0.0, 6.0}, {10.0, 1.0})));
  const engine::BodyId box = world.CreateBody(testing::Box({0.0, -3.0}, {2.0, 1.0}));
  engine::SpringDef spring;
  spring.body_a = box;
  spring.local_a = {0.0, 0.5};
  spring.local_b = {0.0, 5.5};
  spring.rest_length = 8.0;
  spring.stiffness = 10.0;
  world.AddSpring(spring);
  return world;
}

}  // namespace

TEST_CASE("render links: a spring is a zig-zag between its ends, over the background", "[render][links]") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  const engine::World world = SpringWorld();
  const Image image = Draw(gl, world, {kCeiling, kBody});
  // Its midpoint, (0, 1.5), is on the line: the zig-zag crosses the axis there.
  const int mid_x = PixelX(0.0), mid_y = PixelY(1.5);
  INFO("midpoint pixel " << Show(image.At(mid_x, mid_y)));
  CHECK(Difference(image.At(mid_x, mid_y), render::kBackgroundColor) > 60);
  CHECK(NearestWithin(image, mid_x, mid_y, 1, render::kSpringColor) <= 8);
  // It swings to either side of the axis by kSpringAmplitudePixels (5 px): dark pixels 4 px
  // left and right of it, none 9 px away.
  int left = 0, right = 0, far = 0;
  for (int y = PixelY(4.0); y <= PixelY(-1.0); ++y) {
    left += Difference(image.At(mid_x - 4, y), render::kSpringColor) <= 40 ? 1 : 0;
    right += Difference(image.At(mid_x + 4, y), render::kSpringColor) <= 40 ? 1 : 0;
    far += Difference(image.At(mid_x - 9, y), render::kBackgroundColor) > 0 ? 1 : 0;
    far += Difference(image.At(mid_x + 9, y), render::kBackgroundColor) > 0 ? 1 : 0;
  }
  INFO("spring pixels 4 px left: " << left << ", right: " << right);
  CHECK(left >= 4);
  CHECK(right >= 4);
  CHECK(far == 0);
  // Its ends: a dot on the box's top edge and one on the ceiling's underside.
  CHECK(NearestWithin(image, PixelX(0.0), PixelY(-2.5), 1, render::kSpringColor) <= 8);
  CHECK(NearestWithin(image, PixelX(0.0), PixelY(5.5), 1, render::kSpringColor) <= 8);

  // Without the spring layer the picture is the world's without the spring.
  const Image hidden = Draw(gl, world, {kCeiling, kBody}, {.springs = false});
  CHECK(hidden.At(mid_x, mid_y) == render::kBackgroundColor);
  engine::World bare(testing::Still(false));
  bare.CreateBody(testing::Static(testing::Box({0.0, 6.0}, {10.0, 1.0})));
  bare.CreateBody(testing::Box({0.0, -3.0}, {2.0, 1.0}));
  CHECK(Draw(gl, bare, {kCeiling, kBody}).rgb == hidden.rgb);
}

TEST_CASE("render links: springs show in a world of bodies made of parts too", "[render][links]") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::TurningWorld());
  const engine::BodyId triangle = world.CreateBody(
      testing::PartsBody({testing::PolygonPart({{-1.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}})}, {-4.0, -4.0}));
  engine::SpringDef spring;
  spring.body_a = triangle;
  spring.local_a = {0.0, 1.0};       // the apex, (−4, −3)
  spring.local_b = {4.0, 5.0};       // a world point
  spring.rest_length = 1.0;
  world.AddSpring(spring);
  const Image image = Draw(gl, world, {kBody});
  // The midpoint of (−4, −3) and (4, 5) is (0, 1).
  CHECK(Difference(image.At(PixelX(0.0), PixelY(1.0)), render::kBackgroundColor) > 60);
  CHECK(Draw(gl, world, {kBody}, {.springs = false}).At(PixelX(0.0), PixelY(1.0)) ==
        render::kBackgroundColor);
}

TEST_CASE("render links: a joint is drawn through its anchors, a grab as a line to its target",
          "[render][links]") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World world(testing::Still(true));
  const engine::BodyId a = world.CreateBody(testing::Static(testing::Box({-5.0, 0.0}, {2.0, 2.0})));
  const engine::BodyId b = world.CreateBody(testing::Box({3.0, 0.0}, {2.0, 2.0}));
  const engine::BodyId ball = world.CreateBody(testing::Circle({6.0, -5.0}, 1.0));
  engine::JointDef hinge;
  hinge.type = engine::JointType::kRevolute;
  hinge.body_a = a;
  hinge.body_b = b;
  hinge.anchor = {0.0, 4.0};
  world.CreateJoint(hinge);
  engine::JointDef grab;
  grab.type = engine::JointType::kTarget;
  grab.body_b = ball;
  grab.anchor = {6.0, -5.0};
  grab.target = {2.0, -5.0};
  grab.spring = engine::JointSpring{5.0, 0.7};
  grab.max_force = 1000.0;
  world.CreateJoint(grab);
  const std::vector<Color> colors{kCeiling, kBody, kBody};
  const Image image = Draw(gl, world, colors);

  // A's centre to the anchor, and the anchor to B's centre, over the background; the hinge a dot.
  for (const engine::Vec2 p : {engine::Vec2{-2.5, 2.0}, engine::Vec2{1.5, 2.0}, engine::Vec2{0.0, 4.0}}) {
    INFO("at (" << p.x << ", " << p.y << "): " << Show(image.At(PixelX(p.x), PixelY(p.y))));
    CHECK(Difference(image.At(PixelX(p.x), PixelY(p.y)), render::kBackgroundColor) > 60);
    CHECK(NearestWithin(image, PixelX(p.x), PixelY(p.y), 1, render::kJointColor) <= 8);
  }
  // The grab: from the grabbed point to the target, in its own colour.
  CHECK(NearestWithin(image, PixelX(4.0), PixelY(-5.0), 1, render::kGrabColor) <= 8);
  CHECK(NearestWithin(image, PixelX(2.0), PixelY(-5.0), 1, render::kGrabColor) <= 8);
  // Nothing beyond the target.
  CHECK(image.At(PixelX(1.0), PixelY(-5.0)) == render::kBackgroundColor);

  // Without the joint layer: the bodies alone, as a world without the joints draws them.
  const Image hidden = Draw(gl, world, colors, {.joints = false});
  CHECK(hidden.At(PixelX(0.0), PixelY(4.0)) == render::kBackgroundColor);
  engine::World bare(testing::Still(true));
  bare.CreateBody(testing::Static(testing::Box({-5.0, 0.0}, {2.0, 2.0})));
  bare.CreateBody(testing::Box({3.0, 0.0}, {2.0, 2.0}));
  bare.CreateBody(testing::Circle({6.0, -5.0}, 1.0));
  CHECK(Draw(gl, bare, colors).rgb == hidden.rgb);
}

TEST_CASE("render links: a world without springs or joints draws the same bytes with links on or "
          "off, and after a picture that had them", "[render][links]") {
  Gl gl = testing::MakeOffscreenGl(kWidth, kHeight);
  engine::World plain(testing::Still(true));
  plain.CreateBody(testing::Circle({-4.0, 1.3}, 1.7));
  plain.CreateBody(testing::Box({3.3, -2.1}, {3.0, 1.2}));
  engine::World parts(testing::TurningWorld());
  parts.CreateBody(testing::PartsBody({testing::PolygonPart(testing::RegularPolygon(7, 2.0))}, {1.0, 1.0}, 0.4));
  parts.CreateBody(testing::Circle({-6.0, -3.0}, 1.0));

  const Image plain_first = Draw(gl, plain, {kBody, kCeiling});
  const Image parts_first = Draw(gl, parts, {kBody, kCeiling});
  CHECK(Draw(gl, plain, {kBody, kCeiling}, {.springs = false, .joints = false}).rgb == plain_first.rgb);
  CHECK(Draw(gl, parts, {kBody, kCeiling}, {.springs = false, .joints = false}).rgb == parts_first.rgb);
  // The link program leaves no state behind that changes the next picture.
  const engine::World springs = SpringWorld();
  CHECK(Draw(gl, springs, {kCeiling, kBody}).rgb != Draw(gl, springs, {kCeiling, kBody}, {.springs = false}).rgb);
  CHECK(Draw(gl, plain, {kBody, kCeiling}).rgb == plain_first.rgb);
  (void)Draw(gl, springs, {kCeiling, kBody});
  CHECK(Draw(gl, parts, {kBody, kCeiling}).rgb == parts_first.rgb);
  // And a picture with links is the same bytes in a fresh renderer.
  const Image with_links = Draw(gl, springs, {kCeiling, kBody});
  gl.renderer.reset();
  gl.context.reset();
  Gl fresh = testing::MakeOffscreenGl(kWidth, kHeight);
  CHECK(Draw(fresh, springs, {kCeiling, kBody}).rgb == with_links.rgb);
}

TEST_CASE("render links: ballbox render shows spring_pendulum's spring", "[render][links]") {
  const std::filesystem::path dir = testing::FreshTestDir("render_links", "spring_pendulum");
  const testing::ProgramRun run = testing::Ballbox(
      "render '" BALLBOX_ASSETS "/scenes/spring_pendulum.json' --frames 1 --out frames", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  int width = 0, height = 0, channels = 0;
  stbi_uc* rgb = stbi_load((dir / "frames" / "frame_00000.png").c_str(), &width, &height, &channels, 3);
  REQUIRE(rgb != nullptr);
  REQUIRE((width == 800 && height == 600));
  // The spring runs from the plank's corner (0.7, 3.2) to the ceiling point (0, 4); its midpoint
  // (0.35, 3.6) is at pixel (446.7, 166.7) through the scene's camera (centre (0, 2.6), 6 m wide).
  const render::Camera camera{{0.0, 2.6}, 6.0};
  const engine::Vec2 mid = render::WorldToPixel(camera, width, height, {0.35, 3.6});
  int nearest = 255;
  int most_unlike_background = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const stbi_uc* p = rgb + 3 * (static_cast<int>(mid.y + dy) * width + static_cast<int>(mid.x + dx));
      const Color c{p[0], p[1], p[2]};
      nearest = std::min(nearest, Difference(c, render::kSpringColor));
      most_unlike_background = std::max(most_unlike_background, Difference(c, render::kBackgroundColor));
    }
  }
  stbi_image_free(rgb);
  CHECK(most_unlike_background > 60);
  CHECK(nearest <= 8);
}
