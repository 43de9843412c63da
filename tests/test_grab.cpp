// The drag rule (game/grab.h): which body a grab takes, the target joint it makes, and scripted
// drags in `ballbox sim` and `render`: the ball goes to the held target and stays within the
// spring's sag of it, falls freely once released, and pixel events map as clicks do.
#include <catch2/catch.hpp>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/world.h"
#include "game/grab.h"
#include "render/camera.h"
#include "run_program.h"
#include "shape_builders.h"
#include "world_builders.h"

namespace fs = std::filesystem;

namespace {

std::string StateHash(const std::string& out) {
  std::smatch m;
  static const std::regex kHash("state-hash: ([0-9a-f]{16})\n$");
  return std::regex_search(out, m, kHash) ? m[1].str() : "";
}

// A ball of 1 kg, radius 0.25 m, resting on a floor under the default gravity; the camera
// shows 8 m across, centred on (0, 2).
constexpr const char* kDragScene = R"({
  "name": "drag",
  "camera": { "center": [0, 2], "width": 8 },
  "bodies": [
    { "id": "floor", "shape": "box", "size": [8, 1], "position": [0, -0.5], "static": true },
    { "id": "ball", "shape": "circle", "radius": 0.25, "position": [0, 0.25], "mass": 1 }
  ]
})";

struct Row {
  double x, y, vx, vy;
};

// The ball's rows of a --dump, by step.
std::map<std::int64_t, Row> BallRows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "step,time,id,x,y,vx,vy,angle,omega");
  std::map<std::int64_t, Row> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string step, time, id, x, y, vx, vy;
    std::getline(fields, step, ',');
    std::getline(fields, time, ',');
    std::getline(fields, id, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, vx, ',');
    std::getline(fields, vy, ',');
    if (id == "ball") rows[std::stoll(step)] = {std::stod(x), std::stod(y), std::stod(vx), std::stod(vy)};
  }
  return rows;
}

}  // namespace

TEST_CASE("grab: the topmost dynamic body under the point, never a static or kinematic one",
          "[grab]") {
  engine::World world(testing::NoGravity());
  world.CreateBody(testing::Static(testing::Box({0.0, 0.0}, {4.0, 1.0})));          // 0: floor
  const engine::BodyId ball = world.CreateBody(testing::Circle({0.0, 0.0}, 0.5));   // 1
  const engine::BodyId box = world.CreateBody(testing::Box({0.3, 0.0}, {1.0, 1.0}));  // 2
  world.CreateBody(testing::Kinematic(testing::Box({3.0, 0.0}, {1.0, 1.0})));       // 3
  const engine::BodyId triangle = world.CreateBody(
      testing::PartsBody({testing::PolygonPart({{-1.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}})}, {-2.0, 2.0}));

  // Where the ball and the box overlap, the box (later in slot order, drawn on top) is taken.
  CHECK(game::GrabbableAt(world, {0.2, 0.0}) == box);
  CHECK(game::GrabbableAt(world, {-0.4, 0.0}) == ball);  // the ball alone, over the floor
  CHECK_FALSE(game::GrabbableAt(world, {-1.8, 0.0}));    // the static floor alone
  CHECK_FALSE(game::GrabbableAt(world, {3.0, 0.0}));     // the kinematic box
  CHECK_FALSE(game::GrabbableAt(world, {0.0, 5.0}));     // nothing
  // A polygon body by its shape, not its bounds: inside the triangle, then in a corner of its box.
  CHECK(game::GrabbableAt(world, {-2.0, 2.5}) == triangle);
  CHECK_FALSE(game::GrabbableAt(world, {-2.9, 2.9}));
  // Touching counts, as in every query: the ball's rightmost point, beyond the floor's top.
  engine::World lone(testing::NoGravity());
  const engine::BodyId only = lone.CreateBody(testing::Circle({0.0, 0.0}, 0.5));
  CHECK(game::GrabbableAt(lone, {0.5, 0.0}) == only);
  CHECK_FALSE(game::GrabbableAt(lone, {0.5 + 1e-3, 0.0}));
}

TEST_CASE("grab: the joint pulls the grabbed point at 5 Hz, damping ratio 0.7, capped at 1000 "
          "times the weight", "[grab]") {
  engine::WorldDef def;
  def.gravity = {0.0, -20.0};
  engine::World heavy(def);
  const engine::BodyId ball = heavy.CreateBody(testing::WithMass(testing::Circle({1.0, 2.0}, 0.5), 2.0));
  const engine::JointDef joint = game::GrabJoint(heavy, ball, {1.25, 2.0});
  CHECK(joint.type == engine::JointType::kTarget);
  CHECK(joint.body_b == ball);
  CHECK((joint.anchor == engine::Vec2{1.25, 2.0} && joint.target == engine::Vec2{1.25, 2.0}));
  REQUIRE(joint.spring);
  CHECK(joint.spring->hertz == 5.0);
  CHECK(joint.spring->damping_ratio == 0.7);
  CHECK(joint.max_force == Approx(1000.0 * 2.0 * 20.0));
  // With no gravity (or little), as strong as under Earth's: a weightless body can be dragged.
  engine::World floating(testing::NoGravity());
  const engine::BodyId drifting = floating.CreateBody(testing::WithMass(testing::Circle({}, 0.5), 2.0));
  CHECK(game::GrabJoint(floating, drifting, {}).max_force == Approx(1000.0 * 2.0 * 9.8));
}

TEST_CASE("grab: grab, drag and release through the world; one grab at a time", "[grab]") {
  engine::World world(testing::NoGravity());
  const engine::BodyId a = world.CreateBody(testing::Circle({0.0, 0.0}, 0.5));
  const engine::BodyId b = world.CreateBody(testing::Box({3.0, 0.0}, {1.0, 1.0}));
  CHECK_FALSE(game::CurrentGrab(world));
  CHECK_FALSE(game::Drag(world, {1.0, 1.0}));  // nothing held: nothing happens
  CHECK_FALSE(game::Release(world));

  REQUIRE(game::Grab(world, {0.1, 0.2}) == a);
  const std::optional<engine::JointId> first = game::CurrentGrab(world);
  REQUIRE(first);
  CHECK(world.JointIds().size() == 1);
  CHECK(world.GetJointDef(*first).body_b == a);
  CHECK(world.Joint(*first).anchor_b == engine::Vec2{0.1, 0.2});

  CHECK(game::Drag(world, {-2.0, 1.5}));
  CHECK(world.GetJointDef(*first).target == engine::Vec2{-2.0, 1.5});
  CHECK(world.Joint(*first).anchor_a == engine::Vec2{-2.0, 1.5});  // a target joint's A is its target

  // A second grab lets go of the first: still one grab, now on the box.
  REQUIRE(game::Grab(world, {3.2, 0.1}) == b);
  CHECK_FALSE(world.IsValid(*first));
  REQUIRE(world.JointIds().size() == 1);
  CHECK(world.GetJointDef(*game::CurrentGrab(world)).body_b == b);
  // A grab on nothing lets go and holds nothing.
  CHECK_FALSE(game::Grab(world, {10.0, 10.0}));
  CHECK(world.JointIds().empty());
  REQUIRE(game::Grab(world, {0.0, 0.0}) == a);
  CHECK(game::Release(world));
  CHECK(world.JointIds().empty());
}

TEST_CASE("grab: a scripted drag in sim carries the ball to the held target; released, it falls "
          "freely", "[grab][sim]") {
  const fs::path dir = testing::FreshTestDir("grab", "sim_drag");
  std::ofstream(dir / "drag.json") << kDragScene;
  // Grabbed at its centre (no torque), the target 2 m right and 2.75 m up, held for 2 s
  // (120 steps of 1/60 s), then let go for 0.5 s.
  std::ofstream(dir / "drag.script") << "0 grab-world 0 0.25\n0 drag-world 2 3\n120 release\n";
  const testing::ProgramRun run = testing::Ballbox(
      "sim drag.json --script drag.script --steps 150 --dump drag.csv", dir);
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("events: 1 grab (1 took hold of a body), 1 drag, 1 release\n"));
  const std::map<std::int64_t, Row> rows = BallRows(dir / "drag.csv");
  REQUIRE(rows.size() == 151);

  const engine::Vec2 target{2.0, 3.0};
  auto distance = [&](std::int64_t step) {
    return engine::Length(engine::Vec2{rows.at(step).x, rows.at(step).y} - target);
  };
  const double start = distance(0);
  CHECK(start == Approx(std::sqrt(4.0 + 2.75 * 2.75)));
  // A 5 Hz spring damped at 0.7 settles within a few of its time constants 1/(ζω) = 45 ms: the
  // distance shrinks to a tenth within 0.25 s, and stays small.
  CHECK(distance(5) < start);
  CHECK(distance(15) < 0.1 * start);
  // Held, the spring carries the ball's weight: it hangs below the target by the static stretch
  // of a 5 Hz spring, g/ω² = 9.8 / (2π·5)² = 0.993 cm (seen: 0.993 cm).
  const double sag = 9.8 / std::pow(2.0 * 3.14159265358979323846 * 5.0, 2);
  for (const std::int64_t step : {60, 90, 120}) {
    INFO("step " << step << ": ball at (" << rows.at(step).x << ", " << rows.at(step).y
                 << "), " << distance(step) * 100.0 << " cm from the target");
    CHECK(distance(step) < 0.03);
    CHECK(std::abs(rows.at(step).x - target.x) < 0.005);
    CHECK(target.y - rows.at(step).y == Approx(sag).epsilon(0.05));
    CHECK(std::abs(rows.at(step).vy) < 0.05);
  }
  // Let go at step 120, it falls freely: semi-implicit Euler's parabola from its state then, in
  // the substep solver's 4 substeps a step (rotation off).
  const Row& released = rows.at(120);
  const testing::FreeFall fall =
      testing::SemiImplicitFall(released.y, released.vy, -9.8, 1.0 / 240.0, 4 * 30);
  CHECK(rows.at(150).y == Approx(fall.position).margin(1e-9));
  CHECK(rows.at(150).vy == Approx(fall.velocity).margin(1e-9));
  CHECK(rows.at(150).x == Approx(released.x + 0.5 * released.vx).margin(0.01));
}

TEST_CASE("grab: pixel grabs and drags map through the camera as clicks do, at any --size; render "
          "replays them to sim's state", "[grab][sim][render]") {
  const fs::path dir = testing::FreshTestDir("grab", "pixels");
  std::ofstream(dir / "drag.json") << kDragScene;
  // Pixels of an 800x600 picture; the world script holds the points they map to.
  const render::Camera view{{0.0, 2.0}, 8.0};
  const engine::Vec2 grab_px{400.0, 475.0}, drag_px{610.5, 80.25};
  std::ofstream(dir / "pixels.script") << "size 800 600\n3 grab 400 475\n3 drag 610.5 80.25\n70 release\n";
  char world_script[256];
  const engine::Vec2 g = render::PixelToWorld(view, 800, 600, grab_px.x, grab_px.y);
  const engine::Vec2 d = render::PixelToWorld(view, 800, 600, drag_px.x, drag_px.y);
  std::snprintf(world_script, sizeof world_script,
                "3 grab-world %.17g %.17g\n3 drag-world %.17g %.17g\n70 release\n", g.x, g.y, d.x, d.y);
  std::ofstream(dir / "world.script") << world_script;

  const testing::ProgramRun world_run = testing::Ballbox("sim drag.json --script world.script --steps 100", dir);
  REQUIRE(world_run.exit_code == 0);
  const std::string hash = StateHash(world_run.out);
  REQUIRE(hash.size() == 16);
  for (const char* size : {"800x600", "320x240", "123x77"}) {
    INFO("--size " << size);
    const testing::ProgramRun pixels =
        testing::Ballbox("sim drag.json --script pixels.script --steps 100 --size " + std::string(size), dir);
    CHECK(StateHash(pixels.out) == hash);
  }
  // The grab took hold: without it the ball lies still and the state is another.
  const testing::ProgramRun plain = testing::Ballbox("sim drag.json --steps 100", dir);
  CHECK(StateHash(plain.out) != hash);

  // render simulates the same steps (frame 100 of --every 1 is step 100) to the same state.
  const testing::ProgramRun render = testing::Ballbox(
      "render drag.json --script pixels.script --frames 11 --every 10 --size 160x120 --out frames "
      "--save-state rendered.state", dir);
  INFO(render.err);
  REQUIRE(render.exit_code == 0);
  const testing::ProgramRun loaded =
      testing::Ballbox("sim drag.json --load-state rendered.state --steps 0", dir);
  INFO(loaded.err);
  CHECK(StateHash(loaded.out) == hash);
}
