// The frame writer behind `ballbox render`: file names, every queued frame written whole, and
// a write failure reported (exit 1) instead of lost.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "game/frame_writer.h"

namespace fs = std::filesystem;

namespace {

fs::path FreshDir(const std::string& name) {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "frame_writer" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

render::Image Solid(int width, int height, std::uint8_t value) {
  return render::Image{width, height,
                       std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 3, value)};
}

}  // namespace

TEST_CASE("frame writer: names have five digits, more when needed", "[render][frames]") {
  CHECK(game::FrameFileName(0) == "frame_00000.png");
  CHECK(game::FrameFileName(42) == "frame_00042.png");
  CHECK(game::FrameFileName(99999) == "frame_99999.png");
  CHECK(game::FrameFileName(100000) == "frame_100000.png");
  CHECK(game::FrameFileName(1234567) == "frame_1234567.png");
}

TEST_CASE("frame writer: every submitted frame is written, and nothing else", "[render][frames]") {
  const fs::path dir = FreshDir("all");
  {
    // A queue of one frame and three writers: Submit must block, not drop.
    game::FrameWriter writer(dir.string(), render::PngEncoding::kFast, 3, 1);
    for (int i = 0; i < 20; ++i) REQUIRE(writer.Submit(i, Solid(16, 8, static_cast<std::uint8_t>(i))));
    CHECK_FALSE(writer.Finish());
  }
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    INFO(entry.path());
    CHECK(entry.path().extension() == ".png");
  }
  CHECK(files == 20);
  for (int i = 0; i < 20; ++i) {
    int w = 0, h = 0, n = 0;
    const std::string path = (dir / game::FrameFileName(i)).string();
    stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &n, 3);
    REQUIRE(pixels != nullptr);
    CHECK(w == 16);
    CHECK(h == 8);
    CHECK(pixels[0] == i);  // frame i holds the image submitted as i
    stbi_image_free(pixels);
  }
}

TEST_CASE("frame writer: frames encoded side by side are written in the order submitted",
          "[render][frames]") {
  const fs::path dir = FreshDir("order");
  {
    // Frame 0 takes far longer to encode (a large image of noise) than the tiny ones after it,
    // which the other writers finish first: they must still wait for it, so that a full disk
    // stops the sequence at one place.
    render::Image slow = Solid(1200, 1200, 0);
    std::uint32_t noise = 12345;
    for (std::uint8_t& byte : slow.rgb) {
      noise = noise * 1664525u + 1013904223u;  // a linear congruential generator's steps
      byte = static_cast<std::uint8_t>(noise >> 24);
    }
    game::FrameWriter writer(dir.string(), render::PngEncoding::kFast, 3, 8);
    REQUIRE(writer.Submit(0, std::move(slow)));
    for (int i = 1; i < 8; ++i) REQUIRE(writer.Submit(i, Solid(16, 8, static_cast<std::uint8_t>(i))));
    CHECK_FALSE(writer.Finish());
  }
  for (int i = 0; i + 1 < 8; ++i) {
    INFO("frames " << i << " and " << i + 1);
    CHECK(fs::last_write_time(dir / game::FrameFileName(i)) <=
          fs::last_write_time(dir / game::FrameFileName(i + 1)));
  }
}

TEST_CASE("frame writer: a failed write is reported as an I/O failure", "[render][frames]") {
  const fs::path dir = FreshDir("gone") / "missing";  // never created
  game::FrameWriter writer(dir.string(), render::PngEncoding::kFast, 2, 2);
  bool accepted = true;
  // Once a write has failed, Submit refuses further frames; it must not block forever.
  for (int i = 0; i < 50 && accepted; ++i) accepted = writer.Submit(i, Solid(8, 8, 0));
  const game::Status status = writer.Finish();
  REQUIRE(status);
  CHECK(status->exit_code == game::kExitFailure);
  CHECK_THAT(status->message, Catch::Contains("missing/frame_0"));
}
