// What `ballbox render` films beyond the plain sequence: --camera, --follow (the follow camera's
// lag), --from, --hud, the progress bar's ETA, and a run interrupted with Ctrl-C or killed.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "game/film_camera.h"
#include "game/hud.h"
#include "game/progress_bar.h"
#include "game/session.h"
#include "render/bitmap_text.h"
#include "render/color.h"
#include "render/image.h"
#include "png_file.h"
#include "run_program.h"

namespace fs = std::filesystem;
using testing::Ballbox;
using engine::Vec2;

namespace {

fs::path FreshDir(const std::string& name) { return testing::FreshTestDir("film", name); }

using testing::LoadPng;

// A scene with one static box, 2 m square at (10, 10), coloured #c84 (0xcc, 0x88, 0x44).
void WriteBoxScene(const fs::path& path) {
  std::ofstream(path) << R"({"name": "box", "bodies": [
    {"id": "b", "shape": "box", "size": [2, 2], "position": [10, 10], "static": true, "color": "#c84"},
    {"id": "far", "shape": "circle", "radius": 1, "position": [-30, -30], "static": true}]})";
}

bool IsBox(render::Color c) { return c == render::Color{0xcc, 0x88, 0x44}; }

}  // namespace

TEST_CASE("render --camera: the picture shows X,Y at its centre, WIDTH metres across at 800x600",
          "[film][camera]") {
  const fs::path dir = FreshDir("camera");
  WriteBoxScene(dir / "box.json");
  // 4 m across 400 px: 100 px per metre, so the 2 m box covers columns 100 to 300.
  REQUIRE(Ballbox("render box.json --frames 1 --size 400x300 --camera 10,10,4 --out f", dir).exit_code == 0);
  const render::Image image = LoadPng(dir / "f" / "frame_00000.png");
  CHECK(IsBox(image.At(200, 150)));
  CHECK(IsBox(image.At(110, 150)));
  CHECK(IsBox(image.At(289, 60)));
  CHECK(image.At(90, 150) == render::kBackgroundColor);
  CHECK(image.At(310, 150) == render::kBackgroundColor);
  CHECK(image.At(200, 40) == render::kBackgroundColor);
  // At 16:9 the same camera keeps its 3 m height and shows more at the sides.
  REQUIRE(Ballbox("render box.json --frames 1 --size 640x360 --camera 10,10,4 --out w", dir).exit_code == 0);
  const render::Image wide = LoadPng(dir / "w" / "frame_00000.png");
  CHECK(IsBox(wide.At(320, 180)));
  CHECK(IsBox(wide.At(320, 65)));    // 120 px per metre: the box spans rows 60 to 300
  CHECK(wide.At(320, 55) == render::kBackgroundColor);
}

TEST_CASE("follow camera: starts on the body, keeps a steady mover centred, smooths a sudden turn",
          "[film][camera]") {
  engine::WorldDef def;
  def.gravity = {0, 0};
  engine::World world(def);
  engine::BodyDef ball;
  ball.shape = {engine::ShapeType::kCircle, 0.5, {}};
  ball.position = {3, 4};
  ball.velocity = {2, 0};
  const engine::BodyId id = world.CreateBody(ball);
  game::FilmCamera camera(render::Camera{{0, 0}, 20}, id, world);
  CHECK(camera.View().center == Vec2{3, 4});
  CHECK(camera.View().width == 20);
  for (int i = 0; i < 300; ++i) {  // 5 s: twenty time constants, the lag has settled
    world.Step();
    camera.Advance(world);
  }
  // The aim runs v·τ ahead, and a first-order lag of an aim moving v·dt a step settles at
  // v·dt·(1 − a)/a behind it, a = 1 − exp(−dt/τ): the camera leads the body by
  // v·τ − v·dt·(1 − a)/a, about v·dt/2 (a plain lag would trail it by v·τ = 0.5 m).
  const double dt = def.dt;
  const double tau = game::FilmCamera::kFollowSeconds;
  const double a = 1.0 - std::exp(-dt / tau);
  const double lead = camera.View().center.x - world.State(id).position.x;
  CHECK(lead == Approx(2.0 * tau - 2.0 * dt * (1.0 - a) / a).epsilon(1e-6));
  CHECK(std::abs(lead) < 2.0 * dt);
  CHECK(camera.View().center.y == 4.0);
  // The ball stops dead (as against a wall): the centre does not jump, it eases over.
  const double before = camera.View().center.x;
  world.ApplyLinearImpulseToCenter(id, {-2.0 * 3.14159265358979323846 * 0.25, 0});  // mass π·0.5², v = 2
  world.Step();
  camera.Advance(world);
  CHECK(std::abs(world.State(id).velocity.x) < 1e-12);
  CHECK(std::abs(camera.View().center.x - before) < 2.0 * 0.5 * a + 2.0 * dt);
  // Without a body to follow, the view stays put.
  game::FilmCamera still(render::Camera{{1, 2}, 20}, std::nullopt, world);
  still.Advance(world, 50);
  CHECK(still.View().center == Vec2{1, 2});
}

TEST_CASE("render --follow: the followed ball is at the centre of frame 0; an unknown id is exit 2",
          "[film][camera]") {
  const fs::path dir = FreshDir("follow");
  REQUIRE(Ballbox("render --frames 1 --size 200x150 --follow heavy_ball --out f", dir).exit_code == 0);
  REQUIRE(Ballbox("render --frames 1 --size 200x150 --out plain", dir).exit_code == 0);
  const render::Color heavy_ball{0x8e, 0x44, 0xad};
  CHECK(LoadPng(dir / "f" / "frame_00000.png").At(100, 75) == heavy_ball);
  CHECK(LoadPng(dir / "plain" / "frame_00000.png").At(100, 75) == render::kBackgroundColor);
  const testing::ProgramRun bad = Ballbox("render --frames 1 --follow heavy --out g", dir);
  CHECK(bad.exit_code == 2);
  CHECK(bad.err == "error: --follow: the default scene has no body with the id \"heavy\"\n");
  CHECK_FALSE(fs::exists(dir / "g"));
}

TEST_CASE("render --from STEP: frame k shows step STEP + k*K, the same pictures as a run from 0",
          "[film]") {
  const fs::path dir = FreshDir("from");
  REQUIRE(Ballbox("render --frames 41 --size 96x72 --out all", dir).exit_code == 0);
  const testing::ProgramRun run = Ballbox("render --from 30 --frames 3 --every 5 --size 96x72 --out part", dir);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("3 frames, 40 steps"));
  CHECK(testing::SortedNames(dir / "part") == std::vector<std::string>{"frame_00000.png", "frame_00001.png", "frame_00002.png"});
  CHECK(testing::ReadFile(dir / "part" / "frame_00000.png") == testing::ReadFile(dir / "all" / "frame_00030.png"));
  CHECK(testing::ReadFile(dir / "part" / "frame_00002.png") == testing::ReadFile(dir / "all" / "frame_00040.png"));
}

TEST_CASE("render --hud: the corner shows step, time and state hash; the rest is the plain frame",
          "[film][hud]") {
  CHECK(game::HudText(300, 5.0, 0x61e9c117a690e3b1u) == "STEP 300  T 5.000 S  HASH 61E9C117A690E3B1");
  const fs::path dir = FreshDir("hud");
  REQUIRE(Ballbox("render --frames 2 --every 300 --size 800x600 --hud --out hud", dir).exit_code == 0);
  REQUIRE(Ballbox("render --frames 2 --every 300 --size 800x600 --out plain", dir).exit_code == 0);
  const render::Image hud = LoadPng(dir / "hud" / "frame_00001.png");
  render::Image plain = LoadPng(dir / "plain" / "frame_00001.png");
  // Frame 1 shows step 300: the demo's hash there is 61e9c117a690e3b1 (README, sim --steps 300).
  const std::string text = game::HudText(300, 5.0, 0x61e9c117a690e3b1u);
  const int cell = 2;
  const int panel_width = render::TextWidth(text, cell) + 4 * cell;
  const int panel_height = render::kGlyphRows * cell + 4 * cell;
  int differing = 0, outside = 0;
  for (int y = 0; y < 600; ++y) {
    for (int x = 0; x < 800; ++x) {
      if (hud.At(x, y) == plain.At(x, y)) continue;
      ++differing;
      const bool in_panel = x >= 2 * cell && x < 2 * cell + panel_width && y >= 2 * cell && y < 2 * cell + panel_height;
      if (!in_panel) ++outside;
    }
  }
  CHECK(outside == 0);
  CHECK(differing > panel_width * panel_height / 2);
  game::PaintHud(plain, text);  // the plain frame with the expected text is the HUD frame exactly
  CHECK(plain.rgb == hud.rgb);
}

TEST_CASE("progress bar: the time left at the rate so far", "[film]") {
  CHECK(game::EtaText(0.2, 10, 100).empty());  // too early to tell
  CHECK(game::EtaText(5.0, 0, 100).empty());
  CHECK(game::EtaText(2.0, 50, 100) == "0:02");
  CHECK(game::EtaText(10.0, 10, 100) == "1:30");
  CHECK(game::EtaText(3600.0, 1, 3) == "2:00:00");
  CHECK(game::EtaText(1.0, 100, 100) == "0:00");
}

TEST_CASE("render interrupted with Ctrl-C: no temporary file or video left, and it says which frames "
          "are complete", "[film][interrupt]") {
  const fs::path dir = FreshDir("interrupt");
  // SIGINT once three frames are out, in the middle of a run far too long to finish. (At a fixed
  // second, a loaded machine could send it before the handler was in place: exit 130.)
  const testing::ProgramRun cut = testing::RunShell(
      "'" BALLBOX_EXE "' render --frames 10000000 --size 64x48 --out frames --video film.gif & pid=$!; "
      "for i in $(seq 1200); do [ -e frames/frame_00002.png ] && break; sleep 0.05; done; "
      "kill -INT $pid; wait $pid", dir, dir.parent_path() / "interrupt_cut");
  CHECK(cut.exit_code == 1);
  std::smatch m;
  const std::regex said(R"(error: interrupted at frame (\d+) of 10000000: frame_00000\.png to (frame_\d+\.png) in frames are complete; film\.gif was not written\n)");
  INFO(cut.err);
  REQUIRE(std::regex_match(cut.err, m, said));
  const int frames = std::stoi(m[1]);
  REQUIRE(frames > 1);
  char last[32];
  std::snprintf(last, sizeof last, "frame_%05d.png", frames - 1);
  CHECK(m[2] == last);
  CHECK(testing::SortedNames(dir) == std::vector<std::string>{"frames"});  // no film.gif, no film.gif.tmp-*
  const std::vector<std::string> names = testing::SortedNames(dir / "frames");
  CHECK(names.size() == static_cast<std::size_t>(frames));  // every frame named, nothing half-written
  CHECK(names.back() == last);
  CHECK(LoadPng(dir / "frames" / last).width == 64);
}

TEST_CASE("render: temporary frames of dead runs are removed, a live process's are kept", "[film]") {
  const fs::path dir = FreshDir("dead");
  fs::create_directories(dir / "f");
  // A process that has ended: its id is free (the kernel hands ids out in order, so it is not
  // reused within this test).
  const pid_t child = fork();
  if (child == 0) _exit(0);
  REQUIRE(child > 0);
  int status = 0;
  waitpid(child, &status, 0);
  const std::string dead = "frame_00003.png.tmp-" + std::to_string(child);
  const std::string live = "frame_00004.png.tmp-" + std::to_string(getpid());
  for (const std::string& name : {dead, live, std::string("frame_3.png.tmp-") + std::to_string(child),
                                  std::string("notes.tmp-") + std::to_string(child)}) {
    std::ofstream(dir / "f" / name) << "";
  }
  REQUIRE(Ballbox("render --frames 1 --size 32x24 --out f", dir).exit_code == 0);
  CHECK(testing::SortedNames(dir / "f") == std::vector<std::string>{"frame_00000.png", live,
                                                     "frame_3.png.tmp-" + std::to_string(child),
                                                     "notes.tmp-" + std::to_string(child)});
}
