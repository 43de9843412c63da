// The renderer on OSMesa with bodies made of parts: polygons (convex, concave, rounded), capsules,
// segment polylines and compound bodies land where the contract's pixel mapping puts them,
// filled in their colour, outlined once around the whole body (no seam where parts or convex
// pieces meet), with smooth edges; circles and boxes beside them look as they do without them.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"
#include "render/color.h"
#include "render/context.h"
#include "render/image.h"
#include "render/png_writer.h"
#include "render/renderer.h"
#include "render/window.h"
#include "run_program.h"
#include "offscreen_gl.h"
#include "world_builders.h"

using engine::Vec2;
using render::Color;
using render::Image;

namespace {

constexpr Color kFill{200, 40, 30};
constexpr Color kOther{30, 90, 200};
const Color kBackground = render::kBackgroundColor;

namespace fs = std::filesystem;

// As in test_render.cpp: 200x150 pixels of a 20 m wide view centred on the origin, 0.1 m per
// pixel, so world (x, y) lies at pixel (100 + 10x, 75 − 10y); pixel (i, j)'s centre is the
// world point ((i + 0.5 − 100) / 10, (75 − j − 0.5) / 10).
constexpr int kWidth = 200;
constexpr int kHeight = 150;
constexpr double kPixel = 0.1;
const render::Camera kCamera{{0.0, 0.0}, 20.0};

Vec2 PixelCentre(int i, int j) { return {(i + 0.5 - 100.0) * kPixel, (75.0 - j - 0.5) * kPixel}; }

using Gl = testing::OffscreenGl;

Gl MakeGl(int width = kWidth, int height = kHeight) { return testing::MakeOffscreenGl(width, height); }

Image Draw(Gl& gl, const engine::World& world, const std::vector<Color>& colors) {
  return testing::DrawFrame(gl, world, colors, kCamera);
}

using testing::Still;

std::string Show(Color c) {
  char text[24];
  std::snprintf(text, sizeof text, "(%d, %d, %d)", c.r, c.g, c.b);
  return text;
}

engine::ShapePart Polygon(std::vector<Vec2> points, double radius = 0.0) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kPolygon;
  part.points = std::move(points);
  part.radius = radius;
  return part;
}

engine::ShapePart Capsule(double length, double radius, Vec2 offset = {}, double angle = 0.0) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kCapsule;
  part.length = length;
  part.radius = radius;
  part.offset = offset;
  part.angle = angle;
  return part;
}

engine::ShapePart Circle(double radius, Vec2 offset) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kCircle;
  part.radius = radius;
  part.offset = offset;
  return part;
}

engine::ShapePart BoxPart(Vec2 half_extents, Vec2 offset = {}, double angle = 0.0) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kBox;
  part.half_extents = half_extents;
  part.offset = offset;
  part.angle = angle;
  return part;
}

engine::ShapePart Segments(std::vector<Vec2> points, bool loop = false) {
  engine::ShapePart part;
  part.type = engine::ShapeType::kSegments;
  part.points = std::move(points);
  part.loop = loop;
  return part;
}

engine::BodyDef Made(std::vector<engine::ShapePart> parts, Vec2 position, double angle = 0.0,
                     bool is_static = false) {
  engine::BodyDef def;
  def.parts = std::move(parts);
  def.position = position;
  def.angle = angle;
  def.is_static = is_static;
  return def;
}

// Signed distances in metres, for the expected pictures (negative inside).
double SegmentDistance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double t = engine::Clamp(engine::Dot(p - a, ab) / engine::Dot(ab, ab), 0.0, 1.0);
  return engine::Length(p - (a + t * ab));
}

double PolygonDistance(Vec2 p, const std::vector<Vec2>& v) {
  double nearest = INFINITY;
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    nearest = std::min(nearest, SegmentDistance(p, v[j], v[i]));
    if ((v[i].y > p.y) != (v[j].y > p.y) &&
        p.x < v[j].x + (p.y - v[j].y) * (v[i].x - v[j].x) / (v[i].y - v[j].y)) {
      inside = !inside;
    }
  }
  return inside ? -nearest : nearest;
}

std::vector<Vec2> Placed(const std::vector<Vec2>& points, Vec2 origin, double angle = 0.0) {
  std::vector<Vec2> out;
  for (const Vec2 p : points) out.push_back(origin + engine::Rotate(engine::MakeRot(angle), p));
  return out;
}

// Every pixel whose centre lies `inner` (2.5 px) or more inside the shape (by `distance`) is
// exactly `fill` (the outline is 2 px wide, its anti-aliased inner edge half a pixel more), and
// every pixel whose centre lies more than half a pixel outside it is exactly `background`.
// Pixels in between are the outline and the edge; a NaN distance leaves the pixel unchecked.
// Returns "" or how many pixels broke the rule, with the first few.
std::string Mismatches(const Image& image, const std::function<double(Vec2)>& distance,
                       Color fill, Color background, double inner = 0.25) {
  std::string where;
  int bad = 0;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const double d = distance(PixelCentre(i, j));
      const Color c = image.At(i, j);
      const bool wrong = (d <= -inner && !(c == fill)) || (d > 0.051 && !(c == background));
      if (!wrong) continue;
      if (++bad <= 5) {
        where += "pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") at " +
                 std::to_string(d) + " m is " + Show(c) + "; ";
      }
    }
  }
  return bad == 0 ? "" : std::to_string(bad) + " pixels wrong: " + where;
}

// How many pixels are neither the fill nor the background: the outline and edge blends.
int EdgePixels(const Image& image, Color fill) {
  int count = 0;
  for (int j = 0; j < image.height; ++j) {
    for (int i = 0; i < image.width; ++i) {
      const Color c = image.At(i, j);
      if (!(c == fill) && !(c == kBackground)) ++count;
    }
  }
  return count;
}

}  // namespace

TEST_CASE("render shapes: a triangle is filled inside, outlined at its edge, background outside",
          "[render]") {
  Gl gl = MakeGl();
  const std::vector<Vec2> triangle{{-4.0, -3.0}, {4.0, -3.0}, {0.0, 4.0}};
  for (const bool clockwise : {false, true}) {
    INFO((clockwise ? "clockwise" : "counter-clockwise"));
    std::vector<Vec2> points = triangle;
    if (clockwise) std::reverse(points.begin(), points.end());
    engine::World world(Still(false));
    world.CreateBody(Made({Polygon(points)}, {1.0, 0.5}));
    const Image image = Draw(gl, world, {kFill});

    // Hand-computed (the apex is (1, 4.5)): the centroid (1, −0.17) is pixel (110, 76);
    // pixel (110, 45), (1.05, 2.95), is 0.7 m inside; pixel (132, 45), (3.25, 2.95), outside;
    // pixel (110, 31), (1.05, 4.35), is inside but 0.08 m from the sides: the outline.
    CHECK(Show(image.At(110, 76)) == Show(kFill));
    CHECK(Show(image.At(110, 45)) == Show(kFill));
    CHECK(Show(image.At(132, 45)) == Show(kBackground));
    CHECK(image.At(110, 31).r < kFill.r);
    // Along row 75 (y = −0.05) the right edge x = 1 + 4·4.55/7 ≈ 3.6 is at pixel 136: 132
    // is inside by 3 px, 140 outside.
    CHECK(Show(image.At(132, 75)) == Show(kFill));
    CHECK(Show(image.At(140, 75)) == Show(kBackground));
    // Just inside the edge: the outline, a darker shade of the fill.
    const Color outline = image.At(135, 75);
    INFO("outline " << Show(outline));
    CHECK(outline.r < kFill.r);
    CHECK(outline.r > 0);

    const auto distance = [&](Vec2 p) { return PolygonDistance(p, Placed(triangle, {1.0, 0.5})); };
    CHECK(Mismatches(image, distance, kFill, kBackground) == "");
  }
}

TEST_CASE("render shapes: a concave L shows one outline and no edge between its pieces",
          "[render]") {
  Gl gl = MakeGl();
  // An L 8 m tall and wide, 3 m thick; the engine splits it into two or more convex pieces.
  const std::vector<Vec2> l_shape{{0, 0}, {8, 0}, {8, 3}, {3, 3}, {3, 8}, {0, 8}};
  engine::World world(Still(false));
  const engine::BodyId id = world.CreateBody(Made({Polygon(l_shape)}, {-5.0, -5.0}));
  REQUIRE(world.Pieces(id).size() >= 2);
  const Image image = Draw(gl, world, {kFill});

  // Every pixel 2.5 px or more inside the L, the seams between pieces included, is the fill.
  const auto distance = [&](Vec2 p) { return PolygonDistance(p, Placed(l_shape, {-5.0, -5.0})); };
  CHECK(Mismatches(image, distance, kFill, kBackground) == "");
  // The reflex corner at world (−2, −2), pixel (80, 95): its inside is the outline's shade,
  // the notch diagonally out from it background.
  CHECK(Show(image.At(75, 100)) == Show(kFill));
  CHECK(Show(image.At(85, 90)) == Show(kBackground));
  CHECK(image.At(80, 95).r < kFill.r);  // on the corner: the outline
  // Only the outline's ring of pixels is neither fill nor background: 2 px along the 32 m
  // (320 px) perimeter, since edges on pixel boundaries put centres 0.5 and 1.5 px inside;
  // an edge between pieces, 30 px long, would add twice 60 or more.
  const int edge = EdgePixels(image, kFill);
  CHECK(edge >= 2 * 320 - 20);
  CHECK(edge <= 2 * 320 + 40);
}

TEST_CASE("render shapes: a turned, rounded bowl of many pieces shows none of its cuts",
          "[render]") {
  Gl gl = MakeGl();
  // Half a ring, 8 m across and 1.2 m thick, of 34 points: the engine fans it into triangles
  // and larger pieces, whose cuts meet at shared corners.
  std::vector<Vec2> bowl;
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i <= 16; ++i) bowl.push_back({-8.0 * std::cos(kPi * i / 16), -8.0 * std::sin(kPi * i / 16)});
  for (int i = 16; i >= 0; --i) bowl.push_back({-6.8 * std::cos(kPi * i / 16), -6.8 * std::sin(kPi * i / 16)});
  const double radius = 0.15, angle = 0.3;
  const Vec2 origin{0.5, 3.0};
  engine::World world(Still(true));
  const engine::BodyId id = world.CreateBody(Made({Polygon(bowl, radius)}, origin, angle, true));
  REQUIRE(world.Pieces(id).size() >= 8);
  const Image image = Draw(gl, world, {kFill});
  const std::vector<Vec2> placed = Placed(bowl, origin, angle);
  CHECK(Mismatches(image, [&](Vec2 p) { return PolygonDistance(p, placed) - radius; }, kFill,
                   kBackground) == "");
}

TEST_CASE("render shapes: a capsule has round caps and turns with its body", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(true));
  // 6 m between the cap centres, radius 1.5: caps centred on (±3, 0).
  world.CreateBody(Made({Capsule(6.0, 1.5)}, {0.0, 0.0}));
  // The same turned a quarter turn by its body, at (−6.5, 0): caps on (−6.5, ±3).
  world.CreateBody(Made({Capsule(6.0, 1.5)}, {-6.5, 0.0}, 2.0 * std::atan(1.0)));
  const Image image = Draw(gl, world, {kFill, kOther});

  CHECK(Show(image.At(140, 70)) == Show(kFill));        // (4.05, 0.45): inside the right cap
  CHECK(Show(image.At(144, 61)) == Show(kBackground));  // (4.45, 1.35): a box's corner, not a cap's
  CHECK(Show(image.At(100, 63)) == Show(kFill));        // (0.05, 1.15): the straight middle
  CHECK(Show(image.At(147, 75)) == Show(kBackground));  // beyond the tip at x = 4.5
  CHECK(Show(image.At(35, 35)) == Show(kOther));        // (−6.45, 3.95): the upper cap
  CHECK(Show(image.At(10, 75)) == Show(kBackground));   // (−8.95, 0): beside the standing one

  // Each body against its own shape, on its own side of x = −4.75 (NaN: not checked).
  const auto lying = [](Vec2 p) {
    return p.x > -4.75 ? SegmentDistance(p, {-3, 0}, {3, 0}) - 1.5 : NAN;
  };
  CHECK(Mismatches(image, lying, kFill, kBackground) == "");
  const auto standing = [](Vec2 p) {
    return p.x < -4.75 ? SegmentDistance(p, {-6.5, -3}, {-6.5, 3}) - 1.5 : NAN;
  };
  CHECK(Mismatches(image, standing, kOther, kBackground) == "");
}

TEST_CASE("render shapes: a rounded polygon's corners are round", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  // A 6 m square core grown by 1 m: a 8 m square with corners of radius 1 m.
  const std::vector<Vec2> core{{-3, -3}, {3, -3}, {3, 3}, {-3, 3}};
  world.CreateBody(Made({Polygon(core, 1.0)}, {0.0, 0.0}));
  const Image image = Draw(gl, world, {kFill});
  CHECK(Show(image.At(138, 37)) == Show(kBackground));  // (3.85, 3.75): a sharp square's corner
  CHECK(Show(image.At(136, 75)) == Show(kFill));        // (3.65, −0.05): the grown side
  CHECK(Mismatches(image, [&](Vec2 p) { return PolygonDistance(p, core) - 1.0; }, kFill,
                   kBackground) == "");
}

TEST_CASE("render shapes: a segment polyline is a band with no seam at its joins", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  const std::vector<Vec2> line{{-8, -4}, {-2, -4}, {2, 0}, {8, 0}};
  world.CreateBody(Made({Segments(line)}, {0.0, 0.0}, 0.0, true));
  const Image image = Draw(gl, world, {render::kStaticColor});

  // The band is 6 px wide (0.3 m either side of the line): filled within 1 px of the line,
  // outlined 1.5 px, background past 3.5 px.
  const auto distance = [&](Vec2 p) {
    double d = INFINITY;
    for (std::size_t i = 0; i + 1 < line.size(); ++i) d = std::min(d, SegmentDistance(p, line[i], line[i + 1]));
    return d - 0.3;
  };
  CHECK(Mismatches(image, distance, render::kStaticColor, kBackground, 0.2) == "");
  // The horizontal run at y = −4 lies between rows 114 and 115, 0.5 px from both centres.
  CHECK(Show(image.At(50, 114)) == Show(render::kStaticColor));
  CHECK(Show(image.At(50, 115)) == Show(render::kStaticColor));
  CHECK(Show(image.At(50, 110)) == Show(kBackground));
  // On the line 2.5 px before the join at (−2, −4): within the next segment's round end's
  // outline band, which must not show.
  CHECK(Show(image.At(77, 114)) == Show(render::kStaticColor));
  CHECK(Show(image.At(77, 115)) == Show(render::kStaticColor));
}

TEST_CASE("render shapes: a closed loop is drawn all round and stays hollow", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(false));
  const std::vector<Vec2> square{{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  world.CreateBody(Made({Segments(square, true)}, {0.0, 0.0}, 0.0, true));
  const Image image = Draw(gl, world, {render::kStaticColor});
  CHECK(Show(image.At(100, 75)) == Show(kBackground));  // the middle: a loop is not filled
  // The closing segment, from (−5, 5) back to (−5, −5), at pixel column 50.
  CHECK(Show(image.At(50, 75)) == Show(render::kStaticColor));
  CHECK(Show(image.At(49, 75)) == Show(render::kStaticColor));
  // The corner where the loop closes, (−5, −5) at pixel (50, 125).
  CHECK(Show(image.At(49, 124)) == Show(render::kStaticColor));
}

TEST_CASE("render shapes: a compound body is one filled shape with one outline", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(true));
  // A bar with a wheel at its right end and a post across its left end, turned 0.3 rad about
  // its origin (1, 1).
  const double angle = 0.3;
  const Vec2 origin{1.0, 1.0};
  const engine::BodyId id = world.CreateBody(Made(
      {BoxPart({3.0, 0.6}), Circle(1.5, {3.0, 0.0}), Capsule(3.0, 0.5, {-3.0, 0.0}, 1.5707963267948966)},
      origin, angle));
  REQUIRE(world.Origin(id).x == Approx(origin.x));
  REQUIRE(world.Origin(id).y == Approx(origin.y));
  const Image image = Draw(gl, world, {kFill});

  const engine::Rot turn = engine::MakeRot(angle);
  const auto to_body = [&](Vec2 p) { return engine::InvRotate(turn, p - origin); };
  const auto distance = [&](Vec2 world_point) {
    const Vec2 p = to_body(world_point);
    // The wheel's spoke, from its centre along the body's x axis, is not the fill.
    if (SegmentDistance(p, {3, 0}, {4.5, 0}) < 0.25) return double{NAN};
    const double bar = PolygonDistance(p, {{-3, -0.6}, {3, -0.6}, {3, 0.6}, {-3, 0.6}});
    const double wheel = engine::Length(p - Vec2{3, 0}) - 1.5;
    const double post = SegmentDistance(p, {-3, -1.5}, {-3, 1.5}) - 0.5;
    return std::min({bar, wheel, post});
  };
  CHECK(Mismatches(image, distance, kFill, kBackground) == "");
  // Where the bar enters the wheel (body (1.8, 0), inside both): fill, no outline of either.
  const Vec2 seam = origin + engine::Rotate(turn, {1.6, 0.0});
  const Vec2 px = render::WorldToPixel(kCamera, kWidth, kHeight, seam);
  CHECK(Show(image.At(static_cast<int>(px.x), static_cast<int>(px.y))) == Show(kFill));
}

TEST_CASE("render shapes: boxes that touch or cross in one body have one outline", "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(true));
  // An L of two boxes that only touch (the upright stands on the base's top, y = 1), and a cross
  // of two boxes that overlap; both turned, so the touching edges meet only up to rounding.
  const Vec2 l_origin{-4.0, -2.0}, cross_origin{5.0, 1.0};
  const double l_angle = 0.5, cross_angle = -0.3;
  world.CreateBody(Made({BoxPart({3.0, 1.0}), BoxPart({1.0, 2.0}, {-2.0, 3.0})}, l_origin, l_angle));
  world.CreateBody(Made({BoxPart({3.0, 0.8}), BoxPart({0.8, 3.0})}, cross_origin, cross_angle));
  const Image image = Draw(gl, world, {kFill, kOther});
  const std::vector<Vec2> l_outline =
      Placed({{-3, -1}, {3, -1}, {3, 1}, {-1, 1}, {-1, 5}, {-3, 5}}, l_origin, l_angle);
  const std::vector<Vec2> cross_outline =
      Placed({{-3, -0.8}, {-0.8, -0.8}, {-0.8, -3}, {0.8, -3}, {0.8, -0.8}, {3, -0.8}, {3, 0.8},
              {0.8, 0.8}, {0.8, 3}, {-0.8, 3}, {-0.8, 0.8}, {-3, 0.8}},
             cross_origin, cross_angle);
  // Each body against its own outline, on its own side of x = 0.5 (NaN: not checked).
  CHECK(Mismatches(image, [&](Vec2 p) { return p.x < 0.5 ? PolygonDistance(p, l_outline) : NAN; },
                   kFill, kBackground) == "");
  CHECK(Mismatches(image, [&](Vec2 p) { return p.x > 0.5 ? PolygonDistance(p, cross_outline) : NAN; },
                   kOther, kBackground) == "");
}

TEST_CASE("render shapes: circles and boxes beside parts look as they do alone", "[render]") {
  Gl gl = MakeGl();
  // The ball and box of test_render.cpp's first test, drawn by the plain path alone and then
  // by the part path, with a small triangle in the top-left corner.
  engine::World plain(Still(false));
  plain.CreateBody(testing::Circle({-4.0, 1.0}, 2.025));
  plain.CreateBody(testing::Box({5.0, -1.0}, {4.0, 2.0}));
  const Image alone = Draw(gl, plain, {kFill, kOther});

  engine::World mixed(Still(false));
  mixed.CreateBody(testing::Circle({-4.0, 1.0}, 2.025));
  mixed.CreateBody(testing::Box({5.0, -1.0}, {4.0, 2.0}));
  mixed.CreateBody(Made({Polygon({{0, 0}, {1, 0}, {0, 1}})}, {-9.5, 6.0}));
  const Image beside = Draw(gl, mixed, {kFill, kOther, kOther});

  CHECK(Show(beside.At(60, 65)) == Show(kFill));
  CHECK(Show(beside.At(150, 85)) == Show(kOther));
  CHECK(Show(beside.At(7, 12)) == Show(kOther));  // (−9.25, 6.25): the triangle, 2.5 px in
  // Away from the triangle, the two pictures differ by a level or two at edges at most.
  int worst = 0;
  for (int j = 30; j < kHeight; ++j) {
    for (int i = 0; i < kWidth; ++i) {
      const Color a = alone.At(i, j), b = beside.At(i, j);
      worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
    }
  }
  CHECK(worst <= 2);
}

TEST_CASE("render shapes: a circle part shows its spoke, and later bodies draw on top",
          "[render]") {
  Gl gl = MakeGl();
  engine::World world(Still(true));
  // A square, then a wheel part turned a quarter turn over its middle: the spoke points up.
  world.CreateBody(Made({Polygon({{-4, -4}, {4, -4}, {4, 4}, {-4, 4}})}, {0.0, 0.0}));
  engine::ShapePart wheel = Circle(2.0, {0.0, 0.0});
  wheel.angle = 2.0 * std::atan(1.0);
  world.CreateBody(Made({wheel}, {0.0, 0.0}));
  const Image image = Draw(gl, world, {kOther, kFill});
  CHECK(image.At(100, 65).r < kFill.r);                // on the spoke, 1 m up
  CHECK(Show(image.At(100, 85)) == Show(kFill));       // 1 m down: the wheel's fill
  CHECK(Show(image.At(100, 105)) == Show(kOther));     // 3 m down: the square around it
}

namespace {

// Every kind at once: a rounded concave polygon, a capsule, a polyline and a ball, turned.
void AddEveryKind(engine::World& world) {
  world.CreateBody(
      Made({Polygon({{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}}, 0.2)}, {-6.3, -2.2}, 0.4));
  world.CreateBody(Made({Capsule(3.0, 0.7)}, {3.1, 2.3}, -0.2));
  world.CreateBody(Made({Segments({{-9, -6}, {0, -5}, {9, -6.5}})}, {0.0, 0.0}, 0.0, true));
  world.CreateBody(testing::Circle({4.0, -2.0}, 1.2));
}
const std::vector<Color> kEveryKindColors{kFill, kOther, render::kStaticColor, kFill};

}  // namespace

TEST_CASE("render shapes: the same world draws the same bytes", "[render]") {
  engine::World world(Still(true));
  AddEveryKind(world);
  const std::vector<Color>& colors = kEveryKindColors;
  Gl first = MakeGl();
  const Image a = Draw(first, world, colors);
  CHECK(Draw(first, world, colors).rgb == a.rgb);
  first.renderer.reset();
  first.context.reset();
  Gl second = MakeGl();
  CHECK(Draw(second, world, colors).rgb == a.rgb);
}

// `ballbox play` draws with the same Renderer into a GLFW window's context. The test below runs
// this one in a fresh Xvfb (the test binary starts without a display), which writes its picture
// where BALLBOX_SHAPES_PNG says.
TEST_CASE("window child: the shapes drawn in a window's context (run by render shapes)",
          "[.shapes_in_window]") {
  const char* path = std::getenv("BALLBOX_SHAPES_PNG");
  REQUIRE(path != nullptr);
  render::Window::Failure failure = render::Window::Failure::kNone;
  std::string error;
  const auto window = render::Window::Open(kWidth, kHeight, "shapes", failure, error);
  INFO(error);
  REQUIRE(window);
  auto renderer = render::Renderer::Create(*window, kWidth, kHeight, error);
  INFO(error);
  REQUIRE(renderer);
  engine::World world(Still(true));
  AddEveryKind(world);
  renderer->Draw(world, kEveryKindColors, kCamera);
  Image image;
  renderer->ReadImage(image);
  const std::vector<std::uint8_t> png = render::EncodePng(image);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

TEST_CASE("play window: the part shapes drawn in a window's context (as play draws) match the offscreen ones",
          "[render][xvfb]") {
  const bool have = std::system("command -v xvfb-run >/dev/null 2>&1 && command -v flock "
                                ">/dev/null 2>&1") == 0;
  if (!render::WindowSupportBuilt() || !have) {
    WARN("SKIPPED: needs a build with GLFW, xvfb-run and flock");
    return;
  }
  const fs::path dir = testing::FreshTestDir("render_shapes", "window");
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::string lock = (fs::path(BALLBOX_TEST_TMP) / "xvfb.lock").string();
  // One Xvfb at a time (the lock the play window tests take): two xvfb-run -a can collide.
  const testing::ProgramRun run = testing::RunShell(
      "BALLBOX_SHAPES_PNG=window.png flock '" + lock +
          "' xvfb-run -a -s '-screen 0 1024x768x24' '" + self + "' '[.shapes_in_window]'",
      dir, dir.parent_path() / "window_captured");
  INFO("stdout: " << run.out << "\nstderr: " << run.err);
  REQUIRE(run.exit_code == 0);

  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load((dir / "window.png").c_str(), &width, &height, &channels, 3);
  REQUIRE(pixels != nullptr);
  const std::vector<std::uint8_t> shot(pixels, pixels + static_cast<std::size_t>(width) * height * 3);
  stbi_image_free(pixels);
  REQUIRE(width == kWidth);
  REQUIRE(height == kHeight);

  Gl gl = MakeGl();
  engine::World world(Still(true));
  AddEveryKind(world);
  const Image offscreen = Draw(gl, world, kEveryKindColors);
  // The same renderer on the same Mesa: equal but for a few edge pixels by a level or two.
  int differing = 0;
  for (std::size_t i = 0; i < shot.size(); ++i) {
    if (std::abs(shot[i] - offscreen.rgb[i]) > 2) ++differing;
  }
  CHECK(differing <= kWidth * kHeight / 1000);
  // And it holds the shapes: the capsule's middle, (3.1, 2.3), is pixel (131, 52).
  const std::size_t at = (52 * static_cast<std::size_t>(kWidth) + 131) * 3;
  CHECK(Show({shot[at], shot[at + 1], shot[at + 2]}) == Show(kOther));
}
