// The command line: ParseCommandLine in-process, then the ballbox binary end to end (exit codes, CSV dump).
#include <catch2/catch.hpp>

#include "print_ids.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "game/cli.h"
#include "game/default_scene.h"
#include "game/scene.h"
#include "game/script.h"
#include "game/session.h"
#include "run_program.h"

namespace fs = std::filesystem;

namespace {

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

game::CommandLine Parse(const std::vector<std::string>& args) {
  game::Expected<game::CommandLine> cl = game::ParseCommandLine(args);
  if (!cl.HasValue()) FAIL(cl.Error().message);
  return cl.Value();
}

void RequireUsageError(const std::vector<std::string>& args, const std::string& message) {
  const game::Expected<game::CommandLine> cl = game::ParseCommandLine(args);
  REQUIRE_FALSE(cl.HasValue());
  CHECK(cl.Error().exit_code == 2);
  CHECK(cl.Error().message == message);
}

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// A fresh, empty scratch folder for one test; outputs go inside it, captured streams beside it.
fs::path ScratchDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / ("cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using Run = testing::ProgramRun;
using testing::ReadFile;

// Runs the ballbox binary with `args`, stdout and stderr captured to files beside `dir`.
Run RunBallbox(const fs::path& dir, const std::vector<std::string>& args) {
  std::string command = std::string("'") + BALLBOX_EXE + "'";
  for (const std::string& a : args) command += " '" + a + "'";
  return testing::RunShell(command, fs::current_path(), dir);
}

std::string LastLine(const std::string& text) {
  const std::vector<std::string> lines = Split(text, '\n');
  return lines.empty() ? "" : lines.back();
}

bool IsEmptyDir(const fs::path& dir) { return fs::is_directory(dir) && fs::is_empty(dir); }

std::uint64_t Bits(double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  return bits;
}

// The contract's hash, written out independently: FNV-1a 64 over x, y, vx, vy, angle, ω (little-endian
// bytes).
std::string HashByHand(const engine::World& world) {
  std::uint64_t hash = 0xcbf29ce484222325ull;
  for (const engine::BodyId id : world.BodyIds()) {
    const engine::BodyState& s = world.State(id);
    for (double v : {s.position.x, s.position.y, s.velocity.x, s.velocity.y, s.angle, s.angular_velocity}) {
      const std::uint64_t bits = Bits(v);
      for (int byte = 0; byte < 8; ++byte) {
        hash ^= (bits >> (8 * byte)) & 0xff;
        hash *= 0x100000001b3ull;
      }
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

game::Scene LoadOrFail(const std::string& path) {
  game::Expected<game::Scene> scene = game::LoadScene(path);
  if (!scene.HasValue()) FAIL(scene.Error().message);
  return scene.Value();
}

}  // namespace

// --- ParseCommandLine in-process.

TEST_CASE("cli: no arguments, --help, -h and help print the usage", "[cli]") {
  for (const std::vector<std::string>& args : {std::vector<std::string>{}, {"--help"}, {"-h"}, {"help"}}) {
    const game::CommandLine cl = Parse(args);
    CHECK(cl.kind == game::CommandKind::kHelp);
    CHECK(cl.help_text.find("ballbox sim    [SCENE] [--script FILE] --steps N") != std::string::npos);
  }
}

TEST_CASE("cli: --version", "[cli]") { CHECK(Parse({"--version"}).kind == game::CommandKind::kVersion); }

TEST_CASE("cli: COMMAND --help gives that command's usage", "[cli]") {
  CHECK(Parse({"sim", "--help"}).help_text.rfind("usage: ballbox sim ", 0) == 0);
  CHECK(Parse({"render", "x.json", "--help"}).help_text.rfind("usage: ballbox render ", 0) == 0);
  CHECK(Parse({"play", "-h"}).help_text.rfind("usage: ballbox play ", 0) == 0);
  CHECK(Parse({"sim", "--help"}).kind == game::CommandKind::kHelp);
}

TEST_CASE("cli: sim defaults", "[cli]") {
  const game::CommandLine cl = Parse({"sim", "--steps", "5"});
  CHECK(cl.kind == game::CommandKind::kSim);
  CHECK(cl.sim.steps == 5);
  CHECK(cl.sim.dump_every == 1);
  CHECK_FALSE(cl.sim.dump_path.has_value());
  CHECK_FALSE(cl.sim.run.scene_path.has_value());
  CHECK_FALSE(cl.sim.run.script_path.has_value());
  CHECK(cl.sim.run.width == 800);
  CHECK(cl.sim.run.height == 600);
}

TEST_CASE("cli: render and play defaults", "[cli]") {
  const game::CommandLine render = Parse({"render"});
  CHECK(render.kind == game::CommandKind::kRender);
  CHECK(render.render.frames == 300);
  CHECK(render.render.every == 1);
  CHECK_FALSE(render.render.out_dir.has_value());
  CHECK((render.render.run.width == 800 && render.render.run.height == 600));
  const game::CommandLine play = Parse({"play", "s.json"});
  CHECK(play.kind == game::CommandKind::kPlay);
  CHECK(play.play.run.scene_path == "s.json");
  CHECK_FALSE(play.play.record_path.has_value());
}

TEST_CASE("cli: sim flags as --flag value and --flag=value", "[cli]") {
  const game::CommandLine a = Parse({"sim", "s.json", "--script", "in.txt", "--steps", "42", "--dump",
                                     "d.csv", "--dump-every", "7", "--size", "640x480"});
  const game::CommandLine b = Parse(
      {"sim", "--script=in.txt", "--steps=42", "--dump=d.csv", "--dump-every=7", "--size=640x480", "s.json"});
  for (const game::CommandLine& cl : {a, b}) {
    CHECK(cl.sim.run.scene_path == "s.json");
    CHECK(cl.sim.run.script_path == "in.txt");
    CHECK(cl.sim.steps == 42);
    CHECK(cl.sim.dump_path == "d.csv");
    CHECK(cl.sim.dump_every == 7);
    CHECK((cl.sim.run.width == 640 && cl.sim.run.height == 480));
  }
}

TEST_CASE("cli: render and play flags as --flag value and --flag=value", "[cli]") {
  for (const game::CommandLine& cl :
       {Parse({"render", "--frames", "12", "--every", "3", "--out", "o", "--size", "1x2"}),
        Parse({"render", "--frames=12", "--every=3", "--out=o", "--size=1x2"})}) {
    CHECK(cl.render.frames == 12);
    CHECK(cl.render.every == 3);
    CHECK(cl.render.out_dir == "o");
    CHECK((cl.render.run.width == 1 && cl.render.run.height == 2));
  }
  CHECK(Parse({"play", "--record", "r.txt"}).play.record_path == "r.txt");
  CHECK(Parse({"play", "--record=r.txt"}).play.record_path == "r.txt");
}

TEST_CASE("cli: sim --steps 0 is allowed", "[cli]") { CHECK(Parse({"sim", "--steps", "0"}).sim.steps == 0); }

TEST_CASE("cli error: unknown command", "[cli]") {
  RequireUsageError({"simulate"},
                    "unknown command \"simulate\" (expected render, sim or play) (see: ballbox --help)");
}

TEST_CASE("cli error: unknown option, long and short", "[cli]") {
  RequireUsageError({"sim", "--steps", "1", "--bogus"},
                    "unknown option \"--bogus\" for ballbox sim (see: ballbox sim --help)");
  RequireUsageError({"render", "-x"},
                    "unknown option \"-x\" for ballbox render (see: ballbox render --help)");
}

TEST_CASE("cli error: another command's option", "[cli]") {
  RequireUsageError({"render", "--steps", "5"},
                    "unknown option \"--steps\" for ballbox render (see: ballbox render --help)");
  RequireUsageError({"sim", "--steps", "5", "--frames", "3"},
                    "unknown option \"--frames\" for ballbox sim (see: ballbox sim --help)");
  RequireUsageError({"play", "--dump", "x.csv"},
                    "unknown option \"--dump\" for ballbox play (see: ballbox play --help)");
}

TEST_CASE("cli error: missing value, at the end or after =", "[cli]") {
  RequireUsageError({"sim", "--steps"}, "--steps needs a value (see: ballbox sim --help)");
  RequireUsageError({"sim", "--steps", "1", "--script="}, "--script needs a value (see: ballbox sim --help)");
  RequireUsageError({"render", "--out"}, "--out needs a value (see: ballbox render --help)");
}

TEST_CASE("cli error: bad --size", "[cli]") {
  for (const char* size :
       {"0x0", "800x", "axb", "x600", "800", "800x0", "-800x600", "800x600x2", "16385x100", "8e2x600"}) {
    RequireUsageError({"sim", "--steps", "1", "--size", size},
                      std::string("--size: expected WxH with whole numbers from 1 to 16384, got \"") + size +
                          "\" (see: ballbox sim --help)");
  }
}

TEST_CASE("cli error: a flag where a value belongs is a missing value", "[cli]") {
  // "--steps" must not be taken as the script path (and "5" as the scene).
  RequireUsageError({"sim", "--script", "--steps", "5"}, "--script needs a value (see: ballbox sim --help)");
}

TEST_CASE("cli: largest --size is allowed", "[cli]") {
  const game::CommandLine cl = Parse({"render", "--size", "16384x1"});
  CHECK((cl.render.run.width == 16384 && cl.render.run.height == 1));
}

TEST_CASE("cli error: bad counts", "[cli]") {
  RequireUsageError(
      {"sim", "--steps", "-1"},
      "--steps: expected a whole number from 0 to 1000000000000, got \"-1\" (see: ballbox sim --help)");
  RequireUsageError(
      {"sim", "--steps", "1.5"},
      "--steps: expected a whole number from 0 to 1000000000000, got \"1.5\" (see: ballbox sim --help)");
  RequireUsageError(
      {"sim", "--steps", "1", "--dump-every", "0"},
      "--dump-every: expected a whole number from 1 to 1000000000000, got \"0\" (see: ballbox sim --help)");
  RequireUsageError(
      {"render", "--frames", "0"},
      "--frames: expected a whole number from 1 to 100000000, got \"0\" (see: ballbox render --help)");
  RequireUsageError(
      {"render", "--every=abc"},
      "--every: expected a whole number from 1 to 1000000000000, got \"abc\" (see: ballbox render --help)");
}

TEST_CASE("cli: --threads for every simulating command, and its bounds", "[cli]") {
  CHECK(Parse({"sim", "--steps", "1"}).sim.run.threads == 0);  // 0: one per core
  CHECK(Parse({"sim", "--steps", "1", "--threads", "3"}).sim.run.threads == 3);
  CHECK(Parse({"render", "--threads=1"}).render.run.threads == 1);
  CHECK(Parse({"play", "--threads", "256"}).play.run.threads == 256);
  RequireUsageError({"sim", "--steps", "1", "--threads", "0"},
                    "--threads: expected a whole number from 1 to 256, got \"0\" (see: ballbox sim --help)");
  RequireUsageError({"render", "--threads", "257"},
                    "--threads: expected a whole number from 1 to 256, got \"257\" (see: ballbox render --help)");
}

TEST_CASE("cli error: sim without --steps", "[cli]") {
  RequireUsageError({"sim", "s.json"}, "ballbox sim needs --steps N (see: ballbox sim --help)");
}

TEST_CASE("cli error: two scenes", "[cli]") {
  RequireUsageError({"sim", "a.json", "--steps", "1", "b.json"},
                    "more than one scene given: \"a.json\" and \"b.json\" (see: ballbox sim --help)");
}

TEST_CASE("cli error: a flag given twice", "[cli]") {
  // The later value would win silently; `--steps 10 --steps 20` may be a typo for anything.
  RequireUsageError({"sim", "--steps", "10", "--steps", "20"},
                    "--steps is given more than once (see: ballbox sim --help)");
  RequireUsageError({"render", "--script", "a.txt", "--script=b.txt"},
                    "--script is given more than once (see: ballbox render --help)");
  RequireUsageError({"render", "--hud", "--hud"}, "--hud is given more than once (see: ballbox render --help)");
  RequireUsageError({"play", "--misses", "--size", "8x6", "--misses"},
                    "--misses is given more than once (see: ballbox play --help)");
}

TEST_CASE("cli: the film and events flags", "[cli]") {
  const game::CommandLine cl = Parse({"render", "--video", "film.MP4", "--camera", "-1.5,2e1,+10",
                                      "--follow", "small_ball", "--from", "120", "--hud", "--misses"});
  CHECK(cl.render.video_path == "film.MP4");
  REQUIRE(cl.render.view.camera);
  CHECK(cl.render.view.camera->center.x == -1.5);
  CHECK(cl.render.view.camera->center.y == 20);
  CHECK(cl.render.view.camera->width == 10);
  CHECK(cl.render.view.follow == "small_ball");
  CHECK(cl.render.from == 120);
  CHECK(cl.render.hud);
  CHECK(cl.render.run.list_misses);
  const game::CommandLine defaults = Parse({"render"});
  CHECK_FALSE(defaults.render.video_path);
  CHECK_FALSE(defaults.render.view.camera);
  CHECK_FALSE(defaults.render.view.follow);
  CHECK(defaults.render.from == 0);
  CHECK_FALSE(defaults.render.hud);
  CHECK_FALSE(defaults.render.run.list_misses);
  const game::CommandLine play = Parse({"play", "--camera=0,5,30", "--follow=ball"});
  CHECK(play.play.view.camera->width == 30);
  CHECK(play.play.view.follow == "ball");
  CHECK(Parse({"sim", "--steps", "3", "--misses"}).sim.run.list_misses);
}

TEST_CASE("cli error: bad film flags", "[cli]") {
  for (const char* camera : {"1,2", "1,2,0", "1,2,-3", "a,2,3", "1,2,3,4", "1,,3", "1e10,0,5", "1,2,inf", "1;2;3"}) {
    RequireUsageError({"render", "--camera", camera},
                      std::string("--camera: expected X,Y,WIDTH (metres; WIDTH > 0, each at most 1e9 in size), got \"") +
                          camera + "\" (see: ballbox render --help)");
  }
  RequireUsageError({"render", "--from", "-1"},
                    "--from: expected a whole number from 0 to 1000000000000, got \"-1\" (see: ballbox render --help)");
  RequireUsageError({"render", "--video", "film.mov"},
                    "--video: \"film.mov\" does not end in .mp4, .webm or .gif (see: ballbox render --help)");
  RequireUsageError({"render", "--hud=yes"}, "--hud takes no value, got \"yes\" (see: ballbox render --help)");
  RequireUsageError({"sim", "--steps", "1", "--hud"}, "unknown option \"--hud\" for ballbox sim (see: ballbox sim --help)");
  RequireUsageError({"play", "--video", "a.mp4"}, "unknown option \"--video\" for ballbox play (see: ballbox play --help)");
}

TEST_CASE("cli: every flag a command takes is in its --help", "[cli]") {
  const std::vector<std::pair<std::string, std::vector<std::string>>> flags = {
      {"render", {"--script", "--size", "--misses", "--frames", "--every", "--out", "--video", "--camera",
                  "--follow", "--from", "--hud"}},
      {"sim", {"--script", "--size", "--misses", "--steps", "--dump", "--dump-every"}},
      {"play", {"--script", "--size", "--misses", "--record", "--camera", "--follow"}}};
  // The flag as a whole word: "--every" must not be found inside "--dump-every".
  auto names_flag = [](const std::string& text, const std::string& flag) {
    for (std::size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + 1)) {
      const char before = at > 0 ? text[at - 1] : ' ';
      const char after = at + flag.size() < text.size() ? text[at + flag.size()] : ' ';
      if ((before == ' ' || before == '[') && (after == ' ' || after == ']')) return true;
    }
    return false;
  };
  for (const auto& [command, names] : flags) {
    const std::string help = Parse({command, "--help"}).help_text;
    const std::string usage = Parse({"--help"}).help_text;
    for (const std::string& flag : names) {
      INFO(command << " " << flag);
      CHECK(help.find("\n  " + flag + " ") != std::string::npos);  // a line that explains it
      CHECK(names_flag(help.substr(0, help.find("\n\n")), flag));  // in the usage line
      const std::string line = usage.substr(usage.find("ballbox " + command));
      CHECK(names_flag(line.substr(0, line.find("ballbox", 8)), flag));  // and in ballbox --help
    }
  }
}

// --- The real binary.

TEST_CASE("ballbox --help, COMMAND --help and --version exit 0 on stdout", "[cli][exe]") {
  const fs::path dir = ScratchDir("help");
  const Run help = RunBallbox(dir, {"--help"});
  CHECK(help.exit_code == 0);
  CHECK(help.out.find("usage:") != std::string::npos);
  CHECK(help.err.empty());
  const Run sim_help = RunBallbox(dir, {"sim", "--help"});
  CHECK(sim_help.exit_code == 0);
  CHECK(sim_help.out.rfind("usage: ballbox sim", 0) == 0);
  const Run version = RunBallbox(dir, {"--version"});
  CHECK(version.exit_code == 0);
  CHECK(version.out == std::string("ballbox ") + game::VersionString() + "\n");
}

TEST_CASE("ballbox sim --steps 0 ends with the hash of the initial default scene", "[cli][exe]") {
  const Run run = RunBallbox(ScratchDir("steps0"), {"sim", "--steps", "0"});
  REQUIRE(run.exit_code == 0);
  CHECK(run.err.empty());
  const std::string last = LastLine(run.out);
  CHECK(std::regex_match(last, std::regex("state-hash: [0-9a-f]{16}")));
  game::Expected<game::Scene> scene = game::ParseScene(game::DefaultSceneJson(), "<default>", "default");
  REQUIRE(scene.HasValue());
  CHECK(last == "state-hash: " + HashByHand(game::BuildWorld(scene.Value())));
}

TEST_CASE("ballbox sim: the same state hash at --threads 1, 2 and 3 on a pile that shares its step out",
          "[cli][exe][parallel]") {
  // 2 800 circles dropped into a box: enough contacts (over 4 096) that the narrow phase and the
  // solve's colours are shared among the threads.
  const fs::path dir = ScratchDir("threads");
  std::string json = "{\"bodies\": [\n"
                     "  {\"shape\": \"box\", \"size\": [22, 1], \"position\": [0, -0.5], \"static\": true},\n"
                     "  {\"shape\": \"box\", \"size\": [1, 40], \"position\": [-11.5, 20], \"static\": true},\n"
                     "  {\"shape\": \"box\", \"size\": [1, 40], \"position\": [11.5, 20], \"static\": true}";
  for (int i = 0; i < 2800; ++i) {
    const double x = -10.5 + 0.52 * (i % 40) + 0.01 * (i % 7);
    const double y = 0.4 + 0.52 * (i / 40);
    json += ",\n  {\"shape\": \"circle\", \"radius\": 0.25, \"position\": [" + std::to_string(x) + ", " +
            std::to_string(y) + "]}";
  }
  json += "\n]}\n";
  const fs::path scene = dir / "pile.json";
  std::ofstream(scene) << json;
  std::vector<std::string> hashes;
  for (const char* threads : {"1", "2", "3"}) {
    const Run run = RunBallbox(dir, {"sim", scene.string(), "--steps", "60", "--threads", threads});
    REQUIRE(run.exit_code == 0);
    hashes.push_back(LastLine(run.out));
  }
  CHECK(std::regex_match(hashes[0], std::regex("state-hash: [0-9a-f]{16}")));
  CHECK(hashes[1] == hashes[0]);
  CHECK(hashes[2] == hashes[0]);
}

TEST_CASE("ballbox sim: a bad scene is exit 2, one error line, nothing written", "[cli][exe]") {
  const fs::path dir = ScratchDir("bad_scene");
  const std::string scene = DataPath("scene_bad_radius.json");
  const Run run = RunBallbox(dir, {"sim", scene, "--steps", "5", "--dump", (dir / "d.csv").string()});
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + scene + ": bodies[2].radius: must be > 0\n");
  CHECK(run.out.empty());
  CHECK(IsEmptyDir(dir));
}

TEST_CASE("ballbox sim: a body both static and kinematic is exit 2, naming the key", "[cli][exe][kinematic]") {
  const fs::path dir = ScratchDir("static_kinematic");
  const std::string scene = DataPath("scene_static_kinematic.json");
  const Run run = RunBallbox(dir, {"sim", scene, "--steps", "5", "--dump", (dir / "d.csv").string()});
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + scene + ": bodies[1].kinematic: a body cannot be both static and kinematic\n");
  CHECK(run.out.empty());
  CHECK(IsEmptyDir(dir));
}

TEST_CASE("ballbox sim: a bad script is exit 2, one error line, nothing written", "[cli][exe]") {
  const fs::path dir = ScratchDir("bad_script");
  const std::string script = DataPath("script_decreasing.txt");
  const Run run = RunBallbox(dir, {"sim", DataPath("cli_scene.json"), "--script", script, "--steps", "5",
                                   "--dump", (dir / "d.csv").string()});
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + script +
                       ":4: step 5 comes before the previous event's step 10 (steps must not decrease)\n");
  CHECK(run.out.empty());
  CHECK(IsEmptyDir(dir));
}

TEST_CASE("ballbox sim: a bad flag is exit 2, one error line, nothing written", "[cli][exe]") {
  const fs::path dir = ScratchDir("bad_flag");
  const Run run = RunBallbox(dir, {"sim", DataPath("cli_scene.json"), "--steps", "5", "--dump",
                                   (dir / "d.csv").string(), "--dump-every", "0"});
  CHECK(run.exit_code == 2);
  CHECK(run.err ==
        "error: --dump-every: expected a whole number from 1 to 1000000000000, got \"0\" (see: ballbox sim "
        "--help)\n");
  CHECK(run.out.empty());
  const Run unknown = RunBallbox(dir, {"sim", "--steps", "5", "--dump", (dir / "d.csv").string(), "--bogus"});
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err == "error: unknown option \"--bogus\" for ballbox sim (see: ballbox sim --help)\n");
  CHECK(unknown.out.empty());
  CHECK(IsEmptyDir(dir));
}

TEST_CASE("ballbox sim: a missing scene file is exit 2", "[cli][exe]") {
  const fs::path dir = ScratchDir("missing_scene");
  const std::string scene = (dir / "nope.json").string();
  const Run run = RunBallbox(dir, {"sim", scene, "--steps", "1"});
  CHECK(run.exit_code == 2);
  CHECK(run.err == "error: " + scene + ": cannot open: No such file or directory\n");
}

TEST_CASE("ballbox sim: a scene number too large for a double is exit 2, not a crash",
          "[cli][exe]") {
  // nlohmann reports 1e999 as out_of_range, which must not escape and abort the program.
  const std::string scene = DataPath("scene_non_finite.json");
  const Run run = RunBallbox(ScratchDir("non_finite"), {"sim", scene, "--steps", "1"});
  CHECK(run.exit_code == 2);
  CHECK(run.err.rfind("error: " + scene + ":", 0) == 0);
  CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

TEST_CASE("ballbox sim: an unwritable --dump path is exit 1", "[cli][exe]") {
  const fs::path dir = ScratchDir("unwritable");
  const std::string dump = (dir / "no_such_dir" / "d.csv").string();
  const Run run = RunBallbox(dir, {"sim", DataPath("cli_scene.json"), "--steps", "3", "--dump", dump});
  CHECK(run.exit_code == 1);
  CHECK(run.err == "error: " + dump + ": cannot write: No such file or directory\n");
  CHECK(IsEmptyDir(dir));
}

TEST_CASE("ballbox sim --dump: header, scene order, step 0, --dump-every spacing, exact doubles",
          "[cli][exe]") {
  const fs::path dir = ScratchDir("dump");
  const std::string scene_path = DataPath("cli_scene.json"), script_path = DataPath("cli_script.txt");
  const std::int64_t steps = 50, every = 7;
  const Run run =
      RunBallbox(dir, {"sim", scene_path, "--script", script_path, "--steps", std::to_string(steps), "--dump",
                       (dir / "d.csv").string(), "--dump-every", std::to_string(every)});
  REQUIRE(run.exit_code == 0);
  const std::vector<std::string> lines = Split(ReadFile(dir / "d.csv"), '\n');
  REQUIRE(!lines.empty());
  CHECK(lines[0] == "step,time,id,x,y,vx,vy,angle,omega");

  // The same run in-process: same scene, same events, same image size.
  const game::Scene scene = LoadOrFail(scene_path);
  const auto events = game::LoadScript(script_path);
  REQUIRE(events.HasValue());
  game::Session session(scene, events.Value(), 800, 600);
  const std::size_t bodies = scene.bodies.size();
  REQUIRE(bodies == 4);
  std::size_t row = 1;
  for (std::int64_t step = 0; step <= steps; ++step) {
    if (step > 0) session.Step();
    if (step % every != 0) continue;
    for (std::size_t id = 0; id < bodies; ++id, ++row) {
      INFO("step " << step << " body " << id);
      REQUIRE(row < lines.size());
      const std::vector<std::string> f = Split(lines[row], ',');
      REQUIRE(f.size() == 9);
      CHECK(f[0] == std::to_string(step));
      CHECK(Bits(std::strtod(f[1].c_str(), nullptr)) == Bits(static_cast<double>(step) * scene.world.dt));
      CHECK(f[2] == scene.bodies[id].id);
      const engine::BodyState& s = session.World().State({static_cast<engine::BodyIndex>(id)});
      const double expected[] = {s.position.x, s.position.y, s.velocity.x,
                                 s.velocity.y, s.angle,      s.angular_velocity};
      for (int k = 0; k < 6; ++k) CHECK(Bits(std::strtod(f[3 + k].c_str(), nullptr)) == Bits(expected[k]));
    }
  }
  CHECK(row == 1 + 8 * bodies);  // steps 0, 7, ..., 49
  CHECK(lines.size() == row);
  CHECK(LastLine(run.out) == "state-hash: " + HashByHand(session.World()));
}

TEST_CASE("ballbox sim --steps 0 --dump writes the header and step 0 only", "[cli][exe]") {
  const fs::path dir = ScratchDir("dump0");
  const Run run = RunBallbox(
      dir, {"sim", DataPath("cli_scene.json"), "--steps", "0", "--dump=" + (dir / "d.csv").string()});
  REQUIRE(run.exit_code == 0);
  CHECK(ReadFile(dir / "d.csv") ==
        "step,time,id,x,y,vx,vy,angle,omega\n"
        "0,0,floor,0,-0.5,0,0,0,0\n"
        "0,0,ball,0,2,1,0,0,0\n"
        "0,0,crate,2,0.5,0,0,0,0\n"
        "0,0,pebble,-1,3,0.5,0,0.10000000000000001,2\n");
}

TEST_CASE("ballbox sim: the same command twice gives the same hash and dump", "[cli][exe]") {
  const fs::path dir = ScratchDir("twice");
  std::vector<std::string> hashes, dumps;
  for (const char* name : {"a.csv", "b.csv"}) {
    const Run run =
        RunBallbox(dir, {"sim", DataPath("cli_scene.json"), "--script", DataPath("cli_script.txt"), "--steps",
                         "120", "--dump", (dir / name).string()});
    REQUIRE(run.exit_code == 0);
    hashes.push_back(LastLine(run.out));
    dumps.push_back(ReadFile(dir / name));
  }
  CHECK(std::regex_match(hashes[0], std::regex("state-hash: [0-9a-f]{16}")));
  CHECK(hashes[0] == hashes[1]);
  CHECK(dumps[0] == dumps[1]);
}

TEST_CASE("ballbox sim --dump: an id with a comma still gives 9 CSV fields a row", "[cli][exe]") {
  // Written raw, "ball,1" would split into 10 fields; the CSV quotes it (RFC 4180).
  const fs::path dir = ScratchDir("comma_id");
  const Run run = RunBallbox(
      dir, {"sim", DataPath("cli_comma_id.json"), "--steps", "0", "--dump", (dir / "d.csv").string()});
  if (run.exit_code == 2) {
    CHECK(run.err.find("bodies[0].id") != std::string::npos);
    return;
  }
  REQUIRE(run.exit_code == 0);
  const std::vector<std::string> lines = Split(ReadFile(dir / "d.csv"), '\n');
  REQUIRE(lines.size() == 2);
  CHECK(lines[1] == "0,0,\"ball,1\",0,2,0,0,0,0");
}
