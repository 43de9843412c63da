// A scene's soft-body and fluid colours reach the picture (game/scene_colors.h), run as the
// user runs it: `ballbox render` of a still scene, each colour looked for where the contract's
// camera puts its particles, with the renderer's defaults where the scene gives none; and
// `ballbox play` draws them the same (a screenshot under Xvfb, skipped where it is missing).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/color.h"
#include "render/image.h"
#include "render/particle_style.h"
#include "png_file.h"
#include "run_program.h"
#include "xvfb_session.h"

namespace fs = std::filesystem;
using render::Color;

namespace {

fs::path FreshDir(const std::string& name) { return testing::FreshTestDir("scene_colors", name); }

using testing::LoadPng;

// No gravity, so frame 0 and a few steps later look alike. The camera is 20 m across 200x150
// pixels (4:3, so the 800x600 region): 0.1 m a pixel, world (x, y) at pixel
// (100 + 10x, 75 − 10y) by the contract's mapping. A 2 m soft box centred at (−5, 2) covers
// pixels 40..59 × 45..64; a soft ball of radius 1 at (−5, −3) covers a disc of 10 px around
// (50, 105); the fluid block [2, 6] × [−3, 1] covers pixels 120..159 × 65..104 (the liquid
// reaches a little beyond). The colours are the scene's `color` keys, or empty for none.
std::string StillScene(const std::string& box_color, const std::string& ball_color,
                       const std::string& fluid_color) {
  auto color = [](const std::string& c) { return c.empty() ? std::string() : ", \"color\": \"" + c + "\""; };
  return R"({"name": "colours", "gravity": [0, 0], "camera": {"center": [0, 0], "width": 20},
    "bodies": [{"id": "post", "shape": "box", "size": [1, 1], "position": [-8, 6], "static": true}],
    "soft_bodies": [
      {"shape": "box", "size": [2, 2], "position": [-5, 2], "spacing": 0.2)" + color(box_color) + R"(},
      {"shape": "circle", "radius": 1, "position": [-5, -3], "spacing": 0.2)" + color(ball_color) + R"(}],
    "fluids": [
      {"region": [[2, -3], [4, 1]], "spacing": 0.2)" + color(fluid_color) + R"(},
      {"region": [[4, -3], [6, 1]]}]})";
}

// The soft box's, the soft ball's and the fluid's centre pixels, with the pixels around each
// that lie well inside it (away from the outlines and the liquid's lighter rim).
struct Spots {
  std::vector<std::pair<int, int>> box, ball, fluid;
};

Spots Inside() {
  Spots spots;
  for (int d = -4; d <= 4; d += 2) {
    spots.box.push_back({50 + d, 55 - d});
    spots.ball.push_back({50 + d, 105 + d});
  }
  for (int i = 125; i <= 155; i += 5) spots.fluid.push_back({i, 85});
  return spots;
}

// `over` laid on `under` by `alpha`, rounded as an 8-bit framebuffer keeps it.
Color Over(Color over, double alpha, Color under) {
  auto mix = [alpha](int a, int b) { return static_cast<std::uint8_t>(std::lround(alpha * a + (1.0 - alpha) * b)); };
  return {mix(over.r, under.r), mix(over.g, under.g), mix(over.b, under.b)};
}

int Difference(Color a, Color b) {
  return std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
}

// Every spot is `expected` (within `tolerance` levels: blending rounds).
void CheckSpots(const render::Image& image, const std::vector<std::pair<int, int>>& spots, Color expected,
                int tolerance) {
  for (const auto& [x, y] : spots) {
    const Color seen = image.At(x, y);
    INFO("pixel (" << x << ", " << y << ") is (" << int{seen.r} << ", " << int{seen.g} << ", " << int{seen.b}
                   << "), expected (" << int{expected.r} << ", " << int{expected.g} << ", " << int{expected.b} << ")");
    CHECK(Difference(seen, expected) <= tolerance);
  }
}

// Renders `scene` (frame 0, 200x150) in `dir` and reads the frame back.
render::Image RenderStill(const fs::path& dir, const std::string& scene) {
  std::ofstream(dir / "scene.json") << scene;
  const testing::ProgramRun run = testing::Ballbox("render scene.json --frames 1 --size 200x150 --out f", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  return LoadPng(dir / "f" / "frame_00000.png");
}

}  // namespace

TEST_CASE("render draws each soft body and the fluid in the scene's colours", "[scene_colors][render]") {
  const fs::path dir = FreshDir("given");
  const render::Image image = RenderStill(dir, StillScene("#ff0000", "#0000ff", "#00ff00"));
  const Spots spots = Inside();
  // Soft bodies are filled with their colour exactly, each in its own place (slot = scene order).
  CheckSpots(image, spots.box, Color{255, 0, 0}, 0);
  CheckSpots(image, spots.ball, Color{0, 0, 255}, 0);
  // The liquid lies over the background at the renderer's opacity; the second block, which
  // gives no colour, is the first's.
  CheckSpots(image, spots.fluid, Over(Color{0, 255, 0}, render::kFluidOpacity, render::kBackgroundColor), 2);
  // Between them, and far from them, the background.
  CHECK(image.At(100, 75) == render::kBackgroundColor);
  CHECK(image.At(50, 140) == render::kBackgroundColor);
}

TEST_CASE("render draws soft bodies and fluid in the renderer's defaults where the scene gives no colour",
          "[scene_colors][render]") {
  const fs::path dir = FreshDir("defaults");
  const render::Image image = RenderStill(dir, StillScene("", "", ""));
  const Spots spots = Inside();
  CheckSpots(image, spots.box, render::kSoftBodyColor, 0);
  CheckSpots(image, spots.ball, render::kSoftBodyColor, 0);
  CheckSpots(image, spots.fluid, Over(render::kFluidColor, render::kFluidOpacity, render::kBackgroundColor), 2);
}

TEST_CASE("play window: the scene's particle colours drawn as render draws them (a screenshot under Xvfb)",
          "[scene_colors][play][xvfb]") {
  if (!testing::WindowTestsCanRun()) return;
  const fs::path dir = FreshDir("play");
  std::ofstream(dir / "scene.json") << StillScene("#ff0000", "#0000ff", "#00ff00");
  const testing::ProgramRun session = testing::UnderXvfb(
      testing::StartPausedPlay("BALLBOX_PLAY_PAUSE_AT=0", "scene.json --size 200x150", 0) +
          "timeout 30 xdotool key --delay 50 s Escape\n" + testing::EndPlay(),
      dir);
  INFO("session: " << session.err << "play: " << testing::ReadFile(dir / "play.err"));
  REQUIRE(session.exit_code == 0);
  REQUIRE(testing::ReadFile(dir / "play.rc") == "0\n");
  const render::Image image = LoadPng(dir / "screenshots" / "colours_step_000000.png");
  REQUIRE(image.width == 200);
  const Spots spots = Inside();
  CheckSpots(image, spots.box, Color{255, 0, 0}, 0);
  CheckSpots(image, spots.ball, Color{0, 0, 255}, 0);
  CheckSpots(image, spots.fluid, Over(Color{0, 255, 0}, render::kFluidOpacity, render::kBackgroundColor), 2);
}
