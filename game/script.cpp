// Input script parsing and writing: `STEP EVENT X Y` per line, `#` comments, blank lines ignored,
// and one optional `size W H` line before any pixel click.
#include "game/script.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "game/limits.h"
#include "game/text_file.h"

namespace game {

namespace {

bool ParseWholeNumber(const std::string& s, std::int64_t* out) {
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, *out);
  return ec == std::errc() && ptr == end && *out >= 0;
}

bool ParseFiniteNumber(const std::string& s, double* out) {
  // from_chars takes no leading '+', which people write.
  const char* begin = s.data() + (s.size() > 1 && s[0] == '+' && s[1] != '-' ? 1 : 0);
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(begin, end, *out);
  return ec == std::errc() && ptr == end && std::isfinite(*out);
}

struct ImageSize {
  int width = 0;
  int height = 0;
};

// `size W H`: the image size the pixel clicks below it were made for.
Expected<ImageSize> ParseSizeLine(const std::vector<std::string>& tokens, const std::string& where,
                                  bool size_seen, bool pixel_click_seen) {
  if (size_seen) return BadInput(where + "a second size line (a script has at most one)");
  if (pixel_click_seen) {
    return BadInput(where + "the size line must come before the first pixel click");
  }
  if (tokens.size() != 3) {
    return BadInput(where + "expected \"size W H\" (the image size in pixels), got " +
                    std::to_string(tokens.size()) + " fields");
  }
  std::int64_t side[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    if (!ParseWholeNumber(tokens[1 + i], &side[i]) || side[i] < 1 || side[i] > kMaxImageSide) {
      return BadInput(where + (i == 0 ? "width" : "height") + " \"" + tokens[1 + i] +
                      "\" is not a whole number from 1 to " + std::to_string(kMaxImageSide));
    }
  }
  return ImageSize{static_cast<int>(side[0]), static_cast<int>(side[1])};
}

Expected<InputEvent> ParseEventLine(const std::vector<std::string>& tokens,
                                    const std::string& where) {
  if (tokens.size() != 4) {
    return BadInput(where + "expected \"STEP EVENT X Y\", got " + std::to_string(tokens.size()) +
                    (tokens.size() == 1 ? " field" : " fields"));
  }
  InputEvent event;
  if (!ParseWholeNumber(tokens[0], &event.step)) {
    return BadInput(where + "step \"" + tokens[0] + "\" is not a whole number >= 0");
  }
  if (tokens[1] == "click") {
    event.kind = EventKind::kClickPixel;
  } else if (tokens[1] == "click-world") {
    event.kind = EventKind::kClickWorld;
  } else {
    return BadInput(where + "unknown event \"" + tokens[1] +
                    "\" (expected \"click\" or \"click-world\")");
  }
  for (int axis = 0; axis < 2; ++axis) {
    double* coordinate = axis == 0 ? &event.at.x : &event.at.y;
    if (!ParseFiniteNumber(tokens[2 + axis], coordinate)) {
      return BadInput(where + (axis == 0 ? "x" : "y") + " \"" + tokens[2 + axis] +
                      "\" is not a finite number");
    }
  }
  return event;
}

std::vector<std::string> Fields(std::string line) {
  if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
  std::istringstream fields(line);
  std::vector<std::string> tokens;
  for (std::string token; fields >> token;) tokens.push_back(token);
  return tokens;
}

}  // namespace

Expected<std::vector<InputEvent>> ParseScript(std::string_view text, const std::string& file_label) {
  // A byte order mark would otherwise glue itself to the first step ("\ufeff5").
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.starts_with(kByteOrderMark)) text.remove_prefix(kByteOrderMark.size());
  std::vector<InputEvent> events;
  std::optional<ImageSize> size;
  bool pixel_click_seen = false;
  std::istringstream lines{std::string(text)};
  std::string line;
  int line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    const std::string where = file_label + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> tokens = Fields(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "size") {
      Expected<ImageSize> parsed = ParseSizeLine(tokens, where, size.has_value(), pixel_click_seen);
      if (!parsed.HasValue()) return parsed.Error();
      size = parsed.Value();
      continue;
    }
    Expected<InputEvent> parsed = ParseEventLine(tokens, where);
    if (!parsed.HasValue()) return parsed.Error();
    InputEvent& event = parsed.Value();
    if (!events.empty() && event.step < events.back().step) {
      return BadInput(where + "step " + std::to_string(event.step) +
                      " comes before the previous event's step " +
                      std::to_string(events.back().step) + " (steps must not decrease)");
    }
    if (event.kind == EventKind::kClickPixel) {
      pixel_click_seen = true;
      if (size) event.image_width = size->width, event.image_height = size->height;
    }
    events.push_back(event);
  }
  return events;
}

Expected<std::vector<InputEvent>> LoadScript(const std::string& path) {
  Expected<std::string> text = ReadTextFile(path);
  if (!text.HasValue()) return text.Error();
  return ParseScript(text.Value(), path);
}

std::string SizeLine(int image_width, int image_height) {
  return "size " + std::to_string(image_width) + " " + std::to_string(image_height) + "\n";
}

std::string FormatScript(const std::vector<InputEvent>& events) {
  std::string out;
  for (const InputEvent& e : events) {
    if (e.kind == EventKind::kClickPixel && e.image_width > 0) {
      out += SizeLine(e.image_width, e.image_height);
      break;
    }
  }
  out += "# step  event  x  y\n";
  char line[128];
  for (const InputEvent& e : events) {
    // %.17g prints every double so that parsing it back gives the same bits.
    std::snprintf(line, sizeof line, "%lld %s %.17g %.17g\n", static_cast<long long>(e.step),
                  e.kind == EventKind::kClickPixel ? "click" : "click-world", e.at.x, e.at.y);
    out += line;
  }
  return out;
}

}  // namespace game
