// The events summary that render, sim and play end with: clicks applied, hit and missed, each
// miss on request (--misses) with its step, place and the nearest ball, and the events a run
// ended before.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "game/event_log.h"
#include "game/play_controller.h"
#include "game/session.h"
#include "run_program.h"

namespace fs = std::filesystem;
using testing::Ballbox;
using engine::Vec2;

namespace {

fs::path FreshDir(const std::string& name) { return testing::FreshTestDir("events", name); }

// A ball of radius 0.35 at (2, 1) and a box, no gravity, camera 8 m wide at (0, 0).
game::Scene SmallBallScene() {
  game::Scene scene;
  scene.world.gravity = {0, 0};
  scene.camera.center = Vec2{0, 0};
  scene.camera.width = 8;  // 100 px per metre at 800x600
  game::SceneBody ball;
  ball.id = "little";
  ball.def.shape = {engine::ShapeType::kCircle, 0.35, {}};
  ball.def.position = {2, 1};
  game::SceneBody box;
  box.id = "crate";
  box.def.shape = {engine::ShapeType::kBox, 0, {0.5, 0.5}};
  box.def.position = {-2, 0};
  scene.bodies = {ball, box};
  return scene;
}

}  // namespace

TEST_CASE("events: hits and misses are counted; a miss keeps its step, point and nearest ball",
          "[events]") {
  const std::vector<game::InputEvent> events = {
      {0, game::EventKind::kClickWorld, {2.1, 1.0}},           // on the ball
      {3, game::EventKind::kClickWorld, {2.0, 1.5}},           // 0.15 m beyond its rim: a miss
      {4, game::EventKind::kClickPixel, {400, 300}, 800, 600},  // world (0, 0): a miss
      {4, game::EventKind::kClickWorld, {-2.0, 0.0}}};          // on the box: boxes take no clicks
  game::Session session(SmallBallScene(), events, 800, 600);
  for (int i = 0; i < 10; ++i) session.Step();
  const game::EventLog& log = session.Events();
  CHECK(log.Applied() == 4);
  CHECK(log.Hits() == 1);
  REQUIRE(log.Misses().size() == 3);
  const game::MissedClick& near = log.Misses()[0];
  CHECK(near.event.step == 3);
  REQUIRE(near.nearest);
  CHECK(*near.nearest == engine::BodyId{0});
  // The ball moved after its click: its centre at the step of the miss decides the gap.
  CHECK(near.gap > 0.0);
  const game::MissedClick& pixel = log.Misses()[1];
  CHECK(pixel.world == Vec2{0, 0});
  CHECK(session.EventsLeft().count == 0);

  const std::vector<std::string> ids = {"little", "crate"};
  const std::string line = game::MissLine(pixel, ids);
  CHECK_THAT(line, Catch::StartsWith("miss: step 4, click 400 300 (pixels at 800x600) -> world (0, 0): "
                                     "no ball there; nearest \"little\", "));
  CHECK_THAT(line, Catch::EndsWith(" m beyond its rim"));
  CHECK(game::MissLine(log.Misses()[2], ids).rfind("miss: step 4, click-world -2 0: no ball there", 0) == 0);
  CHECK(game::EventSummary(log, session.EventsLeft(), false) ==
        "events: 4 clicks applied, 1 hit a ball, 3 missed (--misses lists where)");
  CHECK(game::EventSummary(log, session.EventsLeft(), true) ==
        "events: 4 clicks applied, 1 hit a ball, 3 missed");
  CHECK(game::EventSummary(game::EventLog{}, game::EventsAfterEnd{}, false) == "events: none");
}

TEST_CASE("events: the gap to the nearest ball is its distance from the rim", "[events]") {
  game::Session session(SmallBallScene(), {{0, game::EventKind::kClickWorld, {5.0, 5.0}}}, 800, 600);
  session.Step();
  REQUIRE(session.Events().Misses().size() == 1);
  const game::MissedClick& miss = session.Events().Misses()[0];
  CHECK(miss.gap == Approx(std::hypot(3.0, 4.0) - 0.35).epsilon(1e-12));
}

TEST_CASE("events: the events a run ends before are counted from the first of them", "[events]") {
  const std::vector<game::InputEvent> events = {{2, game::EventKind::kClickWorld, {2, 1}},
                                                {7, game::EventKind::kClickWorld, {2, 1}},
                                                {9, game::EventKind::kClickWorld, {2, 1}}};
  game::Session session(SmallBallScene(), events, 800, 600);
  for (int i = 0; i < 7; ++i) session.Step();  // steps 0-6: the event at step 7 never applied
  const game::EventsAfterEnd late = session.EventsLeft();
  CHECK(late.count == 2);
  CHECK(late.first_step == 7);
  CHECK(late.end_step == 7);
  CHECK(game::EventSummary(session.Events(), late, false) ==
        "events: 1 click applied, 1 hit a ball, 0 missed; 2 events after the end of the run (the first "
        "at step 7; the run ended before simulating step 7)");
}

TEST_CASE("events: play counts its live clicks and the ones still waiting", "[events][play]") {
  game::PlayController controller(SmallBallScene(), {{50, game::EventKind::kClickWorld, {2, 1}}}, 800, 600,
                                   game::PlayLimits{5, std::nullopt});
  controller.Click({2.0, 1.2});  // applied at step 0: on the ball
  controller.Click({3.0, 3.0});  // also at step 0: a miss
  controller.Advance(1.0);       // runs to the stop at step 5
  controller.Click({2.0, 1.0});  // the run is over: ignored
  CHECK(controller.GetSession().Events().Hits() == 1);
  CHECK(controller.GetSession().Events().Misses().size() == 1);
  CHECK(controller.EventsLeft().count == 1);  // the script's event at step 50
  CHECK(controller.EventsLeft().first_step == 50);
}

TEST_CASE("events: sim, render and play print the summary, with --misses a line per miss",
          "[events][exe]") {
  const fs::path dir = FreshDir("exe");
  // The default demo: all six clicks hit; the hash is still sim's last line.
  const testing::ProgramRun demo = Ballbox("sim --steps 300", dir);
  REQUIRE(demo.exit_code == 0);
  CHECK_THAT(demo.out, Catch::Contains("\nevents: 6 clicks applied, 6 hit a ball, 0 missed\n"
                                       "state-hash: 61e9c117a690e3b1\n"));
  // A click just above the bouncy ball's rim (0.026 m): it misses, and says where and by how much.
  std::ofstream(dir / "near.script") << "size 800 600\n40 click 361 195\n50 click-world 0 -20\n999 click 1 1\n";
  const testing::ProgramRun near = Ballbox("sim --steps 100 --script near.script --misses", dir);
  REQUIRE(near.exit_code == 0);
  const std::vector<std::string> expect = {
      "miss: step 40, click 361 195 (pixels at 800x600) -> world (-1.073, 9.387): no ball there; nearest "
      "\"bouncy_ball\", 0.0263 m beyond its rim\n",
      "miss: step 50, click-world 0 -20: no ball there; nearest \"heavy_ball\", ",
      "events: 2 clicks applied, 0 hit a ball, 2 missed; 1 event after the end of the run (the first at "
      "step 999; the run ended before simulating step 100)\nstate-hash: "};
  for (const std::string& text : expect) CHECK_THAT(near.out, Catch::Contains(text));
  const testing::ProgramRun render = Ballbox("render --frames 3 --size 64x48 --script near.script", dir);
  REQUIRE(render.exit_code == 0);
  CHECK(render.out.rfind("events: 0 clicks applied, 0 hit a ball, 0 missed; 3 events after the end", 0) == 0);
}
