// Input script parsing and writing: `STEP EVENT X Y` per line, `#` comments, blank lines ignored.
#include "game/script.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

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

}  // namespace

Expected<std::vector<InputEvent>> ParseScript(std::string_view text, const std::string& file_label) {
  std::vector<InputEvent> events;
  std::istringstream lines{std::string(text)};
  std::string line;
  int line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    const std::string where = file_label + ":" + std::to_string(line_number) + ": ";
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) continue;
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
    if (!events.empty() && event.step < events.back().step) {
      return BadInput(where + "step " + std::to_string(event.step) +
                      " comes before the previous event's step " +
                      std::to_string(events.back().step) + " (steps must not decrease)");
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

std::string FormatScript(const std::vector<InputEvent>& events) {
  std::string out = "# step  event  x  y\n";
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
