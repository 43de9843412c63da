// `ballbox play` without a window: the fixed-step clock against a plain loop, the controller's
// pause, step, restart and recording (replayed as sim replays it), letterboxing and click
// mapping, the status line's font, and screenshots that never overwrite.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "game/click.h"
#include "game/commands.h"
#include "game/frame_clock.h"
#include "game/grab.h"
#include "game/play_controller.h"
#include "game/play_view.h"
#include "game/screenshot.h"
#include "game/session.h"
#include "render/bitmap_text.h"

namespace fs = std::filesystem;

namespace {

constexpr double kDt = 1.0 / 60.0;

game::RunInput DefaultInput() {
  game::Expected<game::RunInput> input = game::LoadRunInput(game::RunOptions{});
  REQUIRE(input.HasValue());
  return input.Value();
}

// The state hash after every step 0 … steps of a plain loop: Session::Step, one at a time.
std::vector<std::uint64_t> PlainLoopHashes(const game::RunInput& input, int width, int height,
                                           std::int64_t steps) {
  game::Session session(input.scene, input.events, width, height);
  std::vector<std::uint64_t> hashes{session.World().StateHash()};
  for (std::int64_t i = 0; i < steps; ++i) {
    session.Step();
    hashes.push_back(session.World().StateHash());
  }
  return hashes;
}

std::size_t BodyIndex(const game::Scene& scene, const std::string& id) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].id == id) return i;
  }
  FAIL("no body " << id);
  return 0;
}

// A click just left of a ball's centre: it hits, and pushes the ball to the right.
engine::Vec2 ClickBeside(const game::PlayController& controller, std::size_t body) {
  const engine::World& world = controller.GetSession().World();
  const engine::Vec2 c = world.State(static_cast<engine::BodyId>(body)).position;
  return {c.x - 0.5 * world.Info(static_cast<engine::BodyId>(body)).shape.radius, c.y};
}

std::uint64_t ReplayHash(const game::Scene& scene, const std::vector<game::InputEvent>& events,
                         int width, int height, std::int64_t steps) {
  game::Session session(scene, events, width, height);
  for (std::int64_t i = 0; i < steps; ++i) session.Step();
  return session.World().StateHash();
}

}  // namespace

TEST_CASE("frame clock: real time becomes whole steps of dt, the rest carried to the next frame",
          "[play][clock]") {
  game::FrameClock clock(kDt);
  // 16 frames of 1 ms are less than one step; the 17th completes it.
  for (int i = 0; i < 16; ++i) CHECK(clock.Advance(0.001) == 0);
  CHECK(clock.Advance(0.001) == 1);
  CHECK(clock.SecondsToNextStep() > 0.0);
  CHECK(clock.SecondsToNextStep() <= kDt);

  // Ten seconds of 1 ms frames give ten seconds of steps: nothing lost to rounding.
  game::FrameClock steady(kDt);
  std::int64_t steps = 0;
  for (int i = 0; i < 10000; ++i) steps += steady.Advance(0.001);
  CHECK(std::abs(steps - 600) <= 1);

  // A clock that jumps back, or a garbage time, owes nothing.
  game::FrameClock odd(kDt);
  CHECK(odd.Advance(-1.0) == 0);
  CHECK(odd.Advance(std::numeric_limits<double>::quiet_NaN()) == 0);
  CHECK(odd.SecondsToNextStep() == kDt);
}

TEST_CASE("frame clock: the frame-time clamp bounds the steps of a slow frame", "[play][clock]") {
  game::FrameClock clock(kDt);  // clamp: kMaxFrameSeconds = 0.25 s
  REQUIRE(clock.MaxStepsPerFrame() == 16);  // floor(0.25 / dt) + 1 (the carried remainder)
  // A 1 s stall counts as 0.25 s: 15 steps, not 60, so the next frame is not slower still.
  CHECK(clock.Advance(1.0) == 15);
  CHECK(clock.Advance(1e9) <= clock.MaxStepsPerFrame());
  for (const double frame : {0.001, 0.0167, 0.05, 0.2499, 0.26, 1.0, 3600.0}) {
    for (int i = 0; i < 50; ++i) {
      const int n = clock.Advance(frame);
      CHECK(n >= 0);
      CHECK(n <= clock.MaxStepsPerFrame());
    }
  }
  // After Reset nothing is owed: a resumed game starts a fresh step.
  clock.Advance(0.016);
  clock.Reset();
  CHECK(clock.SecondsToNextStep() == kDt);
}

TEST_CASE("play controller: any frame times reach the plain loop's states at the same steps",
          "[play][clock]") {
  const game::RunInput input = DefaultInput();  // the default scene with its demo clicks
  constexpr std::int64_t kSteps = 300;
  const std::vector<std::uint64_t> plain = PlainLoopHashes(input, 800, 600, kSteps + 20);

  const std::map<std::string, std::vector<double>> frame_patterns = {
      {"1 ms", {0.001}},
      {"16.7 ms", {0.0167}},
      {"50 ms", {0.05}},
      {"1 s (clamped)", {1.0}},
      {"mixed", {0.001, 0.0167, 0.05, 1.0, 0.0003, 0.033}},
  };
  for (const auto& [name, pattern] : frame_patterns) {
    INFO("frame times: " << name);
    game::PlayController controller(input.scene, input.events, 800, 600);
    std::int64_t frames = 0;
    std::int64_t compared = 0;
    int most_steps = 0;
    while (controller.GetSession().StepIndex() < kSteps) {
      const int taken = controller.Advance(pattern[frames % pattern.size()]);
      most_steps = std::max(most_steps, taken);
      ++frames;
      const std::int64_t step = controller.GetSession().StepIndex();
      INFO("step " << step << " after frame " << frames);
      REQUIRE(controller.GetSession().World().StateHash() == plain[step]);
      ++compared;
    }
    CHECK(most_steps <= controller.MaxStepsPerFrame());
    // The demo clicks were applied on the way, each before its own step, as sim does.
    CHECK(controller.Recorded().size() ==
          static_cast<std::size_t>(std::count_if(input.events.begin(), input.events.end(),
                                                 [](const auto& e) { return e.step < kSteps; })));
    CHECK(compared == frames);
  }
}

TEST_CASE("play controller: the recording replays to the live state, at any image size",
          "[play][record]") {
  const game::RunInput input = DefaultInput();
  const std::size_t heavy = BodyIndex(input.scene, "heavy_ball");
  const std::size_t bouncy = BodyIndex(input.scene, "bouncy_ball");
  // 640x480: the demo's pixel clicks map through this picture, as `play --size 640x480` does.
  game::PlayController controller(input.scene, input.events, 640, 480);

  // Live clicks at odd moments: mid-frame, two in one step, while paused, and one that misses.
  controller.Advance(0.5);  // clamped to 0.25 s: 15 steps
  controller.Click(ClickBeside(controller, heavy));
  controller.Advance(0.0101);
  controller.Advance(0.0101);
  controller.Click(ClickBeside(controller, bouncy));
  controller.Click(ClickBeside(controller, bouncy));
  controller.TogglePause();
  controller.Advance(0.05);
  controller.Click(ClickBeside(controller, heavy));
  controller.StepOnce();
  controller.Click({100.0, 100.0});  // hits nothing: recorded all the same
  controller.StepOnce();
  controller.TogglePause();
  while (controller.GetSession().StepIndex() < 240) controller.Advance(0.0167);
  const std::int64_t steps = controller.GetSession().StepIndex();
  const std::uint64_t live = controller.GetSession().World().StateHash();

  // Every click applied is recorded as the world point it acted on, steps in order.
  const std::vector<game::InputEvent>& recorded = controller.Recorded();
  REQUIRE(recorded.size() >= 5);
  CHECK(std::is_sorted(recorded.begin(), recorded.end(),
                       [](const auto& a, const auto& b) { return a.step < b.step; }));
  for (const game::InputEvent& e : recorded) CHECK(e.kind == game::EventKind::kClickWorld);

  // Written, read back and replayed the way sim and render replay a script, at other sizes.
  const std::string text = game::FormatScript(recorded);
  game::Expected<std::vector<game::InputEvent>> parsed = game::ParseScript(text, "recorded");
  REQUIRE(parsed.HasValue());
  for (const auto& [width, height] : {std::pair{640, 480}, {800, 600}, {123, 77}}) {
    INFO("replayed at " << width << "x" << height);
    CHECK(ReplayHash(input.scene, parsed.Value(), width, height, steps) == live);
  }
  // The live clicks mattered: without them the state differs.
  game::PlayController untouched(input.scene, input.events, 640, 480);
  while (untouched.GetSession().StepIndex() < steps) untouched.Advance(0.0167);
  CHECK(untouched.GetSession().World().StateHash() != live);
}

TEST_CASE("play controller: a click waits for its step, and a run that ends first neither applies "
          "nor records it", "[play][record]") {
  const game::RunInput input = DefaultInput();
  const std::size_t heavy = BodyIndex(input.scene, "heavy_ball");
  const auto heavy_id = static_cast<engine::BodyId>(heavy);
  game::PlayController controller(input.scene, {}, 800, 600, game::PlayLimits{30, 20});
  while (!controller.Paused()) controller.Advance(0.0167);
  REQUIRE(controller.GetSession().StepIndex() == 20);  // pause_at
  const std::uint64_t at_20 = controller.GetSession().World().StateHash();
  const engine::Vec2 v_before = controller.GetSession().World().State(heavy_id).velocity;
  controller.Click(ClickBeside(controller, heavy));
  // Not applied yet: quitting now (Esc) leaves the state sim reaches at step 20, and a
  // recording without the click.
  CHECK(controller.GetSession().World().State(heavy_id).velocity == v_before);
  CHECK(controller.GetSession().World().StateHash() == at_20);
  CHECK(controller.PendingClicks() == 1);
  CHECK(controller.Recorded().empty());
  // Stepping applies it before step 20 is simulated, and records it at 20.
  controller.StepOnce();
  REQUIRE(controller.Recorded().size() == 1);
  CHECK(controller.Recorded()[0].step == 20);
  CHECK(controller.PendingClicks() == 0);

  controller.TogglePause();
  while (!controller.Finished()) controller.Advance(1.0);
  CHECK(controller.GetSession().StepIndex() == 30);  // stop_at: never past it
  controller.Click(ClickBeside(controller, heavy));   // after the end: ignored
  CHECK(controller.PendingClicks() == 0);
  CHECK(controller.Advance(1.0) == 0);
  CHECK(ReplayHash(input.scene, controller.Recorded(), 800, 600, 30) ==
        controller.GetSession().World().StateHash());
}

TEST_CASE("play controller: pause holds the step, '.' steps once, time paused is not owed",
          "[play]") {
  const game::RunInput input = DefaultInput();
  const std::vector<std::uint64_t> plain = PlainLoopHashes(input, 800, 600, 40);
  game::PlayController controller(input.scene, input.events, 800, 600);
  controller.Advance(0.1);  // 6 steps
  REQUIRE(controller.GetSession().StepIndex() == 6);
  controller.TogglePause();
  CHECK(controller.Paused());
  CHECK(controller.Advance(1.0) == 0);
  CHECK(controller.Advance(0.25) == 0);
  CHECK(controller.StepOnce());
  CHECK(controller.StepOnce());
  CHECK(controller.GetSession().StepIndex() == 8);
  CHECK(controller.GetSession().World().StateHash() == plain[8]);
  controller.TogglePause();
  CHECK_FALSE(controller.StepOnce());  // '.' only steps a paused game
  // Resumed: the seconds spent paused do not come back as a burst of steps.
  CHECK(controller.Advance(0.001) == 0);
  CHECK(controller.GetSession().World().StateHash() == plain[8]);
}

TEST_CASE("play controller: restart starts the scene, the script and the recording over",
          "[play][record]") {
  const game::RunInput input = DefaultInput();
  const std::size_t heavy = BodyIndex(input.scene, "heavy_ball");
  const std::vector<std::uint64_t> plain = PlainLoopHashes(input, 800, 600, 120);
  game::PlayController controller(input.scene, input.events, 800, 600);
  while (controller.GetSession().StepIndex() < 100) controller.Advance(0.05);
  controller.Click(ClickBeside(controller, heavy));
  controller.Advance(0.05);
  REQUIRE_FALSE(controller.Recorded().empty());

  controller.Restart();
  CHECK(controller.GetSession().StepIndex() == 0);
  CHECK(controller.GetSession().World().StateHash() == plain[0]);
  CHECK(controller.Recorded().empty());
  CHECK(controller.PendingClicks() == 0);
  // The script replays from its first event again: the same states as a fresh run.
  while (controller.GetSession().StepIndex() < 100) controller.Advance(0.0167);
  CHECK(controller.GetSession().World().StateHash() ==
        plain[controller.GetSession().StepIndex()]);
  CHECK(ReplayHash(input.scene, controller.Recorded(), 800, 600,
                   controller.GetSession().StepIndex()) ==
        controller.GetSession().World().StateHash());

  // Restarting a paused game shows step 0, still paused.
  controller.TogglePause();
  controller.Restart();
  CHECK(controller.Paused());
  CHECK(controller.Advance(0.1) == 0);
  CHECK(controller.GetSession().StepIndex() == 0);
}

TEST_CASE("play view: the picture keeps its aspect in any window (letterbox)", "[play][view]") {
  using render::PixelRect;
  CHECK(game::Letterbox(800, 600, 800, 600) == PixelRect{0, 0, 800, 600});
  CHECK(game::Letterbox(1000, 600, 800, 600) == PixelRect{100, 0, 800, 600});  // bars left, right
  CHECK(game::Letterbox(800, 800, 800, 600) == PixelRect{0, 100, 800, 600});   // bars top, bottom
  CHECK(game::Letterbox(400, 300, 800, 600) == PixelRect{0, 0, 400, 300});
  CHECK(game::Letterbox(1920, 1080, 800, 600) == PixelRect{240, 0, 1440, 1080});
  CHECK(game::Letterbox(0, 0, 800, 600) == PixelRect{});  // minimised
  const PixelRect thin = game::Letterbox(3, 1000, 800, 600);
  CHECK(thin.width == 3);
  CHECK(thin.height >= 1);
}

TEST_CASE("play view: a click maps through the picture as a pixel click maps through an image",
          "[play][view]") {
  const render::Camera camera{{2.0, 5.0}, 20.0};
  // Unscaled, at the window's corner: the contract's pixel rule exactly.
  const render::PixelRect same{0, 0, 800, 600};
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, {412.0, 300.0}, {799.5, 599.5}}) {
    const auto p = game::WindowPointToWorld(camera, same, x, y);
    REQUIRE(p);
    CHECK(*p == render::PixelToWorld(camera, 800, 600, x, y));
  }
  // Letterboxed and scaled 1.5x: the same spot of the picture is the same world point.
  const render::PixelRect boxed = game::Letterbox(1400, 900, 800, 600);  // {100, 0, 1200, 900}
  REQUIRE(boxed == render::PixelRect{100, 0, 1200, 900});
  const auto centre = game::WindowPointToWorld(camera, boxed, 100 + 600, 450);
  REQUIRE(centre);
  CHECK(centre->x == Approx(2.0));
  CHECK(centre->y == Approx(5.0));
  const auto scaled = game::WindowPointToWorld(camera, boxed, 100 + 1.5 * 412, 1.5 * 300);
  const engine::Vec2 original = render::PixelToWorld(camera, 800, 600, 412, 300);
  REQUIRE(scaled);
  CHECK(scaled->x == Approx(original.x));
  CHECK(scaled->y == Approx(original.y));
  // On the bars: no world point, so no click.
  CHECK_FALSE(game::WindowPointToWorld(camera, boxed, 50, 450));
  CHECK_FALSE(game::WindowPointToWorld(camera, boxed, 1350, 450));
  CHECK_FALSE(game::WindowPointToWorld(camera, render::PixelRect{}, 0, 0));
}

TEST_CASE("play view: the status line and the screenshot name", "[play][view]") {
  CHECK(game::StatusLine(120, 2.0, 59.6, false) == "STEP 120  T 2.00 S  60 FPS");
  CHECK(game::StatusLine(7, 0.1166, 0.0, true) == "STEP 7  T 0.12 S  0 FPS  PAUSED");
  CHECK(game::ScreenshotStem("default", 90) == "default_step_000090");
  CHECK(game::ScreenshotStem("my scene/2", 1234567) == "my_scene_2_step_1234567");
  CHECK(game::ScreenshotStem("", 0) == "scene_step_000000");
  CHECK(game::ScreenshotStem("..", 1) == "scene.._step_000001");
}

TEST_CASE("bitmap text: glyphs are 3x5 cells, lit runs merged, unknown characters as '?'",
          "[play][view]") {
  const render::Color white{255, 255, 255};
  CHECK(render::TextWidth("", 2) == 0);
  CHECK(render::TextWidth("1", 2) == 6);
  CHECK(render::TextWidth("STEP 90", 1) == 7 * 4 - 1);
  // "1": .#. / ##. / .#. / .#. / ### -> one rect a row, 5 rows.
  const std::vector<render::FilledRect> one = render::LayoutText("1", 10, 20, 2, white);
  REQUIRE(one.size() == 5);
  CHECK(one[0].rect == render::PixelRect{12, 20, 2, 2});
  CHECK(one[1].rect == render::PixelRect{10, 22, 4, 2});
  CHECK(one[4].rect == render::PixelRect{10, 28, 6, 2});
  // Every rect stays inside the text's box, and a space draws nothing.
  const std::string text = "STEP 120  T 2.00 S  60 FPS  PAUSED";
  for (const render::FilledRect& r : render::LayoutText(text, 0, 0, 3, white)) {
    CHECK(r.rect.x >= 0);
    CHECK(r.rect.x + r.rect.width <= render::TextWidth(text, 3));
    CHECK(r.rect.y + r.rect.height <= render::kGlyphRows * 3);
  }
  CHECK(render::LayoutText(" ", 0, 0, 1, white).empty());
  CHECK(render::LayoutText("a", 0, 0, 1, white).size() == render::LayoutText("A", 0, 0, 1, white).size());
  CHECK(render::LayoutText("~", 0, 0, 1, white).size() == render::LayoutText("?", 0, 0, 1, white).size());
}

TEST_CASE("screenshot: a taken name gets the next number, and no file is ever replaced",
          "[play][screenshot]") {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "play" / "screenshot_names";
  fs::remove_all(dir);
  render::Image image{2, 1, {255, 0, 0, 0, 0, 255}};
  game::Expected<std::string> first = game::SaveScreenshot(image, (dir / "shots").string(), "x_step_000001");
  REQUIRE(first.HasValue());
  CHECK(first.Value() == (dir / "shots" / "x_step_000001.png").string());
  std::ofstream(dir / "shots" / "x_step_000001-2.png") << "a user's own file";
  game::Expected<std::string> second = game::SaveScreenshot(image, (dir / "shots").string(), "x_step_000001");
  REQUIRE(second.HasValue());
  CHECK(second.Value() == (dir / "shots" / "x_step_000001-3.png").string());
  std::ifstream mine(dir / "shots" / "x_step_000001-2.png");
  CHECK(std::string(std::istreambuf_iterator<char>(mine), {}) == "a user's own file");
  // Only the three files: no temporary left behind.
  CHECK(std::distance(fs::directory_iterator(dir / "shots"), fs::directory_iterator()) == 3);
  // A file where the folder should be: a failure, not a crash.
  std::ofstream(dir / "file") << "x";
  CHECK_FALSE(game::SaveScreenshot(image, (dir / "file").string(), "s").HasValue());
}

TEST_CASE("play controller: rewinding goes back through kept points, and a recording made after a "
          "rewind replays to the live state",
          "[play][rewind]") {
  const game::RunInput input = DefaultInput();
  const std::size_t heavy = BodyIndex(input.scene, "heavy_ball");
  game::PlayController controller(input.scene, input.events, 800, 600);
  const std::vector<std::uint64_t> plain = PlainLoopHashes(input, 800, 600, 130);
  std::vector<std::uint64_t> lived(200, 0);  // the live hash at each step, as last reached
  auto step_to = [&](std::int64_t step) {
    while (controller.GetSession().StepIndex() < step) {
      controller.StepOnce();
      lived[controller.GetSession().StepIndex()] = controller.GetSession().World().StateHash();
    }
  };
  controller.TogglePause();  // step by hand, one at a time
  step_to(57);
  controller.Click(ClickBeside(controller, heavy));  // applied at step 57, then undone
  step_to(95);
  REQUIRE(controller.Recorded().size() > 0);
  // Held Backspace: 95 → 90 → 80 → 70 → 60 → 50, each a kept point with the state lived there
  // (the click at 57 in it from 60 on, and not at 50, where it equals the plain loop's).
  for (const std::int64_t expected : {90, 80, 70, 60, 50}) {
    REQUIRE(controller.Rewind());
    CHECK(controller.GetSession().StepIndex() == expected);
    CHECK(controller.GetSession().World().StateHash() == lived[expected]);
  }
  CHECK(lived[60] != plain[60]);
  CHECK(lived[50] == plain[50]);
  // The click at 57 is forgotten; the demo script's events before step 50 stay.
  for (const game::InputEvent& e : controller.Recorded()) CHECK(e.step < 50);
  // A new future: another click, and on to step 130.
  step_to(66);
  controller.Click(ClickBeside(controller, heavy));
  step_to(130);
  const std::uint64_t live = controller.GetSession().World().StateHash();
  CHECK(live != plain[130]);
  CHECK(ReplayHash(input.scene, controller.Recorded(), 800, 600, 130) == live);
  // Back to the start: no further.
  while (controller.Rewind()) {
  }
  CHECK(controller.GetSession().StepIndex() == 0);
  CHECK(controller.GetSession().World().StateHash() == plain[0]);
  CHECK(controller.RewindSteps() == std::vector<std::int64_t>{0});
}

TEST_CASE("play controller: a live drag is recorded as grab-world, drag-world and release and "
          "replays to the live state; rewinding brings back the grab of that moment",
          "[play][record][drag]") {
  const game::RunInput input = DefaultInput();
  const auto heavy = static_cast<engine::BodyId>(BodyIndex(input.scene, "heavy_ball"));
  game::PlayController controller(input.scene, input.events, 640, 480);
  auto centre = [&] { return controller.GetSession().World().State(heavy).position; };
  using game::EventKind;

  controller.Advance(0.1);  // 6 steps
  const engine::Vec2 grabbed = centre();
  controller.Grab(grabbed);
  controller.Drag(grabbed + engine::Vec2{0.5, 1.0});
  controller.Drag(grabbed + engine::Vec2{1.0, 2.0});  // the same step: only this one counts
  CHECK(controller.PendingEvents() == 2);
  CHECK(controller.PendingClicks() == 0);
  controller.Advance(0.05);
  REQUIRE(controller.Recorded().size() >= 2);
  const auto& first = controller.Recorded();
  CHECK(first[first.size() - 2].kind == EventKind::kGrabWorld);
  CHECK(first[first.size() - 2].step == 6);
  CHECK(first[first.size() - 2].at == grabbed);
  CHECK(first.back().kind == EventKind::kDragWorld);
  CHECK(first.back().at == grabbed + engine::Vec2{1.0, 2.0});
  REQUIRE(game::CurrentGrab(controller.GetSession().World()));

  // The target moves over later frames, while paused and stepped by hand too; a click meanwhile.
  for (int i = 1; i <= 20; ++i) {
    controller.Drag(grabbed + engine::Vec2{1.0 - 0.1 * i, 2.0 + 0.05 * i});
    controller.Advance(0.0167);
  }
  controller.TogglePause();
  controller.Drag(grabbed + engine::Vec2{-2.0, 1.0});
  controller.StepOnce();
  controller.TogglePause();
  while (controller.GetSession().StepIndex() < 70) controller.Advance(0.0167);
  const std::int64_t held_step = controller.GetSession().StepIndex();
  const std::uint64_t held_hash = controller.GetSession().World().StateHash();
  controller.Release();
  controller.Advance(0.0167);
  CHECK_FALSE(game::CurrentGrab(controller.GetSession().World()));
  while (controller.GetSession().StepIndex() < 200) controller.Advance(0.0167);
  const std::int64_t steps = controller.GetSession().StepIndex();
  const std::uint64_t live = controller.GetSession().World().StateHash();

  // Exactly one grab and one release, drags in between, steps in order.
  const std::vector<game::InputEvent>& recorded = controller.Recorded();
  CHECK(std::count_if(recorded.begin(), recorded.end(), [](const auto& e) { return e.kind == EventKind::kGrabWorld; }) == 1);
  CHECK(std::count_if(recorded.begin(), recorded.end(), [](const auto& e) { return e.kind == EventKind::kRelease; }) == 1);
  CHECK(std::count_if(recorded.begin(), recorded.end(), [](const auto& e) { return e.kind == EventKind::kDragWorld; }) >= 20);
  CHECK(std::is_sorted(recorded.begin(), recorded.end(),
                       [](const auto& a, const auto& b) { return a.step < b.step; }));
  // The drag moved heavy_ball: the run without it ends elsewhere.
  game::PlayController untouched(input.scene, input.events, 640, 480);
  while (untouched.GetSession().StepIndex() < steps) untouched.Advance(0.0167);
  CHECK(untouched.GetSession().World().StateHash() != live);

  // Written, read back and replayed as sim and render replay a script, at other sizes.
  const std::string text = game::FormatScript(recorded);
  CHECK_THAT(text, Catch::Contains(" release\n"));
  game::Expected<std::vector<game::InputEvent>> parsed = game::ParseScript(text, "recorded");
  REQUIRE(parsed.HasValue());
  for (const auto& [width, height] : {std::pair{640, 480}, {800, 600}, {123, 77}}) {
    INFO("replayed at " << width << "x" << height);
    CHECK(ReplayHash(input.scene, parsed.Value(), width, height, steps) == live);
  }
  CHECK(ReplayHash(input.scene, parsed.Value(), 640, 480, held_step) == held_hash);

  // Rewinding: to step 60 the grab is held (the snapshot has the joint), before step 6 it is not;
  // a recording made after the rewind still replays to the live state.
  controller.TogglePause();
  while (controller.GetSession().StepIndex() > 60) REQUIRE(controller.Rewind());
  REQUIRE(controller.GetSession().StepIndex() == 60);
  CHECK(game::CurrentGrab(controller.GetSession().World()));
  CHECK(controller.GetSession().World().StateHash() ==
        ReplayHash(input.scene, parsed.Value(), 640, 480, 60));
  while (controller.GetSession().StepIndex() > 0) REQUIRE(controller.Rewind());
  CHECK_FALSE(game::CurrentGrab(controller.GetSession().World()));
  for (int i = 0; i < 30; ++i) controller.StepOnce();
  controller.Grab(centre());
  controller.Drag(centre() + engine::Vec2{0.0, 3.0});
  for (int i = 0; i < 30; ++i) controller.StepOnce();
  controller.Release();
  for (int i = 0; i < 30; ++i) controller.StepOnce();
  CHECK(ReplayHash(input.scene, controller.Recorded(), 800, 600, 90) ==
        controller.GetSession().World().StateHash());
}
