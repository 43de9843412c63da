// `ballbox render --video`: each format opened back with FFmpeg's own decoders (codec, pixel
// format, frame count, frame rate, frame times), compared with the PNG frames of the same run,
// byte-identical on rerun, never changing the pictures, and refusing what it cannot write.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "render/video_encoder.h"
#include "run_program.h"

namespace fs = std::filesystem;
using testing::Ballbox;

namespace {

fs::path FreshDir(const std::string& name) { return testing::FreshTestDir("video", name); }

void CheckExit2WithOneError(const testing::ProgramRun& run) {
  INFO("stdout: " << run.out << "stderr: " << run.err);
  CHECK(run.exit_code == 2);
  CHECK(run.err.rfind("error: ", 0) == 0);
  CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

}  // namespace

#if BALLBOX_VIDEO_PROBE
#include "video_probe.h"

namespace {

std::vector<std::uint8_t> PngPixels(const fs::path& path, int& width, int& height) {
  int channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels, 3);
  REQUIRE(pixels != nullptr);
  std::vector<std::uint8_t> rgb(pixels, pixels + static_cast<std::size_t>(width) * height * 3);
  stbi_image_free(pixels);
  return rgb;
}

struct Difference {
  double mean = 0.0;          // mean absolute difference per channel, in levels
  double exact_share = 0.0;   // pixels equal in all three channels
};

Difference Compare(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  REQUIRE(a.size() == b.size());
  Difference d;
  std::size_t exact = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); i += 3) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = std::abs(a[i + c] - b[i + c]);
      sum += e;
      worst = std::max(worst, e);
    }
    if (worst == 0) ++exact;
  }
  d.mean = sum / static_cast<double>(a.size());
  d.exact_share = static_cast<double>(exact) / static_cast<double>(a.size() / 3);
  return d;
}

// The film in both forms from one run: frames/ as PNG and `video`.
testing::ProbedVideo RenderBoth(const fs::path& dir, const std::string& video, const std::string& flags) {
  const testing::ProgramRun run = Ballbox("render " + flags + " --out frames --video " + video, dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const testing::ProbedVideo probed = testing::ProbeVideo((dir / video).string(), 1000);
  INFO(probed.error);
  REQUIRE(probed.opened);
  return probed;
}

}  // namespace

TEST_CASE("render --video: an .mp4 is H.264 in yuv420p at 60 frames/s, every frame, close to the PNGs",
          "[video]") {
  const fs::path dir = FreshDir("mp4");
  const testing::ProbedVideo video = RenderBoth(dir, "film.mp4", "--frames 12 --size 160x120");
  CHECK(video.codec == "h264");
  CHECK(video.pixel_format == "yuv420p");
  CHECK(video.width == 160);
  CHECK(video.height == 120);
  CHECK(video.rate_num == 60);  // the default scene's dt is 1/60 s, K = 1
  CHECK(video.rate_den == 1);
  REQUIRE(video.frame_seconds.size() == 12);
  for (std::size_t k = 0; k < 12; ++k) CHECK(video.frame_seconds[k] == Approx(k / 60.0).margin(1e-3));
  for (int k : {0, 11}) {
    int w = 0, h = 0;
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", k);
    const Difference d = Compare(PngPixels(dir / "frames" / name, w, h), video.rgb[k]);
    INFO("frame " << k << ": mean difference " << d.mean);
    CHECK(d.mean < 4.0);  // lossy, but the same picture: a moved body differs by far more
  }
}

TEST_CASE("render --video: a .webm is VP9 at 1/(dt*K) frames/s", "[video]") {
  const fs::path dir = FreshDir("webm");
  const testing::ProbedVideo video = RenderBoth(dir, "film.webm", "--frames 6 --every 2 --size 96x72");
  CHECK(video.codec == "vp9");
  CHECK(video.pixel_format == "yuv420p");
  CHECK(video.rate_num == 30);  // 1 / (1/60 s · 2)
  CHECK(video.rate_den == 1);
  REQUIRE(video.frame_seconds.size() == 6);
  CHECK(video.frame_seconds.back() == Approx(5 / 30.0).margin(1e-3));
  int w = 0, h = 0;
  CHECK(Compare(PngPixels(dir / "frames" / "frame_00005.png", w, h), video.rgb[5]).mean < 4.0);
}

TEST_CASE("render --video: a .gif keeps frames 2/100 s apart, in real time, its palette exact on "
          "flat colour", "[video]") {
  const fs::path dir = FreshDir("gif");
  const testing::ProbedVideo video = RenderBoth(dir, "film.gif", "--frames 12 --size 200x150");
  CHECK(video.codec == "gif");
  // Frames k = 0..11 fall at round(100 k / 60) hundredths: 0 2 3 5 7 8 10 12 13 15 17 18. Kept
  // are those at least 2 after the last kept: k = 0 1 3 4 6 7 9 10.
  const std::vector<double> expected = {0.00, 0.02, 0.05, 0.07, 0.10, 0.12, 0.15, 0.17};
  REQUIRE(video.frame_seconds.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) CHECK(video.frame_seconds[i] == Approx(expected[i]).margin(1e-6));
  const int kept_frame[] = {0, 1, 3, 4, 6, 7, 9, 10};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    int w = 0, h = 0;
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", kept_frame[i]);
    const Difference d = Compare(PngPixels(dir / "frames" / name, w, h), video.rgb[i]);
    INFO(name << ": " << d.exact_share << " exact, mean " << d.mean);
    CHECK(d.exact_share > 0.98);  // fills, outlines and background exact; only edge blends move
    CHECK(d.mean < 0.5);
  }
}

TEST_CASE("render --video: the same film twice gives the same bytes", "[video]") {
  const fs::path dir = FreshDir("rerun");
  for (const char* name : {"a.mp4", "b.mp4", "a.gif", "b.gif", "a.webm", "b.webm"}) {
    REQUIRE(Ballbox(std::string("render --frames 20 --size 96x72 --video ") + name, dir).exit_code == 0);
  }
  CHECK(testing::ReadFile(dir / "a.mp4") == testing::ReadFile(dir / "b.mp4"));
  CHECK(testing::ReadFile(dir / "a.gif") == testing::ReadFile(dir / "b.gif"));
  CHECK(testing::ReadFile(dir / "a.webm") == testing::ReadFile(dir / "b.webm"));
  CHECK(testing::ReadFile(dir / "a.mp4") != testing::ReadFile(dir / "a.gif"));
}

#else

TEST_CASE("render --video in a build without FFmpeg says so and exits 1", "[video]") {
  const fs::path dir = FreshDir("not_built");
  const testing::ProgramRun run = Ballbox("render --frames 2 --size 64x48 --video film.mp4", dir);
  CHECK(run.exit_code == 1);
  CHECK(run.err.find("without FFmpeg") != std::string::npos);
  CHECK(testing::SortedNames(dir).empty());
}

#endif

TEST_CASE("render --video alone writes the video and nothing else", "[video]") {
  if (!render::VideoSupportBuilt()) return;
  const fs::path dir = FreshDir("alone");
  const testing::ProgramRun run = Ballbox("render --frames 5 --size 64x48 --video films/film.gif", dir);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(testing::SortedNames(dir) == std::vector<std::string>{"films"});  // no out/ folder
  CHECK(testing::SortedNames(dir / "films") == std::vector<std::string>{"film.gif"});  // no temporary file
  CHECK_THAT(run.out, Catch::Contains("-> films/film.gif (GIF, 4 frames over 0.08 s)"));
}

TEST_CASE("render --video does not change the pictures or the simulation", "[video]") {
  if (!render::VideoSupportBuilt()) return;
  const fs::path dir = FreshDir("same_pictures");
  REQUIRE(Ballbox("render --frames 50 --every 6 --size 120x90 --out plain", dir).exit_code == 0);
  REQUIRE(Ballbox("render --frames 50 --every 6 --size 120x90 --out with --video film.mp4", dir).exit_code == 0);
  const std::vector<std::string> names = testing::SortedNames(dir / "plain");
  REQUIRE(names.size() == 50);
  CHECK(testing::SortedNames(dir / "with") == names);
  for (const std::string& name : names) {
    INFO(name);
    CHECK(testing::ReadFile(dir / "plain" / name) == testing::ReadFile(dir / "with" / name));
  }
}

TEST_CASE("render --video: bad names and sizes exit 2 with one line and write nothing", "[video]") {
  const fs::path dir = FreshDir("bad");
  fs::create_directories(dir / "folder.mp4");
  for (const char* args : {"--video film.avi", "--video film", "--video .mp4", "--video film.mp4 --size 321x240",
                           "--video film.mp4 --size 320x241", "--video folder.mp4", "--video=",
                           "--video a.mp4 --video b.mp4"}) {
    INFO(args);
    CheckExit2WithOneError(Ballbox(std::string("render --frames 2 ") + args, dir));
    CHECK(testing::SortedNames(dir) == std::vector<std::string>{"folder.mp4"});
  }
  const testing::ProgramRun odd = Ballbox("render --frames 2 --video film.mp4 --size 321x241", dir);
  CHECK(odd.err == "error: --video film.mp4: an .mp4 film (H.264 in yuv420p) needs an even width and "
                   "height, got 321x241 (try 322x242)\n");
}
