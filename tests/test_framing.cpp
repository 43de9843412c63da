// Framing at any size (contract: the script's size line; "at least the world region the camera
// shows at 800x600, the wider side grows"): the camera math, the size line's pixel mapping, the
// default demo's state hash at every size, and the floor in the picture at 16:9.
#include <catch2/catch.hpp>

#include <stb/stb_image.h>

#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <string>

#include "game/commands.h"
#include "game/session.h"
#include "render/camera.h"
#include "run_program.h"

namespace fs = std::filesystem;
using engine::Vec2;

namespace {

// The world rectangle an image shows, from its own corners.
struct Region {
  double left, right, bottom, top;
};

Region Shows(const render::Camera& camera, int w, int h) {
  const Vec2 top_left = render::PixelToWorld(camera, w, h, 0, 0);
  const Vec2 bottom_right = render::PixelToWorld(camera, w, h, w, h);
  return {top_left.x, bottom_right.x, bottom_right.y, top_left.y};
}

std::uint64_t DemoHashAt(int width, int height, std::int64_t steps) {
  game::Expected<game::RunInput> input = game::LoadRunInput(game::RunOptions{{}, {}, width, height});
  REQUIRE(input.HasValue());
  game::Session session(input.Value().scene, input.Value().events, width, height);
  for (std::int64_t i = 0; i < steps; ++i) session.Step();
  CHECK(session.Events().Hits() == 6);
  return session.World().StateHash();
}

}  // namespace

TEST_CASE("framing: 4:3 sizes keep the view bit for bit, wider ones grow the width, taller ones "
          "the height", "[framing][camera]") {
  const render::Camera view{{1.5, 6.5}, 22.0};
  for (auto [w, h] : {std::pair{800, 600}, {320, 240}, {1600, 1200}, {4, 3}}) {
    const render::Camera framed = render::FrameCamera(view, w, h);
    CHECK(framed.width == view.width);  // exactly: pixel clicks at 4:3 sizes map as before
    CHECK(framed.center == view.center);
  }
  // 16:9 at 1280x720: the 800x600 view's height, 22 * 3/4 = 16.5 m, stays; the width grows to
  // 16.5 * 16/9 = 29.333 m.
  const Region wide = Shows(render::FrameCamera(view, 1280, 720), 1280, 720);
  CHECK(wide.top - wide.bottom == Approx(16.5).epsilon(1e-12));
  CHECK(wide.right - wide.left == Approx(16.5 * 16.0 / 9.0).epsilon(1e-12));
  // Portrait 600x800: the width stays 22 m, the height grows to 22 * 4/3.
  const Region tall = Shows(render::FrameCamera(view, 600, 800), 600, 800);
  CHECK(tall.right - tall.left == Approx(22.0).epsilon(1e-12));
  CHECK(tall.top - tall.bottom == Approx(22.0 * 4.0 / 3.0).epsilon(1e-12));
}

TEST_CASE("framing: every size shows at least the region the camera shows at 800x600, centred the "
          "same", "[framing][camera]") {
  const render::Camera view{{-3.0, 2.0}, 10.0};
  const Region reference = Shows(view, 800, 600);
  for (auto [w, h] : {std::pair{1280, 720}, {600, 800}, {320, 240}, {1, 1}, {16384, 1}, {1, 16384},
                      {333, 777}, {1921, 1080}}) {
    INFO(w << "x" << h);
    const Region r = Shows(render::FrameCamera(view, w, h), w, h);
    const double slack = 1e-9;
    CHECK(r.left <= reference.left + slack);
    CHECK(r.right >= reference.right - slack);
    CHECK(r.bottom <= reference.bottom + slack);
    CHECK(r.top >= reference.top - slack);
    // One side fits exactly: the picture is not larger than it needs to be.
    const bool width_fits = std::abs((r.right - r.left) - (reference.right - reference.left)) < 1e-9;
    const bool height_fits = std::abs((r.top - r.bottom) - (reference.top - reference.bottom)) < 1e-9;
    CHECK((width_fits || height_fits));
    CHECK((r.left + r.right) / 2 == Approx(-3.0).margin(1e-9));
    CHECK((r.bottom + r.top) / 2 == Approx(2.0).margin(1e-9));
  }
}

TEST_CASE("framing: the default demo's 300-step state hash is the same at every size",
          "[framing][determinism]") {
  // README: sim --steps 300 gives 61e9c117a690e3b1 at 800x600. Its script's size line maps the
  // six clicks at 800x600 whatever size is rendered, so they hit the same balls everywhere.
  for (auto [w, h] : {std::pair{800, 600}, {1280, 720}, {600, 800}, {320, 240}, {1920, 1080}, {97, 1013}}) {
    INFO(w << "x" << h);
    CHECK(DemoHashAt(w, h, 300) == 0x61e9c117a690e3b1u);
  }
}

TEST_CASE("framing: a size line maps pixel clicks at its size; without one they map at the size "
          "rendered", "[framing][click]") {
  game::Expected<game::RunInput> input = game::LoadRunInput({});
  REQUIRE(input.HasValue());
  const game::Scene& scene = input.Value().scene;
  const game::InputEvent sized{0, game::EventKind::kClickPixel, {361, 231}, 800, 600};
  const game::InputEvent unsized{0, game::EventKind::kClickPixel, {361, 231}};
  const game::Session at_800(scene, {}, 800, 600);
  const game::Session at_1280(scene, {}, 1280, 720);
  // The scene's camera: centre (0, 6.5), 22 m across 800 px, so s = 0.0275 m per pixel.
  const Vec2 expected{0 + (361 - 400) * 0.0275, 6.5 - (231 - 300) * 0.0275};
  CHECK(at_800.EventPoint(sized).x == Approx(expected.x).epsilon(1e-15));
  CHECK(at_800.EventPoint(sized).y == Approx(expected.y).epsilon(1e-15));
  CHECK(at_1280.EventPoint(sized) == at_800.EventPoint(sized));  // bit for bit
  CHECK(at_800.EventPoint(unsized) == at_800.EventPoint(sized));
  // Without the size line the pixel is read at 1280x720: s = 29.333 / 1280, centre at (640, 360).
  const double s = 16.5 * 16.0 / 9.0 / 1280.0;
  CHECK(at_1280.EventPoint(unsized).x == Approx((361 - 640) * s).epsilon(1e-12));
  CHECK(at_1280.EventPoint(unsized).y == Approx(6.5 - (231 - 360) * s).epsilon(1e-12));
}

TEST_CASE("framing: the default scene rendered at 1280x720 shows its floor and its walls' tops",
          "[framing][render]") {
  const fs::path dir = fs::path(BALLBOX_TEST_TMP) / "framing";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const testing::ProgramRun run =
      testing::RunShell("'" BALLBOX_EXE "' render --frames 1 --size 1280x720 --out wide", dir, dir / "captured");
  REQUIRE(run.exit_code == 0);
  int w = 0, h = 0, n = 0;
  stbi_uc* pixels = stbi_load((dir / "wide" / "frame_00000.png").c_str(), &w, &h, &n, 3);
  REQUIRE(pixels != nullptr);
  REQUIRE((w == 1280 && h == 720));
  // The floor's top is at world y = 0 and its bottom at -1; the camera shows y from -1.75 to
  // 14.75, so the floor spans rows 720 * (14.75 - 0) / 16.5 = 643.6 to 687.3. Row 665, at x = 0
  // (column 640), is the floor's own colour #4a4f58.
  const stbi_uc* floor = pixels + (665 * 1280 + 640) * 3;
  CHECK(floor[0] == 0x4a);
  CHECK(floor[1] == 0x4f);
  CHECK(floor[2] == 0x58);
  // Below the floor, the background (#f4f1ea) shows: nothing is cut off at the bottom.
  const stbi_uc* below = pixels + (710 * 1280 + 640) * 3;
  CHECK(below[0] == 0xf4);
  CHECK(below[1] == 0xf1);
  CHECK(below[2] == 0xea);
  stbi_image_free(pixels);
}
