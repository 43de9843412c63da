// Input script parsing and writing: `STEP EVENT X Y` per line (`STEP release` alone has no
// coordinates), `#` comments, blank lines ignored, and one optional `size W H` line before any
// pixel event.
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

// `size W H`: the image size the pixel events below it were made for. `first_pixel_event`:
// the name of the first pixel event above it, if any.
Expected<ImageSize> ParseSizeLine(const std::vector<std::string>& tokens, const std::string& where,
                                  bool size_seen, const char* first_pixel_event) {
  if (size_seen) return BadInput(where + "a second size line (a script has at most one)");
  if (first_pixel_event != nullptr) {
    return BadInput(where + "the size line must come before the first pixel " +
                    first_pixel_event);
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

// The events a line may name, as its second field.
struct EventSpelling {
  const char* name;
  EventKind kind;
};
constexpr EventSpelling kEventSpellings[] = {
    {"click", EventKind::kClickPixel}, {"click-world", EventKind::kClickWorld},
    {"grab", EventKind::kGrabPixel},   {"grab-world", EventKind::kGrabWorld},
    {"drag", EventKind::kDragPixel},   {"drag-world", EventKind::kDragWorld},
    {"release", EventKind::kRelease},
};

std::string FieldCount(std::size_t count) {
  return std::to_string(count) + (count == 1 ? " field" : " fields");
}

Expected<InputEvent> ParseEventLine(const std::vector<std::string>& tokens,
                                    const std::string& where) {
  // `release` alone has no coordinates; every other event is STEP EVENT X Y.
  if (tokens.size() >= 2 && tokens[1] == "release" && tokens.size() != 2) {
    return BadInput(where + "expected \"STEP release\" (no coordinates), got " +
                    FieldCount(tokens.size()));
  }
  if (tokens.size() != 4 && !(tokens.size() == 2 && tokens[1] == "release")) {
    return BadInput(where + "expected \"STEP EVENT X Y\", got " + FieldCount(tokens.size()));
  }
  InputEvent event;
  if (!ParseWholeNumber(tokens[0], &event.step)) {
    return BadInput(where + "step \"" + tokens[0] + "\" is not a whole number >= 0");
  }
  const EventSpelling* spelling = nullptr;
  for (const EventSpelling& candidate : kEventSpellings) {
    if (tokens[1] == candidate.name) spelling = &candidate;
  }
  if (spelling == nullptr) {
    return BadInput(where + "unknown event \"" + tokens[1] +
                    "\" (expected click, click-world, grab, grab-world, drag, drag-world or "
                    "release)");
  }
  event.kind = spelling->kind;
  if (event.kind == EventKind::kRelease) return event;
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
  const char* first_pixel_event = nullptr;
  std::istringstream lines{std::string(text)};
  std::string line;
  int line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    const std::string where = file_label + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> tokens = Fields(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "size") {
      Expected<ImageSize> parsed = ParseSizeLine(tokens, where, size.has_value(), first_pixel_event);
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
    if (IsPixelEvent(event.kind)) {
      if (first_pixel_event == nullptr) first_pixel_event = EventName(event.kind);
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

const char* EventName(EventKind kind) {
  for (const EventSpelling& spelling : kEventSpellings) {
    if (spelling.kind == kind) return spelling.name;
  }
  return "?";
}

EventKind WorldKind(EventKind kind) {
  switch (kind) {
    case EventKind::kClickPixel:
      return EventKind::kClickWorld;
    case EventKind::kGrabPixel:
      return EventKind::kGrabWorld;
    case EventKind::kDragPixel:
      return EventKind::kDragWorld;
    default:
      return kind;
  }
}

std::string SizeLine(int image_width, int image_height) {
  return "size " + std::to_string(image_width) + " " + std::to_string(image_height) + "\n";
}

std::string FormatScript(const std::vector<InputEvent>& events) {
  std::string out;
  for (const InputEvent& e : events) {
    if (IsPixelEvent(e.kind) && e.image_width > 0) {
      out += SizeLine(e.image_width, e.image_height);
      break;
    }
  }
  out += "# step  event  x  y\n";
  char line[128];
  for (const InputEvent& e : events) {
    if (e.kind == EventKind::kRelease) {
      std::snprintf(line, sizeof line, "%lld release\n", static_cast<long long>(e.step));
    } else {
      // %.17g prints every double so that parsing it back gives the same bits.
      std::snprintf(line, sizeof line, "%lld %s %.17g %.17g\n", static_cast<long long>(e.step),
                    EventName(e.kind), e.at.x, e.at.y);
    }
    out += line;
  }
  return out;
}

}  // namespace game
