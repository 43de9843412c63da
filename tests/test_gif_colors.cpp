// The colours a GIF film's palette keeps (game/gif_colors.h): a scene without particles keeps
// what it kept before (so its GIF keeps its bytes), the liquid's entry is the colour the
// renderer draws it in, and effect particles, which the first frame (the palette's source)
// does not show yet, come out of the GIF close to their PNG frames.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "game/gif_colors.h"
#include "game/scene.h"
#include "game/scene_colors.h"
#include "offscreen_gl.h"
#include "render/bitmap_text.h"
#include "render/color.h"
#include "png_file.h"
#include "run_program.h"

namespace fs = std::filesystem;
using render::Color;

namespace {

game::Scene Parse(const std::string& json) {
  game::Expected<game::Scene> scene = game::ParseScene(json, "gif.json", "gif");
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

bool Holds(const std::vector<Color>& colors, Color c) {
  return std::find(colors.begin(), colors.end(), c) != colors.end();
}

}  // namespace

TEST_CASE("gif colours: a scene without particles keeps the background, the HUD's and the bodies' colours only",
          "[gif]") {
  const game::Scene scene = Parse(R"({"bodies": [
    {"shape": "box", "size": [4, 1], "position": [0, 0], "static": true},
    {"shape": "circle", "radius": 0.5, "position": [0, 2], "color": "#123456"}]})");
  const std::vector<Color> expected = {render::kBackgroundColor, render::kPanelBackdrop, render::kPanelText,
                                       render::kStaticColor, Color{0x12, 0x34, 0x56}};
  CHECK(game::GifKeepColors(scene, game::BuildWorld(scene)) == expected);
}

TEST_CASE("gif colours: soft bodies' fills are kept, and the liquid as the renderer draws it over the background",
          "[gif][render]") {
  // 20 m across 200x150 pixels: the fluid block's centre (4, −1) at pixel (140, 85).
  const game::Scene scene = Parse(R"({"gravity": [0, 0], "camera": {"center": [0, 0], "width": 20},
    "bodies": [{"shape": "box", "size": [1, 1], "position": [-8, 6], "static": true}],
    "soft_bodies": [{"shape": "circle", "radius": 1, "position": [-5, 2], "color": "#ff0000"}],
    "fluids": [{"region": [[2, -3], [6, 1]], "spacing": 0.2, "color": "#00ff00"}]})");
  const engine::World world = game::BuildWorld(scene);
  const std::vector<Color> keep = game::GifKeepColors(scene, world);
  CHECK(Holds(keep, Color{255, 0, 0}));
  testing::OffscreenGl gl = testing::MakeOffscreenGl(200, 150);
  const game::SceneColors colors = game::ColorsOf(scene);
  gl.renderer->Draw(world, colors.bodies, render::Camera{{0, 0}, 20}, {}, colors.particles);
  render::Image image;
  gl.renderer->ReadImage(image);
  const Color liquid = image.At(140, 85);
  INFO("the liquid is drawn (" << int{liquid.r} << ", " << int{liquid.g} << ", " << int{liquid.b} << ")");
  CHECK(liquid != render::kBackgroundColor);
  CHECK(Holds(keep, liquid));
}

#if BALLBOX_VIDEO_PROBE
#include "video_probe.h"

TEST_CASE("render --video: a GIF shows effect particles born after its first frame in colours close to the PNGs",
          "[gif][video]") {
  const fs::path dir = testing::FreshTestDir("gif_colors", "effects");
  // A blue spray (alpha), grey smoke (alpha) and an orange fire (additive) over it: none of
  // their colours is in the first frame, which shows no particle yet.
  std::ofstream(dir / "effects.json") << R"({"name": "effects", "camera": {"center": [0, 2.5], "width": 10},
    "bodies": [{"shape": "box", "size": [10, 0.4], "position": [0, -0.2], "static": true}],
    "emitters": [
      {"position": [-2.5, 0.2], "direction": 1.5707963267948966, "spread": 0.2, "speed": 5, "rate": 150,
       "lifetime": 1.2, "size": [0.2, 0.3], "color": ["#2060ffee", "#80c0ff00"], "blend": "alpha", "seed": 1},
      {"position": [2.5, 1], "direction": 1.5707963267948966, "spread": 0.3, "speed": 0.6, "rate": 30,
       "lifetime": 2, "size": [0.3, 0.8], "color": ["#55555588", "#88888800"], "blend": "alpha", "buoyancy": 1.3,
       "collide": false, "seed": 2},
      {"position": [2.5, 0.2], "direction": 1.5707963267948966, "spread": 0.35, "speed": 0.8, "rate": 120,
       "lifetime": 0.9, "size": [0.4, 0.05], "color": ["#ffa020ff", "#ff200000"], "blend": "additive",
       "buoyancy": 1.6, "collide": false, "seed": 3}]})";
  const testing::ProgramRun run =
      testing::Ballbox("render effects.json --frames 30 --every 2 --size 200x150 --out frames --video film.gif", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const testing::ProbedVideo video = testing::ProbeVideo((dir / "film.gif").string(), 30);
  INFO(video.error);
  REQUIRE(video.rgb.size() == 30);  // 30 frames/s: every frame kept
  auto load = [&](int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", frame);
    return testing::LoadPng(dir / "frames" / name).rgb;
  };
  const std::vector<std::uint8_t> first = load(0);
  for (const int frame : {15, 29}) {
    const std::vector<std::uint8_t> png = load(frame);
    REQUIRE(png.size() == video.rgb[frame].size());
    // The particles' pixels: those that differ from the first frame. Each within 24 levels in the GIF.
    int particles = 0, off = 0;
    for (std::size_t i = 0; i < png.size(); i += 3) {
      if (std::equal(&png[i], &png[i] + 3, &first[i])) continue;
      ++particles;
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(png[i + c] - video.rgb[frame][i + c]));
      if (d > 24) ++off;
    }
    INFO("frame " << frame << ": " << off << " of " << particles << " particle pixels more than 24 levels off");
    CHECK(particles > 300);
    CHECK(off <= particles / 10);  // 59% of them at frame 15 when the palette knew only the first frame
  }
}
#endif
