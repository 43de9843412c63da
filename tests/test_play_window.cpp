// `ballbox play` end to end, as a user runs it: no display, and under Xvfb with real keys and
// clicks from xdotool (a screenshot against `ballbox render`, a click recorded and replayed,
// restart). Window tests are skipped, with a warning, where xvfb-run or xdotool is missing.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <stb/stb_image.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "game/click.h"
#include "game/grab.h"
#include "game/commands.h"
#include "game/script.h"
#include "game/session.h"
#include "render/window.h"
#include "run_program.h"
#include "xvfb_session.h"

namespace fs = std::filesystem;

namespace {

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "play_window" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using Run = testing::ProgramRun;
using testing::ReadFile;

// Runs a shell command in `cwd` with stdout and stderr captured to files outside it.
Run Shell(const std::string& command, const fs::path& cwd) { return testing::RunShell(command, cwd, cwd); }

std::string Exe() { return "'" BALLBOX_EXE "'"; }

using testing::EndPlay;
using testing::StartPausedPlay;
using testing::UnderXvfb;
using testing::WindowTestsCanRun;

std::string StateHash(const std::string& out) {
  std::smatch m;
  static const std::regex kHash("state-hash: ([0-9a-f]{16})\n$");
  return std::regex_search(out, m, kHash) ? m[1].str() : "";
}

struct Decoded {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

Decoded DecodePng(const fs::path& path) {
  Decoded image;
  int channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
  INFO(path);
  REQUIRE(pixels != nullptr);
  image.rgb.assign(pixels, pixels + static_cast<std::size_t>(image.width) * image.height * 3);
  stbi_image_free(pixels);
  return image;
}

void CheckPlayEnded(const fs::path& dir, const Run& session) {
  INFO("xvfb session stdout: " << session.out << "\nstderr: " << session.err);
  INFO("play stdout: " << ReadFile(dir / "play.out") << "play stderr: " << ReadFile(dir / "play.err"));
  REQUIRE(session.exit_code == 0);
  REQUIRE(ReadFile(dir / "play.rc") == "0\n");
}

}  // namespace

TEST_CASE("play window: no display exits 1 with the message, before anything else",
          "[play][cli]") {
  const fs::path dir = FreshDir("no_display");
  const bool built = render::WindowSupportBuilt();
  for (const std::string display : {"env -u DISPLAY", "env DISPLAY=", "env DISPLAY=:12345"}) {
    INFO(display);
    const Run run = Shell(display + " " + Exe() + " play --record rec.script --size 320x240", dir);
    INFO("stderr: " << run.err);
    CHECK(run.exit_code == 1);
    CHECK(run.out.empty());
    CHECK(run.err.rfind("error: ", 0) == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_THAT(run.err, Catch::Contains(built ? "no display" : "built without GLFW") &&
                            Catch::Contains("try ballbox render"));
    // No recording, no temporary file, no screenshot folder.
    CHECK(fs::is_empty(dir));
  }
  const Run unset = Shell("env -u DISPLAY " + Exe() + " play", dir);
  if (built) CHECK_THAT(unset.err, Catch::Contains("DISPLAY is not set"));
}

TEST_CASE("play window: bad input is exit 2, checked before the display", "[play][cli]") {
  const fs::path dir = FreshDir("bad_input");
  const Run missing = Shell("env -u DISPLAY " + Exe() + " play missing.json", dir);
  CHECK(missing.exit_code == 2);
  CHECK_THAT(missing.err, Catch::StartsWith("error: missing.json"));
  const Run hook = Shell("env -u DISPLAY BALLBOX_PLAY_STOP_AT=ten " + Exe() + " play", dir);
  CHECK(hook.exit_code == 2);
  CHECK_THAT(hook.err, Catch::Contains("BALLBOX_PLAY_STOP_AT"));
  CHECK(fs::is_empty(dir));
}

TEST_CASE("play window: a screenshot (S) shows the same picture as ballbox render at that step",
          "[play][xvfb]") {
  if (!WindowTestsCanRun()) return;
  const fs::path dir = FreshDir("screenshot");
  // Paused at step 90 (the demo click of step 90 not yet applied, as in render), then S twice.
  const Run session = UnderXvfb(
      StartPausedPlay("BALLBOX_PLAY_PAUSE_AT=90", "--size 320x240", 90) +
          "timeout 30 xdotool key --delay 50 s s Escape\n" + EndPlay(),
      dir);
  CheckPlayEnded(dir, session);
  const std::string out = ReadFile(dir / "play.out");
  CHECK_THAT(out, Catch::Contains("play: screenshot at step 90 -> screenshots/default_step_000090.png\n"));
  // The second one is not written over the first.
  CHECK_THAT(out, Catch::Contains("-> screenshots/default_step_000090-2.png\n"));
  CHECK_THAT(out, Catch::Contains("play: stopped at step 90"));

  // ballbox render's frame 1 with --every 90: the world after 90 steps, 320x240.
  const Run render = Shell(Exe() + " render --frames 2 --every 90 --size 320x240 --out frames", dir);
  REQUIRE(render.exit_code == 0);
  const Decoded shot = DecodePng(dir / "screenshots" / "default_step_000090.png");
  const Decoded frame = DecodePng(dir / "frames" / "frame_00001.png");
  REQUIRE(shot.width == 320);
  REQUIRE(shot.height == 240);
  REQUIRE(frame.width == 320);
  REQUIRE(frame.height == 240);
  // The same renderer on the same Mesa: equal but for at most a few edge pixels by a few levels.
  int differing = 0;
  int largest = 0;
  for (std::size_t i = 0; i < shot.rgb.size(); i += 3) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(shot.rgb[i + c] - frame.rgb[i + c]));
    largest = std::max(largest, d);
    if (d > 2) ++differing;
  }
  INFO("pixels differing by more than 2 levels: " << differing << ", largest difference "
                                                  << largest);
  CHECK(differing <= 320 * 240 / 1000);
  // And it is not the initial picture: the scene moved in those 90 steps.
  const Run first = Shell(Exe() + " render --frames 1 --size 320x240 --out frame0", dir);
  REQUIRE(first.exit_code == 0);
  CHECK(DecodePng(dir / "frame0" / "frame_00000.png").rgb != shot.rgb);
}

TEST_CASE("play window: an xdotool click hits a ball, and the recording replays to the live hash",
          "[play][xvfb][record]") {
  if (!WindowTestsCanRun()) return;
  const fs::path dir = FreshDir("click");
  constexpr int kWidth = 400;
  constexpr int kHeight = 300;
  constexpr std::int64_t kClickStep = 60;
  constexpr std::int64_t kStopStep = 150;

  // Where heavy_ball is at step 60 in play --size 400x300 (the default scene and its demo
  // clicks, which map through the 400x300 picture): aim half a radius left of its centre.
  game::Expected<game::RunInput> input = game::LoadRunInput(game::RunOptions{});
  REQUIRE(input.HasValue());
  game::Session aim(input.Value().scene, input.Value().events, kWidth, kHeight);
  for (std::int64_t i = 0; i < kClickStep; ++i) aim.Step();
  engine::BodyId heavy{0};
  while (input.Value().scene.bodies[heavy.index].id != "heavy_ball") ++heavy.index;
  const engine::Vec2 centre = aim.World().State(heavy).position;
  const double radius = aim.World().Info(heavy).shape.radius;
  const engine::Vec2 pixel = render::WorldToPixel(aim.Camera(), kWidth, kHeight,
                                                  {centre.x - 0.5 * radius, centre.y});
  INFO("heavy_ball at (" << centre.x << ", " << centre.y << "), radius " << radius
                          << ": clicking pixel (" << pixel.x << ", " << pixel.y << ")");
  REQUIRE((pixel.x > 0 && pixel.x < kWidth && pixel.y > 0 && pixel.y < kHeight));
  const long px = std::lround(pixel.x);
  const long py = std::lround(pixel.y);

  const std::string env = "BALLBOX_PLAY_PAUSE_AT=" + std::to_string(kClickStep) +
                          " BALLBOX_PLAY_STOP_AT=" + std::to_string(kStopStep);
  const Run session = UnderXvfb(
      StartPausedPlay(env, "--record rec.script --size 400x300", kClickStep) +
          "timeout 30 xdotool mousemove --window \"$wid\" " + std::to_string(px) + " " +
          std::to_string(py) + " click 1 key space\n" + EndPlay(),
      dir);
  CheckPlayEnded(dir, session);
  const std::string out = ReadFile(dir / "play.out");
  INFO("play: " << out);
  CHECK_THAT(out, Catch::Contains("play: stopped at step 150 (2.500 s simulated)\n"));
  const std::string live = StateHash(out);
  REQUIRE(live.size() == 16);

  // The recording: the demo clicks before step 150 and the live click, at step 60, as world
  // points; the live one lies on heavy_ball as it was at step 60.
  game::Expected<std::vector<game::InputEvent>> recorded = game::LoadScript((dir / "rec.script").string());
  REQUIRE(recorded.HasValue());
  std::vector<game::InputEvent> at_click_step;
  for (const game::InputEvent& e : recorded.Value()) {
    CHECK(e.kind == game::EventKind::kClickWorld);
    if (e.step == kClickStep) at_click_step.push_back(e);
  }
  REQUIRE(at_click_step.size() == 1);
  const std::optional<game::ClickHit> hit =
      game::ResolveClick(aim.World(), at_click_step[0].at, input.Value().scene.click_max_impulse);
  REQUIRE(hit);
  CHECK(hit->body == heavy);
  CHECK(hit->impulse.x > 0.0);  // clicked left of the centre: pushed to the right
  CHECK(recorded.Value().size() == 4);  // demo clicks at 40, 90, 130 and the live one
  // The size line names the picture the clicks were made on. The summary counts all four: the
  // live push sends heavy_ball elsewhere, so the demo clicks at 90 and 130, aimed for the run
  // without it, now miss.
  CHECK_THAT(ReadFile(dir / "rec.script"), Catch::Contains("\nsize 400 300\n"));
  CHECK_THAT(out, Catch::Contains("\nevents: 4 clicks applied, 2 hit a ball, 2 missed (--misses lists where); "
                                  "3 events after the end "
                                  "of the run (the first at step 170; the run ended before simulating step "
                                  "150)\nstate-hash: "));

  // sim replays the recording to the live hash (at any --size: the points are world points).
  const Run sim = Shell(Exe() + " sim --script rec.script --steps 150", dir);
  INFO("sim: " << sim.out << sim.err);
  REQUIRE(sim.exit_code == 0);
  CHECK(StateHash(sim.out) == live);
  const Run sim_other_size = Shell(Exe() + " sim --script rec.script --steps 150 --size 97x61", dir);
  CHECK(StateHash(sim_other_size.out) == live);
  // Without the live click the run ends elsewhere: the click did something.
  const Run plain = Shell(Exe() + " sim --steps 150 --size 400x300", dir);
  CHECK(StateHash(plain.out) != live);

  // play replays the recording in the window too (--script), to the same hash.
  const Run replay = UnderXvfb(
      "BALLBOX_PLAY_STOP_AT=150 timeout 120 " + Exe() + " play --script rec.script --size 400x300",
      dir);
  INFO("replay: " << replay.out << replay.err);
  REQUIRE(replay.exit_code == 0);
  CHECK(StateHash(replay.out) == live);
}

TEST_CASE("play window: R restarts the scene, the script and the recording", "[play][xvfb][record]") {
  if (!WindowTestsCanRun()) return;
  const fs::path dir = FreshDir("restart");
  // Past the demo click at step 40, R; the game restarts paused (as it was) at step 0; space
  // runs it to step 50.
  const Run session = UnderXvfb(
      StartPausedPlay("BALLBOX_PLAY_PAUSE_AT=45 BALLBOX_PLAY_STOP_AT=50", "--record rec.script", 45) +
          "timeout 30 xdotool key r\n"
          "timeout 60 xdotool search --sync --name 'paused at step 0\\)' >/dev/null\n"
          "timeout 30 xdotool key space\n" +
          EndPlay(),
      dir);
  CheckPlayEnded(dir, session);
  const std::string out = ReadFile(dir / "play.out");
  INFO("play: " << out);
  CHECK_THAT(out, Catch::Contains("play: restart at step 45"));
  CHECK_THAT(out, Catch::Contains("play: stopped at step 50"));
  // The recording holds the run since the restart: the demo click at 40 once.
  game::Expected<std::vector<game::InputEvent>> recorded = game::LoadScript((dir / "rec.script").string());
  REQUIRE(recorded.HasValue());
  REQUIRE(recorded.Value().size() == 1);
  CHECK(recorded.Value()[0].step == 40);
  // The state is a fresh run's at step 50, and the recording replays to it.
  const Run fresh = Shell(Exe() + " sim --steps 50", dir);
  const Run replay = Shell(Exe() + " sim --script rec.script --steps 50", dir);
  CHECK(StateHash(out) == StateHash(fresh.out));
  CHECK(StateHash(out) == StateHash(replay.out));
}

TEST_CASE("play window: a right-button drag with xdotool lifts the crate, and the recording "
          "replays to the live hash in sim and play", "[play][xvfb][record][drag]") {
  if (!WindowTestsCanRun()) return;
  const fs::path dir = FreshDir("drag");
  // A 1 kg crate on a floor; at 400x300 the camera's 8 m make 50 pixels a metre, so the crate's
  // centre (0, 0.5) is pixel (200, 225) and pixel (260, 100) is the world point (1.2, 3).
  std::ofstream(dir / "drag.json") << R"({
    "name": "drag",
    "camera": { "center": [0, 2], "width": 8 },
    "bodies": [
      { "id": "floor", "shape": "box", "size": [8, 1], "position": [0, -0.5], "static": true },
      { "id": "crate", "shape": "box", "size": [1, 1], "position": [0, 0.5], "mass": 1 }
    ]
  })";
  // Paused at step 10: the right button goes down on the crate and drags it up and right; 20
  // single steps ('.') with the button held, then it goes up, one more step, and on to step 100.
  std::string steps;
  for (int i = 0; i < 20; ++i) steps += " period";
  const Run session = UnderXvfb(
      StartPausedPlay("BALLBOX_PLAY_PAUSE_AT=10 BALLBOX_PLAY_STOP_AT=100",
                      "drag.json --record rec.script --size 400x300", 10) +
          "timeout 30 xdotool mousemove --window \"$wid\" 200 225 mousedown 3 "
          "mousemove --window \"$wid\" 230 160 mousemove --window \"$wid\" 260 100\n"
          "timeout 30 xdotool key --delay 40" + steps + "\n"
          "timeout 30 xdotool mouseup 3 key --delay 40 period space\n" + EndPlay(),
      dir);
  CheckPlayEnded(dir, session);
  const std::string out = ReadFile(dir / "play.out");
  INFO("play: " << out);
  CHECK_THAT(out, Catch::Contains("play: stopped at step 100"));
  CHECK_THAT(out, Catch::Contains("events: 1 grab (1 took hold of a body), "));
  CHECK_THAT(out, Catch::Contains(", 1 release\nstate-hash: "));
  const std::string live = StateHash(out);
  REQUIRE(live.size() == 16);

  // The recording: the grab and the drag at step 10, the release at step 30, as world points.
  game::Expected<std::vector<game::InputEvent>> recorded = game::LoadScript((dir / "rec.script").string());
  REQUIRE(recorded.HasValue());
  const std::vector<game::InputEvent>& events = recorded.Value();
  REQUIRE(events.size() >= 3);
  CHECK(events.front().kind == game::EventKind::kGrabWorld);
  CHECK(events.front().step == 10);
  CHECK(events.front().at.x == Approx(0.0).margin(1e-9));
  CHECK(events.front().at.y == Approx(0.5).margin(1e-9));
  CHECK(events[events.size() - 2].kind == game::EventKind::kDragWorld);
  CHECK(events[events.size() - 2].step == 10);
  CHECK(events[events.size() - 2].at.x == Approx(1.2).margin(1e-9));
  CHECK(events[events.size() - 2].at.y == Approx(3.0).margin(1e-9));
  CHECK(events.back().kind == game::EventKind::kRelease);
  CHECK(events.back().step == 30);

  // sim replays it to the live hash, at any --size; the crate was lifted while held.
  const Run sim = Shell(Exe() + " sim drag.json --script rec.script --steps 100 --dump d.csv", dir);
  INFO("sim: " << sim.out << sim.err);
  REQUIRE(sim.exit_code == 0);
  CHECK(StateHash(sim.out) == live);
  CHECK(StateHash(Shell(Exe() + " sim drag.json --script rec.script --steps 100 --size 97x61", dir).out) == live);
  CHECK(StateHash(Shell(Exe() + " sim drag.json --steps 100", dir).out) != live);
  std::ifstream csv(dir / "d.csv");
  std::string line;
  double lifted_y = 0.0;
  while (std::getline(csv, line)) {
    if (line.rfind("30,", 0) == 0 && line.find(",crate,") != std::string::npos) {
      std::vector<std::string> fields;
      std::stringstream row(line);
      for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
      lifted_y = std::stod(fields[4]);
    }
  }
  CHECK(lifted_y > 2.5);  // held 20 steps under the target at y = 3

  // play replays the recording in the window too, to the same hash.
  const Run replay = UnderXvfb(
      "BALLBOX_PLAY_STOP_AT=100 timeout 120 " + Exe() + " play drag.json --script rec.script --size 400x300",
      dir);
  INFO("replay: " << replay.out << replay.err);
  REQUIRE(replay.exit_code == 0);
  CHECK(StateHash(replay.out) == live);
}
