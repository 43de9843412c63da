// The OpenGL renderer on OSMesa: bodies land where the contract's pixel mapping puts them, in
// their scene colours, with anti-aliased edges; angles show only when rotation is on.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"
#include "render/renderer.h"
#include "offscreen_gl.h"
#include "world_builders.h"

using render::Color;
using render::Image;

namespace {

constexpr Color kBall{200, 40, 30};
constexpr Color kBox{30, 90, 200};

// Every test below draws 200x150 pixels of a 20 m wide view centred on the origin: 0.1 m per
// pixel, so world (x, y) lies at pixel (100 + 10x, 75 − 10y) by the contract's mapping.
constexpr int kWidth = 200;
constexpr int kHeight = 150;
const render::Camera kCamera{{0.0, 0.0}, 20.0};

using Gl = testing::OffscreenGl;

Gl MakeGl(int width = kWidth, int height = kHeight) { return testing::MakeOffscreenGl(width, height); }

Image Draw(Gl& gl, const engine::World& world, const std::vector<Color>& colors) {
  return testing::DrawFrame(gl, world, colors, kCamera);
}

using testing::Still;

engine::BodyDef Turned(engine::BodyDef def, double angle) {
  def.angle = angle;
  return def;
}

std::string Show(Color c) {
  char text[24];
  std::snprintf(text, sizeof text, "(%d, %d, %d)", c.r, c.g, c.b);
  return text;
}

// The mean pixel position of every pixel of exactly `color`.
engine::Vec2 Centroid(const Image& image, Color color, int& count) {
  engine::Vec2 sum;
  count = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.At(x, y) == color) {
        sum += engine::Vec2{x + 0.5, y + 0.5};
        ++count;
      }
    }
  }
  return count > 0 ? sum / count : sum;
}

}  // namespace

TEST_CASE("render: a ball and a box show in their colours over the background", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  // Ball centre at the pixel corner (60, 65), radius 20.25 px; box centre at pixel (150, 85),
  // 40 x 20 px.
  world.CreateBody(testing::Circle({-4.0, 1.0}, 2.025));
  world.CreateBody(testing::Box({5.0, -1.0}, {4.0, 2.0}));
  const Image image = Draw(gl, world, {kBall, kBox});

  CHECK(Show(image.At(60, 65)) == Show(kBall));
  CHECK(Show(image.At(59, 64)) == Show(kBall));
  CHECK(Show(image.At(150, 85)) == Show(kBox));
  CHECK(Show(image.At(140, 82)) == Show(kBox));
  for (auto [x, y] : {std::pair{0, 0}, {199, 0}, {0, 149}, {199, 149}, {100, 20}, {100, 140}}) {
    INFO("pixel " << x << ", " << y);
    CHECK(Show(image.At(x, y)) == Show(render::kBackgroundColor));
  }
}

TEST_CASE("render: a ball's rim is anti-aliased", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  world.CreateBody(testing::Circle({-4.0, 1.0}, 2.025));
  const Image image = Draw(gl, world, {kBall});

  // Along row 65 the pixel centres lie 19.51, 20.51 and 21.51 px from the ball's centre: inside
  // the 20.25 px rim, a quarter pixel past it, and clear of it.
  const Color outline = image.At(79, 65);
  const Color rim = image.At(80, 65);
  const Color outside = image.At(81, 65);
  CHECK(Show(outside) == Show(render::kBackgroundColor));
  // The outline is a darker shade of the fill, distinct from both fill and background.
  CHECK(outline.r < kBall.r);
  CHECK(outline.g <= kBall.g);
  CHECK(outline.b <= kBall.b);
  // The rim pixel blends outline and background. Its centre is covered by about a quarter of
  // a pixel's edge ramp, so it sits roughly a quarter of the way from background to outline.
  const Color bg = render::kBackgroundColor;
  const auto fraction = [](int background, int value, int full) {
    return static_cast<double>(background - value) / (background - full);
  };
  for (auto [b, v, o] : {std::tuple{bg.r, rim.r, outline.r}, {bg.g, rim.g, outline.g},
                         {bg.b, rim.b, outline.b}}) {
    INFO("background " << int(b) << ", rim " << int(v) << ", outline " << int(o));
    REQUIRE(o < b);
    CHECK(v < b);
    CHECK(v > o);
    CHECK(fraction(b, v, o) == Approx(0.25).margin(0.1));
  }
}

TEST_CASE("render: world up is image up and world left is image left", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  world.CreateBody(testing::Circle({-6.0, 4.0}, 1.0));   // up and left: pixel (40, 35)
  world.CreateBody(testing::Box({6.0, -4.0}, {2.0, 2.0}));  // down and right: pixel (160, 115)
  const Image image = Draw(gl, world, {kBall, kBox});

  int count = 0;
  const engine::Vec2 ball = Centroid(image, kBall, count);
  REQUIRE(count > 100);
  CHECK(ball.x == Approx(40.0).margin(0.5));
  CHECK(ball.y == Approx(35.0).margin(0.5));
  const engine::Vec2 box = Centroid(image, kBox, count);
  REQUIRE(count > 100);
  CHECK(box.x == Approx(160.0).margin(0.5));
  CHECK(box.y == Approx(115.0).margin(0.5));
}

TEST_CASE("render: boxes turn with their angle only when rotation is on", "[render]") {
  Gl gl = MakeGl();
  // A 4 m x 1 m bar at the origin turned 45°. Pixel (112, 63) lies on its long axis; pixel
  // (117, 75) lies on the world x axis, inside the bar only if it were not turned.
  const engine::BodyDef bar = Turned(testing::Box({0.0, 0.0}, {4.0, 1.0}), std::atan(1.0));

  engine::World turning(Still(true));
  turning.CreateBody(bar);
  const Image turned = Draw(gl, turning, {kBox});
  CHECK(Show(turned.At(112, 63)) == Show(kBox));
  CHECK(Show(turned.At(117, 75)) == Show(render::kBackgroundColor));

  engine::World axis_aligned(Still(false));
  axis_aligned.CreateBody(bar);
  const Image flat = Draw(gl, axis_aligned, {kBox});
  CHECK(Show(flat.At(117, 75)) == Show(kBox));
  CHECK(Show(flat.At(112, 63)) == Show(render::kBackgroundColor));
}

TEST_CASE("render: a ball's spoke shows its angle when rotation is on", "[render]") {
  Gl gl = MakeGl();
  // A 2 m ball at the origin turned a quarter turn: its spoke points up, towards pixel row 65.
  const engine::BodyDef ball = Turned(testing::Circle({0.0, 0.0}, 2.0), 2.0 * std::atan(1.0));

  engine::World turning(Still(true));
  turning.CreateBody(ball);
  const Image with_spoke = Draw(gl, turning, {kBall});
  const Color up = with_spoke.At(100, 65);
  INFO("on the spoke: " << Show(up));
  CHECK(up.r < kBall.r);
  CHECK(Show(with_spoke.At(100, 85)) == Show(kBall));  // down
  CHECK(Show(with_spoke.At(110, 75)) == Show(kBall));  // right

  engine::World still(Still(false));
  still.CreateBody(ball);
  const Image without = Draw(gl, still, {kBall});
  CHECK(Show(without.At(100, 65)) == Show(kBall));
}

TEST_CASE("render: later bodies draw over earlier ones", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  world.CreateBody(testing::Box({0.0, 0.0}, {6.0, 6.0}));
  world.CreateBody(testing::Circle({0.0, 0.0}, 1.0));
  const Image image = Draw(gl, world, {kBox, kBall});
  CHECK(Show(image.At(100, 75)) == Show(kBall));
  CHECK(Show(image.At(100, 55)) == Show(kBox));
}

TEST_CASE("render: the same world draws the same bytes", "[render]") {
  engine::World world(Still(true));
  world.CreateBody(testing::Circle({-4.0, 1.3}, 1.7));
  world.CreateBody(Turned(testing::Box({3.3, -2.1}, {3.0, 1.2}), 0.3));
  Gl first = MakeGl();
  const Image a = Draw(first, world, {kBall, kBox});
  const Image b = Draw(first, world, {kBall, kBox});
  CHECK(a.rgb == b.rgb);
  // The renderer's GL objects belong to its context: release them before the context goes.
  first.renderer.reset();
  first.context.reset();
  Gl second = MakeGl();
  CHECK(Draw(second, world, {kBall, kBox}).rgb == a.rgb);
}

TEST_CASE("render: an impossible image size is refused with a message", "[render]") {
  std::string error;
  auto context = render::CreateOffscreenContext(error);
  REQUIRE(context);
  CHECK(render::Renderer::Create(*context, 0, 100, error) == nullptr);
  CHECK_THAT(error, Catch::Contains("0x100"));
  error.clear();
  CHECK(render::Renderer::Create(*context, 1 << 20, 100, error) == nullptr);
  CHECK_THAT(error, Catch::Contains("pixels"));
}
