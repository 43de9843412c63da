// A non-finite number born inside the engine is caught at the end of its step, named with body
// and step, and goes no further: not into later steps, a dump or a frame.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <filesystem>
#include <vector>
#include <fstream>

#include "engine/world.h"
#include "game/scene.h"
#include "game/session.h"
#include "world_builders.h"

namespace fs = std::filesystem;

namespace {

// Two bodies 1e-160 m apart under mutual gravitation: |r|³ underflows, the pull overflows.
constexpr const char* kOverflowScene = R"({ "gravitational_constant": 1, "gravity": [0, 0], "bodies": [
  { "id": "near", "shape": "circle", "radius": 1, "position": [3, 0] },
  { "id": "a", "shape": "circle", "radius": 1, "position": [0, 0] },
  { "id": "b", "shape": "circle", "radius": 1, "position": [1e-160, 0] } ] })";

}  // namespace

TEST_CASE("the engine records the first non-finite state and stops stepping", "[fault]") {
  engine::WorldDef def;
  def.gravity = {0, 0};
  def.gravitational_constant = 1;
  engine::World world(def);
  world.CreateBody(testing::Circle({0, 0}, 1));
  world.CreateBody(testing::Circle({1e-160, 0}, 1));
  CHECK_FALSE(world.Fault());
  world.Step();
  REQUIRE(world.Fault());
  CHECK(world.Fault()->step == 0);
  CHECK(world.Fault()->body == 0);  // the first in id order
  CHECK(std::string(world.Fault()->what) == "velocity");  // caught in the forces, where it began
  const std::uint64_t hash = world.StateHash();
  world.Step();
  CHECK(world.StepCount() == 0);     // the broken step never completes, nor any after it
  CHECK(world.StateHash() == hash);
}

TEST_CASE("on two threads, the fault is the same first body as on one", "[fault][parallel]") {
  // 3 000 bodies (enough that the threads share the looking), two of them pushed twice by the
  // largest force a double holds, which sum to infinity, in the second half of the ids: the
  // first of the two is named, on any threads.
  for (const int threads : {1, 2}) {
    INFO("threads " << threads);
    engine::WorldDef def;
    def.gravity = {0, 0};
    def.threads = threads;
    def.adapt_threads = false;  // the shared paths, even on a busy machine
    engine::World world(def);
    std::vector<engine::BodyId> ids;
    for (int i = 0; i < 3000; ++i) {
      ids.push_back(world.CreateBody(testing::Circle({3.0 * (i % 60), 3.0 * (i / 60)}, 1)));
    }
    for (const int body : {2700, 2500, 2700, 2500}) world.ApplyForceToCenter(ids[body], {1e308, 0});
    world.Step();
    REQUIRE(world.Fault());
    CHECK(world.Fault()->step == 0);
    CHECK(world.Fault()->body == 2500);
  }
}

TEST_CASE("a healthy world never reports a fault", "[fault]") {
  engine::World world(engine::WorldDef{});
  world.CreateBody(testing::Static(testing::Box({0, -0.5}, {10, 1})));
  world.CreateBody(testing::Circle({0, 5}, 0.5, {3, 0}));
  for (int i = 0; i < 600; ++i) world.Step();
  CHECK_FALSE(world.Fault());
}

TEST_CASE("the session names the body by its scene id, with exit code 1", "[fault]") {
  game::Expected<game::Scene> scene = game::ParseScene(kOverflowScene, "overflow.json", "overflow");
  REQUIRE(scene.HasValue());
  game::Session session(scene.Value(), {}, 800, 600);
  CHECK_FALSE(session.Fault());
  session.Step();
  const game::Status fault = session.Fault();
  REQUIRE(fault);
  CHECK(fault->exit_code == 1);
  CHECK(fault->message.find("\"a\" (bodies[1])") != std::string::npos);
  CHECK(fault->message.find("step 0") != std::string::npos);
}

TEST_CASE("sim and render stop at the fault: exit 1, no dump, no frame of the broken state", "[fault][exe]") {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "fault";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = dir / "overflow.json";
  std::ofstream(scene) << kOverflowScene;
  const std::string quiet = " > " + (dir / "out.txt").string() + " 2> " + (dir / "err.txt").string();

  const int sim = std::system((std::string(BALLBOX_EXE) + " sim " + scene.string() + " --steps 5 --dump " +
                               (dir / "dump.csv").string() + quiet).c_str());
  CHECK(WEXITSTATUS(sim) == 1);
  CHECK_FALSE(fs::exists(dir / "dump.csv"));
  std::ifstream err(dir / "err.txt");
  std::string line;
  std::getline(err, line);
  CHECK(line.rfind("error: the simulation broke down: body \"a\"", 0) == 0);

  const int render = std::system((std::string(BALLBOX_EXE) + " render " + scene.string() +
                                  " --frames 4 --size 64x48 --out " + (dir / "frames").string() + quiet).c_str());
  CHECK(WEXITSTATUS(render) == 1);
  CHECK(fs::exists(dir / "frames" / "frame_00000.png"));   // the initial state was fine
  CHECK_FALSE(fs::exists(dir / "frames" / "frame_00001.png"));  // the broken one is not drawn
}
