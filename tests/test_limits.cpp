// The input limits of docs/limits.md: each one is refused as bad input (exit 2) with a message
// naming the file and the key, and a value right at the limit is accepted.
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "game/cli.h"
#include "game/limits.h"
#include "game/scene.h"
#include "game/script.h"
#include "run_program.h"

namespace fs = std::filesystem;

namespace {

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "limits" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void RequireSceneError(const std::string& file, const std::string& rest) {
  const std::string path = DataPath(file);
  const game::Expected<game::Scene> scene = game::LoadScene(path);
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == path + ": " + rest);
}

std::string OneCircle(const std::string& body_keys) {
  return R"({"bodies": [{"shape": "circle", "radius": 0.5, "position": [0, 0])" + body_keys + "}]}";
}

using Run = testing::ProgramRun;

Run Ballbox(const std::string& args, const fs::path& cwd) {
  return testing::RunShell("'" BALLBOX_EXE "' " + args, cwd, cwd / "captured");
}

}  // namespace

TEST_CASE("limits: a number beyond 1e9 is refused with its key path (fuzz: radius 1e299)",
          "[limits][scene]") {
  // Found by fuzz_scene: the circle's mass, density × area, overflowed to infinity and the
  // engine stopped the program on its precondition.
  RequireSceneError("scene_fuzz_radius_1e299.json",
                    "bodies[0].radius: must be between -1e9 and 1e9 (docs/limits.md)");
  RequireSceneError("scene_position_too_far.json",
                    "bodies[1].position[0]: must be between -1e9 and 1e9 (docs/limits.md)");
  for (const char* keys : {R"(, "velocity": [0, 1.0000001e9])", R"(, "density": 2e9)"}) {
    INFO(keys);
    const game::Expected<game::Scene> scene = game::ParseScene(OneCircle(keys), "s.json", "s");
    REQUIRE_FALSE(scene.HasValue());
    CHECK_THAT(scene.Error().message, Catch::EndsWith(": must be between -1e9 and 1e9 (docs/limits.md)"));
  }
  const game::Expected<game::Scene> dt = game::ParseScene(
      R"({"dt": 1e300, "bodies": []})", "s.json", "s");
  REQUIRE_FALSE(dt.HasValue());
  CHECK(dt.Error().message == "s.json: dt: must be between -1e9 and 1e9 (docs/limits.md)");
}

TEST_CASE("limits: a mass below 1e-12 kg is refused, given or from density and area",
          "[limits][scene]") {
  // The twin of the fuzz crash, found by reading the fix: a radius of 1e-200 made density × area 0,
  // which the engine refuses by stopping the program. (Such a radius is now refused as too small;
  // the smallest radius, 1e-9 m, still gives a mass of 3e-18 kg with the default density.)
  RequireSceneError("scene_mass_underflow.json",
                    "bodies[0]: its mass, density * area, must be at least 1e-12 kg (docs/limits.md)");
  // 5e-324 is > 0, but 1 / 5e-324 is infinite.
  RequireSceneError("scene_mass_too_small.json",
                    "bodies[0].mass: must be at least 1e-12 kg (docs/limits.md)");
  // Static bodies have no mass, so any size the size limit allows will do for them.
  const game::Expected<game::Scene> tiny_static = game::ParseScene(
      R"({"bodies": [{"shape": "circle", "radius": 1e-9, "position": [0, 0], "static": true}]})",
      "s.json", "s");
  CHECK(tiny_static.HasValue());
}

TEST_CASE("limits: a radius or box side below 1e-9 m is refused (fuzz: a side of 25e-325)",
          "[limits][scene]") {
  // Found by fuzz_scene: the side 25e-325 reads as 5e-324, positive, but its half (the box's
  // half extent) rounds to 0 and the engine stopped the program on its precondition.
  RequireSceneError("scene_fuzz_size_subnormal.json",
                    "bodies[0].size[1]: must be at least 1e-09 m (docs/limits.md)");
  for (const char* shape : {R"("shape": "circle", "radius": 9.9e-10)", R"("shape": "box", "size": [1, 9.9e-10])",
                            R"("shape": "box", "size": [1e-300, 1], "static": true)"}) {
    INFO(shape);
    const game::Expected<game::Scene> scene = game::ParseScene(
        std::string(R"({"bodies": [{)") + shape + R"(, "position": [0, 0], "mass": 1}]})", "s.json", "s");
    REQUIRE_FALSE(scene.HasValue());
    CHECK(scene.Error().exit_code == 2);
    CHECK_THAT(scene.Error().message, Catch::EndsWith(": must be at least 1e-09 m (docs/limits.md)"));
  }
  // Right at the limit: loads and steps.
  const game::Expected<game::Scene> smallest = game::ParseScene(
      R"({"bodies": [{"shape": "box", "size": [1e-9, 1e-9], "position": [0, 0], "mass": 1}]})", "s.json", "s");
  REQUIRE(smallest.HasValue());
  engine::World world = game::BuildWorld(smallest.Value());
  world.Step();
  CHECK(engine::IsFinite(world.State({0}).position));
}

TEST_CASE("limits: values right at the limits load and simulate to finite numbers",
          "[limits][scene]") {
  const game::Expected<game::Scene> scene = game::LoadScene(DataPath("scene_at_limits.json"));
  if (!scene.HasValue()) FAIL(scene.Error().message);
  CHECK(scene.Value().bodies[0].def.mass == game::kMinBodyMass);
  engine::World world = game::BuildWorld(scene.Value());
  for (int step = 0; step < 10; ++step) world.Step();
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    INFO("body " << id);
    CHECK(std::isfinite(s.position.x));
    CHECK(std::isfinite(s.position.y));
    CHECK(std::isfinite(s.velocity.x));
    CHECK(std::isfinite(s.velocity.y));
  }
}

TEST_CASE("limits: more than a million bodies is refused before any is read", "[limits][scene]") {
  // Empty objects would each be an error; the count is checked first, so the message is the
  // limit's, and no body is built.
  std::string json = R"({"bodies": [{})";
  for (std::size_t i = 1; i <= game::kMaxBodies; ++i) json += ",{}";
  json += "]}";
  const game::Expected<game::Scene> scene = game::ParseScene(json, "many.json", "many");
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message ==
        "many.json: bodies: 1000001 bodies, more than the limit of 1000000 (docs/limits.md)");
}

TEST_CASE("limits: an input file over 128 MiB is refused, one at the limit is read",
          "[limits][scene][script]") {
  const fs::path dir = FreshDir("file_size");
  // Sparse files: no disk is spent on the zeros.
  const fs::path at_limit = dir / "at_limit.json";
  const fs::path over = dir / "over.json";
  std::ofstream(at_limit).close();
  std::ofstream(over).close();
  fs::resize_file(at_limit, game::kMaxInputFileBytes);
  fs::resize_file(over, game::kMaxInputFileBytes + 1);

  const std::string too_large =
      ": larger than 128 MiB, the most an input file may hold (docs/limits.md)";
  const game::Expected<game::Scene> scene = game::LoadScene(over.string());
  REQUIRE_FALSE(scene.HasValue());
  CHECK(scene.Error().exit_code == 2);
  CHECK(scene.Error().message == over.string() + too_large);
  const game::Expected<std::vector<game::InputEvent>> script = game::LoadScript(over.string());
  REQUIRE_FALSE(script.HasValue());
  CHECK(script.Error().message == over.string() + too_large);

  // At the limit the file is read, and its first byte (a NUL) is the syntax error.
  const game::Expected<game::Scene> read = game::LoadScene(at_limit.string());
  REQUIRE_FALSE(read.HasValue());
  CHECK_THAT(read.Error().message, Catch::StartsWith(at_limit.string() + ":1:1: "));
  fs::remove(at_limit);
  fs::remove(over);
}

TEST_CASE("limits: an endless input (/dev/zero) exits 2 instead of filling memory",
          "[limits][cli]") {
  const fs::path dir = FreshDir("endless");
  for (const char* args : {"sim /dev/zero --steps 1", "sim --script /dev/zero --steps 1"}) {
    INFO(args);
    const Run run = Ballbox(args, dir);
    CHECK(run.exit_code == 2);
    CHECK(run.err ==
          "error: /dev/zero: larger than 128 MiB, the most an input file may hold (docs/limits.md)\n");
  }
}

TEST_CASE("limits: the command line's counts and sizes end where docs/limits.md says",
          "[limits][cli]") {
  auto accepts = [](std::vector<std::string> args) { return game::ParseCommandLine(args).HasValue(); };
  CHECK(accepts({"render", "--size", "16384x16384"}));
  CHECK_FALSE(accepts({"render", "--size", "16385x1"}));
  CHECK(accepts({"render", "--frames", "100000000"}));
  CHECK_FALSE(accepts({"render", "--frames", "100000001"}));
  CHECK(accepts({"sim", "--steps", "1000000000000"}));
  CHECK_FALSE(accepts({"sim", "--steps", "1000000000001"}));
  CHECK(game::kMaxImageSide == 16384);
}
