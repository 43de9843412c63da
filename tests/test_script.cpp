// game::ParseScript / LoadScript / FormatScript: the input-script format, its errors and an exact round trip.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "game/script.h"

namespace {

std::string DataPath(const std::string& name) { return std::string(BALLBOX_TEST_DATA) + "/" + name; }

// Loads tests/data/`file`; requires bad input reading `path:LINE: rest`.
void RequireScriptError(const std::string& file, int line, const std::string& rest) {
  const std::string path = DataPath(file);
  const auto events = game::LoadScript(path);
  REQUIRE_FALSE(events.HasValue());
  CHECK(events.Error().exit_code == 2);
  CHECK(events.Error().message == path + ":" + std::to_string(line) + ": " + rest);
}

// Parses inline text labelled "s.txt"; requires bad input with exactly `message`.
void RequireParseError(const std::string& text, const std::string& message) {
  const auto events = game::ParseScript(text, "s.txt");
  REQUIRE_FALSE(events.HasValue());
  CHECK(events.Error().exit_code == 2);
  CHECK(events.Error().message == message);
}

std::uint64_t Bits(double d) {
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  return bits;
}

}  // namespace

TEST_CASE("script with comments, blank lines, both events and equal steps", "[script]") {
  const auto events = game::LoadScript(DataPath("script_good.txt"));
  REQUIRE(events.HasValue());
  const std::vector<game::InputEvent>& e = events.Value();
  REQUIRE(e.size() == 4);
  CHECK(e[0].step == 0);
  CHECK(e[0].kind == game::EventKind::kClickPixel);
  CHECK((e[0].at.x == 400.0 && e[0].at.y == 300.0));
  CHECK(e[1].step == 30);
  CHECK(e[1].kind == game::EventKind::kClickWorld);
  CHECK((e[1].at.x == 1.5 && e[1].at.y == -2.25));
  CHECK(e[2].step == 30);  // equal steps are allowed
  CHECK((e[2].at.x == -0.125 && e[2].at.y == 0.001));
  CHECK(e[3].step == 45);  // tabs separate fields; "#" ends the line even without a space
  CHECK(e[3].kind == game::EventKind::kClickPixel);
  CHECK((e[3].at.x == 12.5 && e[3].at.y == 0.75));
}

TEST_CASE("script that is empty or only comments has no events", "[script]") {
  for (const char* text : {"", "\n\n", "# nothing\n   # still nothing\n", "   \t  "}) {
    const auto events = game::ParseScript(text, "s.txt");
    REQUIRE(events.HasValue());
    CHECK(events.Value().empty());
  }
}

TEST_CASE("script with CRLF line ends and no final newline", "[script]") {
  const auto events = game::ParseScript("# header\r\n3 click-world 1 2\r\n4 click 5 6", "s.txt");
  REQUIRE(events.HasValue());
  REQUIRE(events.Value().size() == 2);
  CHECK(events.Value()[0].at.y == 2.0);
  CHECK(events.Value()[1].step == 4);
  CHECK(events.Value()[1].at.y == 6.0);
}

TEST_CASE("script error: wrong field count names file and line", "[script]") {
  RequireScriptError("script_field_count.txt", 3, "expected \"STEP EVENT X Y\", got 3 fields");
}

TEST_CASE("script error: one field and five fields", "[script]") {
  RequireParseError("\n30\n", "s.txt:2: expected \"STEP EVENT X Y\", got 1 field");
  RequireParseError("30 click 1 2 3\n", "s.txt:1: expected \"STEP EVENT X Y\", got 5 fields");
}

TEST_CASE("script error: step that is not a whole number", "[script]") {
  RequireScriptError("script_bad_step.txt", 2, "step \"1.5\" is not a whole number >= 0");
}

TEST_CASE("script error: negative step", "[script]") {
  RequireScriptError("script_negative_step.txt", 3, "step \"-3\" is not a whole number >= 0");
}

TEST_CASE("script error: step with letters or out of range", "[script]") {
  RequireParseError("3a click 1 2", "s.txt:1: step \"3a\" is not a whole number >= 0");
  RequireParseError("99999999999999999999 click 1 2",
                    "s.txt:1: step \"99999999999999999999\" is not a whole number >= 0");
}

TEST_CASE("script error: unknown event", "[script]") {
  RequireScriptError("script_unknown_event.txt", 2,
                     "unknown event \"tap\" (expected click, click-world, grab, grab-world, drag, "
                     "drag-world or release)");
}

TEST_CASE("script error: non-finite x", "[script]") {
  RequireScriptError("script_non_finite.txt", 3, "x \"nan\" is not a finite number");
}

TEST_CASE("script error: non-finite or malformed y", "[script]") {
  RequireParseError("1 click 2 inf", "s.txt:1: y \"inf\" is not a finite number");
  RequireParseError("1 click 2 1e999", "s.txt:1: y \"1e999\" is not a finite number");
  RequireParseError("1 click 2 3px", "s.txt:1: y \"3px\" is not a finite number");
}

TEST_CASE("script error: decreasing steps", "[script]") {
  RequireScriptError("script_decreasing.txt", 4,
                     "step 5 comes before the previous event's step 10 (steps must not decrease)");
}

TEST_CASE("script error: a missing file", "[script]") {
  const std::string path = DataPath("script_does_not_exist.txt");
  const auto events = game::LoadScript(path);
  REQUIRE_FALSE(events.HasValue());
  CHECK(events.Error().exit_code == 2);
  CHECK(events.Error().message == path + ": cannot open: No such file or directory");
}

TEST_CASE("FormatScript then ParseScript gives back bit-identical events", "[script]") {
  const double values[] = {0.1,
                           1e-300,
                           123456.789,
                           -0.0,
                           1.0 / 3.0,
                           std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::denorm_min(),
                           -2.5e-7};
  std::vector<game::InputEvent> events;
  std::int64_t step = 0;
  for (double v : values) {
    events.push_back({step, game::EventKind::kClickWorld, {v, -v}});
    events.push_back({step, game::EventKind::kClickPixel, {0.7 * v, v}});
    step += 17;
  }
  events.push_back({std::int64_t{1} << 40, game::EventKind::kClickPixel, {1.0, 2.0}});

  const auto parsed = game::ParseScript(game::FormatScript(events), "round-trip");
  REQUIRE(parsed.HasValue());
  REQUIRE(parsed.Value().size() == events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    INFO("event " << i << " x " << events[i].at.x);
    CHECK(parsed.Value()[i].step == events[i].step);
    CHECK(parsed.Value()[i].kind == events[i].kind);
    CHECK(Bits(parsed.Value()[i].at.x) == Bits(events[i].at.x));
    CHECK(Bits(parsed.Value()[i].at.y) == Bits(events[i].at.y));
  }
}

TEST_CASE("script: a UTF-8 byte order mark at the start is skipped", "[script]") {
  // Notepad and other editors write EF BB BF first; it must not glue itself to the first step.
  const auto events = game::ParseScript("\xEF\xBB\xBF" "5 click-world 1 2\n", "bom.txt");
  REQUIRE(events.HasValue());
  REQUIRE(events.Value().size() == 1);
  CHECK(events.Value()[0].step == 5);
  // Elsewhere it is no whitespace: a byte order mark in the middle of a line stays an error.
  RequireParseError("1 click-world 1 2\n\xEF\xBB\xBF" "5 click-world 1 2\n",
                    "s.txt:2: step \"\xEF\xBB\xBF" "5\" is not a whole number >= 0");
}

TEST_CASE("script: a size line gives the pixel clicks below it their image size", "[script]") {
  const auto events = game::ParseScript(
      "# made at 1280x720\n5 click-world 1 2\nsize 1280 720   # the size\n6 click 10 20\n7 click 3 4\n",
      "s.txt");
  REQUIRE(events.HasValue());
  REQUIRE(events.Value().size() == 3);
  CHECK(events.Value()[0].image_width == 0);  // world clicks need no size
  for (int i : {1, 2}) {
    CHECK(events.Value()[i].image_width == 1280);
    CHECK(events.Value()[i].image_height == 720);
  }
  // Without one, pixel clicks map at the size being rendered.
  const auto plain = game::ParseScript("6 click 10 20\n", "s.txt");
  REQUIRE(plain.HasValue());
  CHECK(plain.Value()[0].image_width == 0);
  CHECK(plain.Value()[0].image_height == 0);
}

TEST_CASE("script error: a size line after a pixel click, a second one, or a bad size", "[script]") {
  RequireParseError("6 click 10 20\nsize 800 600\n",
                    "s.txt:2: the size line must come before the first pixel click");
  RequireParseError("size 800 600\nsize 400 300\n", "s.txt:2: a second size line (a script has at most one)");
  RequireParseError("size 800\n", "s.txt:1: expected \"size W H\" (the image size in pixels), got 2 fields");
  RequireParseError("size 800 0\n", "s.txt:1: height \"0\" is not a whole number from 1 to 16384");
  RequireParseError("size 16385 600\n", "s.txt:1: width \"16385\" is not a whole number from 1 to 16384");
  RequireParseError("size 8.5 600\n", "s.txt:1: width \"8.5\" is not a whole number from 1 to 16384");
}

TEST_CASE("FormatScript writes the size line, and the round trip keeps it", "[script]") {
  std::vector<game::InputEvent> events = {{3, game::EventKind::kClickWorld, {1, 2}},
                                          {4, game::EventKind::kClickPixel, {10, 20}, 640, 480}};
  const std::string text = game::FormatScript(events);
  CHECK(text.rfind("size 640 480\n", 0) == 0);
  const auto parsed = game::ParseScript(text, "round-trip");
  REQUIRE(parsed.HasValue());
  REQUIRE(parsed.Value().size() == 2);
  CHECK(parsed.Value()[1].image_width == 640);
  CHECK(parsed.Value()[1].image_height == 480);
  CHECK(game::SizeLine(800, 600) == "size 800 600\n");
}

TEST_CASE("script: grab, drag and release events, pixel and world, and the size line over them",
          "[script][drag]") {
  const auto events = game::LoadScript(DataPath("script_drag_good.txt"));
  REQUIRE(events.HasValue());
  const std::vector<game::InputEvent>& e = events.Value();
  REQUIRE(e.size() == 7);
  using game::EventKind;
  const EventKind kinds[] = {EventKind::kGrabPixel, EventKind::kDragPixel,  EventKind::kDragPixel,
                             EventKind::kRelease,   EventKind::kGrabWorld,  EventKind::kDragWorld,
                             EventKind::kRelease};
  const std::int64_t steps[] = {10, 10, 12, 40, 40, 41, 90};
  for (std::size_t i = 0; i < e.size(); ++i) {
    INFO("event " << i);
    CHECK(e[i].kind == kinds[i]);
    CHECK(e[i].step == steps[i]);
    // The size line maps pixel grabs and drags as it maps pixel clicks; world events need none.
    CHECK(e[i].image_width == (game::IsPixelEvent(kinds[i]) ? 640 : 0));
    CHECK(e[i].image_height == (game::IsPixelEvent(kinds[i]) ? 480 : 0));
  }
  CHECK((e[0].at.x == 320.0 && e[0].at.y == 400.5));
  CHECK((e[2].at.x == 330.25 && e[2].at.y == -12.0));  // a drag may leave the picture
  CHECK((e[3].at.x == 0.0 && e[3].at.y == 0.0));       // a release has no point
  CHECK((e[5].at.x == -1.5 && e[5].at.y == 2.0));
}

TEST_CASE("script error: malformed grab, drag and release lines name file and line",
          "[script][drag]") {
  RequireScriptError("script_drag_bad.txt", 4,
                     "expected \"STEP release\" (no coordinates), got 4 fields");
  RequireParseError("5 release 1\n", "s.txt:1: expected \"STEP release\" (no coordinates), got 3 fields");
  RequireParseError("5 grab 1\n", "s.txt:1: expected \"STEP EVENT X Y\", got 3 fields");
  RequireParseError("5 drag-world 1 2 3\n", "s.txt:1: expected \"STEP EVENT X Y\", got 5 fields");
  RequireParseError("5 drag-world nan 2\n", "s.txt:1: x \"nan\" is not a finite number");
  RequireParseError("5 grab-world 1 inf\n", "s.txt:1: y \"inf\" is not a finite number");
  RequireParseError("x release\n", "s.txt:1: step \"x\" is not a whole number >= 0");
  RequireParseError("5 drop 1 2\n",
                    "s.txt:1: unknown event \"drop\" (expected click, click-world, grab, "
                    "grab-world, drag, drag-world or release)");
  RequireParseError("9 release\n8 grab-world 0 0\n",
                    "s.txt:2: step 8 comes before the previous event's step 9 (steps must not decrease)");
  // The size line comes before every pixel event, and says which came first.
  RequireParseError("5 grab 1 2\nsize 800 600\n",
                    "s.txt:2: the size line must come before the first pixel grab");
  RequireParseError("5 grab-world 1 2\n6 drag 3 4\nsize 800 600\n",
                    "s.txt:3: the size line must come before the first pixel drag");
}

TEST_CASE("FormatScript then ParseScript keeps grab, drag and release events bit for bit",
          "[script][drag]") {
  using game::EventKind;
  const std::vector<game::InputEvent> events = {
      {0, EventKind::kGrabWorld, {1.0 / 3.0, -2.5e-7}},
      {0, EventKind::kDragWorld, {0.1, 1e-300}},
      {7, EventKind::kClickWorld, {2.0, 3.0}},
      {7, EventKind::kRelease, {}},
      {9, EventKind::kGrabPixel, {10.5, 20.25}, 640, 480},
      {12, EventKind::kDragPixel, {-3.0, 700.0}, 640, 480},
      {12, EventKind::kRelease, {}},
  };
  const std::string text = game::FormatScript(events);
  CHECK_THAT(text, Catch::StartsWith("size 640 480\n"));
  CHECK_THAT(text, Catch::Contains("\n7 release\n"));
  CHECK_THAT(text, Catch::Contains("\n0 grab-world 0.33333333333333331 -2.4999999999999999e-07\n"));
  const auto parsed = game::ParseScript(text, "round-trip");
  REQUIRE(parsed.HasValue());
  REQUIRE(parsed.Value().size() == events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    INFO("event " << i);
    CHECK(parsed.Value()[i].step == events[i].step);
    CHECK(parsed.Value()[i].kind == events[i].kind);
    CHECK(Bits(parsed.Value()[i].at.x) == Bits(events[i].at.x));
    CHECK(Bits(parsed.Value()[i].at.y) == Bits(events[i].at.y));
    CHECK(parsed.Value()[i].image_width == events[i].image_width);
  }
}
