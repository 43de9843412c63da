// `ballbox render` end to end, run as the user runs it: frame count and names, frame k after
// k·K steps, byte-identical reruns, the golden first frame, and the contract's errors.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "game/commands.h"
#include "game/session.h"
#include "render/context.h"
#include "render/png_writer.h"
#include "render/renderer.h"
#include "run_program.h"

namespace fs = std::filesystem;

namespace {

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "render_command" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using Run = testing::ProgramRun;
using testing::ReadFile;

// Runs `ballbox <args>` in `cwd`, stdout and stderr captured to files (so not a terminal).
Run Ballbox(const std::string& args, const fs::path& cwd) {
  return testing::RunShell("'" BALLBOX_EXE "' " + args, cwd, cwd / "captured");
}

std::set<std::string> FileNames(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  return names;
}

std::set<std::string> FrameNames(int count) {
  std::set<std::string> names;
  char name[32];
  for (int i = 0; i < count; ++i) {
    std::snprintf(name, sizeof name, "frame_%05d.png", i);
    names.insert(name);
  }
  return names;
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

void CheckExit2WithOneError(const Run& run) {
  INFO("stdout: " << run.out << "stderr: " << run.err);
  CHECK(run.exit_code == 2);
  CHECK(run.err.rfind("error: ", 0) == 0);
  CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

}  // namespace

TEST_CASE("render command: --frames and --every give that many frames, named in order",
          "[render][cli]") {
  const fs::path dir = FreshDir("count");
  const Run run = Ballbox("render --frames 5 --every 3 --size 160x120 --out frames", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(FileNames(dir / "frames") == FrameNames(5));  // no temporary files left either
  for (const std::string& name : FrameNames(5)) {
    const Decoded image = DecodePng(dir / "frames" / name);
    CHECK(image.width == 160);
    CHECK(image.height == 120);
  }
  // The events summary (the demo clicks at steps 40 and later come after these 12 steps), then
  // one summary line: frames, steps ((5 − 1) · 3), wall time, frames/s. No progress bar when
  // stderr is not a terminal.
  CHECK(std::count(run.out.begin(), run.out.end(), '\n') == 2);
  CHECK(run.out.rfind("events: 0 clicks applied, 0 hit a ball, 0 missed; 6 events after the end", 0) == 0);
  const std::string last = run.out.substr(run.out.find('\n') + 1);
  CHECK(last.rfind("render: default, ", 0) == 0);
  CHECK_THAT(last, Catch::Contains("5 frames") && Catch::Contains("12 steps") &&
                       Catch::Contains(" s ") && Catch::Contains("frames/s"));
  CHECK(run.err.empty());
}

TEST_CASE("render command: frame k shows the world after k*K steps", "[render][cli]") {
  const fs::path dir = FreshDir("stride");
  REQUIRE(Ballbox("render --frames 4 --every 5 --size 160x120 --out every5", dir).exit_code == 0);
  REQUIRE(Ballbox("render --frames 16 --size 160x120 --out every1", dir).exit_code == 0);
  for (int k = 0; k < 4; ++k) {
    INFO("frame " << k << " of --every 5 against frame " << 5 * k << " of --every 1");
    CHECK(ReadFile(dir / "every5" / FrameNames(k + 1).rbegin()->c_str()) ==
          ReadFile(dir / "every1" / FrameNames(5 * k + 1).rbegin()->c_str()));
  }
  // The scene moves, so the frames above are not all the same picture.
  CHECK(ReadFile(dir / "every1" / "frame_00000.png") != ReadFile(dir / "every1" / "frame_00015.png"));
}

TEST_CASE("render command: frame 0 is the initial state", "[render][cli]") {
  const fs::path dir = FreshDir("initial");
  REQUIRE(Ballbox("render --frames 3 --every 10 --size 200x150 --out frames", dir).exit_code == 0);

  // The default scene, drawn here before any step, encoded the same way.
  game::Expected<game::RunInput> input = game::LoadRunInput(game::RunOptions{{}, {}, 200, 150});
  REQUIRE(input.HasValue());
  game::Session session(input.Value().scene, input.Value().events, 200, 150);
  std::vector<render::Color> colors;
  for (const game::SceneBody& body : session.SceneDef().bodies) colors.push_back(body.color);
  std::string error;
  std::unique_ptr<render::GlContext> context = render::CreateOffscreenContext(error);
  REQUIRE(context);
  std::unique_ptr<render::Renderer> renderer = render::Renderer::Create(*context, 200, 150, error);
  REQUIRE(renderer);
  renderer->Draw(session.World(), colors, session.Camera());
  render::Image image;
  renderer->ReadImage(image);
  const std::vector<std::uint8_t> png = render::EncodePng(image);
  renderer.reset();

  const std::string frame0 = ReadFile(dir / "frames" / "frame_00000.png");
  CHECK(frame0 == std::string(png.begin(), png.end()));
  CHECK(frame0 != ReadFile(dir / "frames" / "frame_00001.png"));
}

TEST_CASE("render command: reruns write byte-identical images", "[render][cli]") {
  const fs::path dir = FreshDir("rerun");
  REQUIRE(Ballbox("render --frames 40 --every 2 --size 320x240 --out first", dir).exit_code == 0);
  REQUIRE(Ballbox("render --frames 40 --every 2 --size 320x240 --out second", dir).exit_code == 0);
  REQUIRE(FileNames(dir / "first") == FrameNames(40));
  REQUIRE(FileNames(dir / "second") == FrameNames(40));
  for (const std::string& name : FrameNames(40)) {
    INFO(name);
    CHECK(ReadFile(dir / "first" / name) == ReadFile(dir / "second" / name));
  }
}

TEST_CASE("render command: --threads 1 and 2 write byte-identical images of a pile that shares its step",
          "[render][cli][parallel]") {
  // 2 800 circles dropped into a box: past the 4 096 contacts and pairs from which the narrow
  // phase and the solve's colours are shared.
  const fs::path dir = FreshDir("threads");
  std::ostringstream json;
  json << "{\"bodies\": [\n"
          "  {\"shape\": \"box\", \"size\": [22, 1], \"position\": [0, -0.5], \"static\": true},\n"
          "  {\"shape\": \"box\", \"size\": [1, 40], \"position\": [-11.5, 20], \"static\": true},\n"
          "  {\"shape\": \"box\", \"size\": [1, 40], \"position\": [11.5, 20], \"static\": true}";
  for (int i = 0; i < 2800; ++i) {
    json << ",\n  {\"shape\": \"circle\", \"radius\": 0.25, \"position\": [" << -10.5 + 0.52 * (i % 40) + 0.01 * (i % 7)
         << ", " << 0.4 + 0.52 * (i / 40) << "]}";
  }
  json << "\n]}\n";
  std::ofstream(dir / "pile.json") << json.str();
  REQUIRE(Ballbox("render pile.json --frames 4 --every 15 --size 160x120 --threads 1 --out one", dir).exit_code == 0);
  REQUIRE(Ballbox("render pile.json --frames 4 --every 15 --size 160x120 --threads 2 --out two", dir).exit_code == 0);
  REQUIRE(FileNames(dir / "one") == FrameNames(4));
  for (const std::string& name : FrameNames(4)) {
    INFO(name);
    CHECK(ReadFile(dir / "one" / name) == ReadFile(dir / "two" / name));
  }
}

TEST_CASE("render command: the default folder is out/<scene name>", "[render][cli]") {
  const fs::path dir = FreshDir("default_dir");
  REQUIRE(Ballbox("render --frames 2 --size 64x48", dir).exit_code == 0);
  CHECK(FileNames(dir / "out" / "default") == FrameNames(2));

  std::ofstream(dir / "named.json") << R"({"name": "tiny", "bodies": [
    {"shape": "circle", "radius": 1, "position": [0, 0]}]})";
  std::ofstream(dir / "stem.json") << R"({"bodies": [
    {"shape": "box", "size": [1, 1], "position": [0, 0]}]})";
  REQUIRE(Ballbox("render named.json --frames 1 --size 64x48", dir).exit_code == 0);
  REQUIRE(Ballbox("render stem.json --frames 1 --size 64x48", dir).exit_code == 0);
  CHECK(FileNames(dir / "out" / "tiny") == FrameNames(1));
  CHECK(FileNames(dir / "out" / "stem") == FrameNames(1));
}

TEST_CASE("render command: the default scene's first frame matches the golden image",
          "[render][cli]") {
  // Regenerate after a deliberate change to the default scene or the look of the renderer:
  //   ballbox render --frames 1 --out /tmp/g
  //   cp /tmp/g/frame_00000.png tests/data/golden_default_frame0.png
  const fs::path dir = FreshDir("golden");
  REQUIRE(Ballbox("render --frames 1 --out frames", dir).exit_code == 0);
  const Decoded got = DecodePng(dir / "frames" / "frame_00000.png");
  const Decoded golden = DecodePng(fs::path(BALLBOX_TEST_DATA) / "golden_default_frame0.png");
  REQUIRE(got.width == 800);
  REQUIRE(got.height == 600);
  REQUIRE(golden.width == got.width);
  REQUIRE(golden.height == got.height);
  // Another Mesa, LLVM or CPU may round edge pixels differently, so allow small differences on
  // a few pixels; a moved, missing or recoloured body changes thousands.
  int differing = 0;
  int largest = 0;
  for (std::size_t i = 0; i < got.rgb.size(); i += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got.rgb[i + c] - golden.rgb[i + c]));
    largest = std::max(largest, worst);
    if (worst > 8) ++differing;
  }
  INFO("largest channel difference " << largest);
  CHECK(differing <= 200);  // of 480,000 pixels
}

TEST_CASE("render command: bad flags exit 2 with one error and write nothing", "[render][cli]") {
  const fs::path dir = FreshDir("bad_flags");
  for (const char* flags : {"--size 0x0", "--size 800", "--size 10x-4", "--frames 0",
                            "--frames -3", "--every 0", "--every x", "--frames", "--bogus"}) {
    INFO("flags: " << flags);
    CheckExit2WithOneError(Ballbox(std::string("render ") + flags + " --out frames", dir));
    CheckExit2WithOneError(Ballbox(std::string("render ") + flags, dir));
    CHECK_FALSE(fs::exists(dir / "frames"));
    CHECK_FALSE(fs::exists(dir / "out"));
  }
}

TEST_CASE("render command: a bad scene or script exits 2 and writes nothing", "[render][cli]") {
  const fs::path dir = FreshDir("bad_input");
  std::ofstream(dir / "broken.json") << "{\"bodies\": [\n  {\"shape\": \"circle\",, }\n]}\n";
  std::ofstream(dir / "broken.script") << "10 click 1 2\nnot a line\n";
  for (const char* args : {"render broken.json --out frames", "render missing.json --out frames",
                           "render --script broken.script --out frames"}) {
    INFO(args);
    const Run run = Ballbox(args, dir);
    CheckExit2WithOneError(run);
    const bool names_the_file =
        run.err.rfind("error: broken.", 0) == 0 || run.err.rfind("error: missing.json", 0) == 0;
    CHECK(names_the_file);
    CHECK_FALSE(fs::exists(dir / "frames"));
  }
}

TEST_CASE("render command: --out naming a file, or a folder inside one, exits 2", "[render][cli]") {
  // A bad flag value (docs/limits.md), refused before anything is written.
  const fs::path dir = FreshDir("bad_out");
  std::ofstream(dir / "a_file") << "not a folder\n";
  for (const char* out : {"a_file/frames", "a_file"}) {
    INFO("--out " << out);
    const Run run = Ballbox(std::string("render --frames 2 --size 64x48 --out ") + out, dir);
    CHECK(run.exit_code == 2);
    CHECK(run.err.rfind(std::string("error: ") + out, 0) == 0);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
  }
  CHECK(ReadFile(dir / "a_file") == "not a folder\n");
}

TEST_CASE("render command: a shorter rerun leaves only its own frames", "[render][cli]") {
  const fs::path dir = FreshDir("shorter");
  REQUIRE(Ballbox("render --frames 6 --size 64x48 --out frames", dir).exit_code == 0);
  // Files that only look like frames are the user's, not ours.
  for (const char* name : {"notes.txt", "frame_00009.jpg", "frame_0000009.png", "frame_x.png"}) {
    std::ofstream(dir / "frames" / name) << "keep\n";
  }
  REQUIRE(Ballbox("render --frames 2 --size 64x48 --out frames", dir).exit_code == 0);
  std::set<std::string> expected = FrameNames(2);
  expected.insert({"notes.txt", "frame_00009.jpg", "frame_0000009.png", "frame_x.png"});
  CHECK(FileNames(dir / "frames") == expected);
}
