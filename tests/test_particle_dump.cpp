// `ballbox sim --dump` with particles (docs/scene-format.md#the-particle-dump): a scene without
// soft bodies, fluid or emitters dumps byte for byte what the build before particles dumped
// (tests/data/dump_golden_*.csv, made by that build) and writes nothing else; a scene with them
// writes FILE.particles.csv beside FILE.csv, one row per particle per dumped step, in the state
// hash's order, every number exact.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "game/dump.h"
#include "game/scene.h"
#include "game/session.h"
#include "run_program.h"

namespace {

namespace fs = std::filesystem;
using testing::Ballbox;
using testing::ProgramRun;
using testing::ReadFile;

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

std::uint64_t Bits(const std::string& number) { return std::bit_cast<std::uint64_t>(std::strtod(number.c_str(), nullptr)); }
std::uint64_t Bits(double v) { return std::bit_cast<std::uint64_t>(v); }

std::vector<std::string> Listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Soft bodies of both shapes (ids with a comma and plain), two fluid blocks, an emitter.
const char* kParticleScene = R"({
  "name": "dumped",
  "bodies": [{"id": "floor", "shape": "box", "size": [10, 1], "position": [0, -0.5], "static": true},
             {"id": "crate", "shape": "box", "size": [0.5, 0.5], "position": [2, 0.25]}],
  "soft_bodies": [{"id": "jelly,1", "shape": "circle", "radius": 0.3, "position": [0, 1]},
                  {"shape": "box", "size": [0.5, 0.3], "position": [-1.5, 0.5]}],
  "fluids": [{"id": "pool", "region": [[-4, 0], [-3.5, 0.3]], "spacing": 0.1},
             {"region": [[3, 0], [3.3, 0.2]]}],
  "emitters": [{"id": "torch", "position": [1, 0.1]}]
})";

}  // namespace

TEST_CASE("particle dump: a scene without particles dumps byte for byte as before particles, and nothing else",
          "[dump][particles][exe]") {
  const fs::path dir = testing::FreshTestDir("particle_dump", "unchanged");
  // The goldens were written by the build before particles (see the file comment).
  ProgramRun run = Ballbox("sim '" + DataPath("cli_scene.json") + "' --steps 60 --dump-every 10 --dump cli.csv", dir);
  REQUIRE(run.exit_code == 0);
  CHECK(ReadFile(dir / "cli.csv") == ReadFile(DataPath("dump_golden_cli_scene.csv")));
  CHECK(Lines(run.out).at(0).rfind("sim: cli, 4 bodies, 60 steps in ", 0) == 0);
  run = Ballbox("sim --steps 120 --dump-every 20 --dump default.csv", dir);  // the default scene and its clicks
  REQUIRE(run.exit_code == 0);
  CHECK(ReadFile(dir / "default.csv") == ReadFile(DataPath("dump_golden_default.csv")));
  CHECK(Listing(dir) == std::vector<std::string>{"cli.csv", "default.csv"});
  // Empty particle lists are no particles either.
  {
    std::ofstream(dir / "empty.json") << R"({"bodies": [{"shape": "circle", "radius": 1, "position": [0, 0]}],
                                            "soft_bodies": [], "fluids": [], "emitters": []})";
  }
  run = Ballbox("sim empty.json --steps 2 --dump e.csv", dir);
  REQUIRE(run.exit_code == 0);
  CHECK_FALSE(fs::exists(dir / "e.particles.csv"));
}

TEST_CASE("particle dump: FILE.particles.csv beside FILE.csv, a row per particle per dumped step, exact",
          "[dump][particles][exe]") {
  const fs::path dir = testing::FreshTestDir("particle_dump", "rows");
  {
    std::ofstream(dir / "scene.json") << kParticleScene;
  }
  const std::int64_t steps = 30, every = 10;
  const ProgramRun run = Ballbox("sim scene.json --steps 30 --dump-every 10 --dump out.csv", dir);
  REQUIRE(run.exit_code == 0);
  CHECK(Lines(run.out).at(0).rfind("sim: dumped, 2 bodies, 2 soft bodies, 21 fluid particles, 1 emitter, 30 steps", 0) == 0);
  CHECK(Listing(dir) == std::vector<std::string>{"out.csv", "out.particles.csv", "scene.json"});
  CHECK(Lines(ReadFile(dir / "out.csv")).size() == 1 + 4 * 2);  // the bodies' dump as ever

  game::Expected<game::Scene> scene = game::LoadScene((dir / "scene.json").string());
  REQUIRE(scene.HasValue());
  game::Session session(scene.Value(), {}, 800, 600);
  const std::vector<std::string> lines = Lines(ReadFile(dir / "out.particles.csv"));
  REQUIRE(!lines.empty());
  CHECK(lines[0] == "step,time,kind,source,particle,x,y,vx,vy");
  std::size_t row = 1;
  const auto check_row = [&](std::int64_t step, const char* kind, const std::string& source, std::size_t particle,
                             engine::Vec2 x, engine::Vec2 v) {
    REQUIRE(row < lines.size());
    const std::string& line = lines[row++];
    INFO(line);
    // The soft body's id has a comma: quoted, so the row splits into one more piece here.
    const std::string quoted = game::CsvField(source);
    const std::string head = std::to_string(step) + ",";
    REQUIRE(line.rfind(head, 0) == 0);
    const std::string after_time = line.substr(line.find(',', head.size()) + 1);
    REQUIRE(after_time.rfind(std::string(kind) + "," + quoted + "," + std::to_string(particle) + ",", 0) == 0);
    const std::vector<std::string> f = Fields(after_time.substr(std::string(kind).size() + quoted.size() + 2));
    REQUIRE(f.size() == 5);
    CHECK(Bits(f[1]) == Bits(x.x));
    CHECK(Bits(f[2]) == Bits(x.y));
    CHECK(Bits(f[3]) == Bits(v.x));
    CHECK(Bits(f[4]) == Bits(v.y));
    CHECK(Bits(Fields(line)[1]) == Bits(static_cast<double>(step) * scene.Value().world.dt));
  };
  for (std::int64_t step = 0; step <= steps; ++step) {
    if (step > 0) session.Step();
    if (step % every != 0) continue;
    const engine::World& world = session.World();
    for (std::size_t s = 0; s < 2; ++s) {
      const engine::SoftBodyId id = world.SoftBodyIds()[s];
      const auto x = world.SoftBodyPositions(id);
      const auto v = world.SoftBodyVelocities(id);
      for (std::size_t i = 0; i < x.size(); ++i) check_row(step, "soft", s == 0 ? "jelly,1" : "soft1", i, x[i], v[i]);
    }
    std::size_t rank = 0;
    for (const engine::EffectParticle& p : world.Effects()) check_row(step, "effect", "torch", rank++, p.position, p.velocity);
    const auto x = world.FluidPositions();
    const auto v = world.FluidVelocities();
    REQUIRE(x.size() == 15 + 6);
    for (std::size_t i = 0; i < 15; ++i) check_row(step, "fluid", "pool", i, x[i], v[i]);
    for (std::size_t i = 0; i < 6; ++i) check_row(step, "fluid", "fluid1", i, x[15 + i], v[15 + i]);
  }
  CHECK(row == lines.size());
  CHECK(Lines(run.out).back() == [&] {
    char hash[40];
    std::snprintf(hash, sizeof hash, "state-hash: %016llx", static_cast<unsigned long long>(session.World().StateHash()));
    return std::string(hash);
  }());
}

TEST_CASE("particle dump: the particle file's name, and a device dump", "[dump][particles][exe]") {
  CHECK(game::ParticleDumpPath("run/out.csv") == std::optional<std::string>("run/out.particles.csv"));
  CHECK(game::ParticleDumpPath("out.txt") == std::optional<std::string>("out.txt.particles.csv"));
  CHECK(game::ParticleDumpPath("out") == std::optional<std::string>("out.particles.csv"));
  CHECK(game::ParticleDumpPath(".csv") == std::optional<std::string>(".csv.particles.csv"));
  CHECK_FALSE(game::ParticleDumpPath("/dev/null").has_value());

  const fs::path dir = testing::FreshTestDir("particle_dump", "device");
  {
    std::ofstream(dir / "scene.json") << kParticleScene;
  }
  const ProgramRun run = Ballbox("sim scene.json --steps 2 --dump /dev/null", dir);
  REQUIRE(run.exit_code == 0);
  CHECK(run.err == "sim: /dev/null is a device or pipe: the particles' dump (FILE.particles.csv beside a file) is "
                   "not written\n");
  CHECK(Listing(dir) == std::vector<std::string>{"scene.json"});
}

TEST_CASE("particle scenes: --save-state then --load-state ends where one run does, clicks included",
          "[dump][particles][exe]") {
  const fs::path dir = testing::FreshTestDir("particle_dump", "saved_state");
  {
    std::ofstream(dir / "scene.json") << kParticleScene;
    // Clicks on the soft circle and the pool, before and after the state is saved at step 20.
    std::ofstream(dir / "clicks.txt") << "10 click-world 0.2 0.8\n25 click-world -3.9 0.5\n";
  }
  const ProgramRun whole = Ballbox("sim scene.json --script clicks.txt --steps 40 --dump whole.csv", dir);
  REQUIRE(whole.exit_code == 0);
  CHECK(Lines(whole.out).at(1) == "events: 2 clicks applied, 0 hit a ball, 2 pushed particles, 0 missed");
  REQUIRE(Ballbox("sim scene.json --script clicks.txt --steps 20 --save-state s.bin", dir).exit_code == 0);
  const ProgramRun resumed =
      Ballbox("sim scene.json --script clicks.txt --load-state s.bin --steps 20 --dump resumed.csv", dir);
  REQUIRE(resumed.exit_code == 0);
  CHECK(Lines(resumed.out).back() == Lines(whole.out).back());
  // The resumed dump is the whole one's from step 20 on.
  const std::vector<std::string> all = Lines(ReadFile(dir / "whole.particles.csv"));
  const std::vector<std::string> tail = Lines(ReadFile(dir / "resumed.particles.csv"));
  REQUIRE(tail.size() > 1);
  const auto from = std::find_if(all.begin(), all.end(), [](const std::string& l) { return l.rfind("20,", 0) == 0; });
  CHECK(std::vector<std::string>(from, all.end()) == std::vector<std::string>(tail.begin() + 1, tail.end()));
}
