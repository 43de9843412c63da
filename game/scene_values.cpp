// The scene reader's checked reads of single JSON values (scene_values.h).
#include "game/scene_values.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "game/limits.h"

namespace game::scene_values {

namespace {

// Edit distance, to suggest the key a typo meant.
std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// The channels of "#" and 3, 4, 6 or 8 hex digits (one or two a channel), if `text` is one of
// the `allowed` lengths; each channel 0..255.
bool HexChannels(const std::string& text, std::initializer_list<std::size_t> allowed, std::uint8_t out[4]) {
  bool length_ok = false;
  for (const std::size_t n : allowed) length_ok = length_ok || text.size() == n + 1;
  if (!length_ok || text[0] != '#') return false;
  for (std::size_t i = 1; i < text.size(); ++i) {
    if (HexDigit(text[i]) < 0) return false;
  }
  const bool short_form = text.size() <= 5;
  const std::size_t channels = short_form ? text.size() - 1 : (text.size() - 1) / 2;
  out[3] = 255;
  for (std::size_t i = 0; i < channels; ++i) {
    out[i] = short_form ? static_cast<std::uint8_t>(HexDigit(text[1 + i]) * 17)
                        : static_cast<std::uint8_t>(HexDigit(text[1 + 2 * i]) * 16 + HexDigit(text[2 + 2 * i]));
  }
  return true;
}

}  // namespace

render::Color ReadColor(const Json& value, const std::string& path) {
  const std::string text = ReadString(value, path);
  std::uint8_t c[4];
  if (!HexChannels(text, {3, 6}, c)) {
    throw SceneError{path, "must be a colour \"#rgb\" or \"#rrggbb\", got " + Quote(text)};
  }
  return {c[0], c[1], c[2]};
}

engine::Rgba ReadRgba(const Json& value, const std::string& path) {
  const std::string text = ReadString(value, path);
  std::uint8_t c[4];
  if (!HexChannels(text, {3, 4, 6, 8}, c)) {
    throw SceneError{path, "must be a colour \"#rgb\", \"#rgba\", \"#rrggbb\" or \"#rrggbbaa\", got " + Quote(text)};
  }
  const auto unit = [](std::uint8_t v) { return static_cast<float>(v) / 255.0f; };
  return {unit(c[0]), unit(c[1]), unit(c[2]), unit(c[3])};
}

double ReadWhole(const Json& value, const std::string& path, double least, double most) {
  const double v = ReadNumber(value, path);
  if (v != std::floor(v) || v < least || v > most) {
    char range[96];
    std::snprintf(range, sizeof range, "must be a whole number from %.17g to %.17g", least, most);
    throw SceneError{path, range};
  }
  return v;
}

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string Quote(const std::string& text) {
  return Json(text).dump(-1, ' ', false, Json::error_handler_t::replace);
}

void RejectUnknownKeys(const Json& object, const std::string& path,
                       std::initializer_list<const char*> known) {
  for (const auto& item : object.items()) {
    bool is_known = false;
    for (const char* k : known) is_known = is_known || item.key() == k;
    if (is_known) continue;
    // Distances only for a key that is wrong: a million-body scene has ten million right ones.
    std::string suggestion;
    std::size_t best = 3;  // suggest only close matches
    for (const char* k : known) {
      const std::size_t distance = EditDistance(item.key(), k);
      if (distance < best) best = distance, suggestion = k;
    }
    std::string message = "unknown key " + Quote(item.key());
    if (!suggestion.empty()) message += " (did you mean \"" + suggestion + "\"?)";
    throw SceneError{path, message};
  }
}

const Json* Find(const Json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

double ReadNumber(const Json& value, const std::string& path) {
  if (!value.is_number()) throw SceneError{path, "must be a number"};
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw SceneError{path, "must be finite"};
  if (std::abs(v) > kMaxSceneMagnitude) {
    throw SceneError{path, "must be between -1e9 and 1e9 (docs/limits.md)"};
  }
  return v;
}

std::string TooSmall() { return "must be at least 1e-09 m (docs/limits.md)"; }

double ReadPositive(const Json& value, const std::string& path) {
  const double v = ReadNumber(value, path);
  if (!(v > 0.0)) throw SceneError{path, "must be > 0"};
  return v;
}

double ReadNonNegative(const Json& value, const std::string& path) {
  const double v = ReadNumber(value, path);
  if (v < 0.0) throw SceneError{path, "must be >= 0"};
  return v;
}

engine::Vec2 ReadVec2(const Json& value, const std::string& path) {
  if (!value.is_array() || value.size() != 2) throw SceneError{path, "must be an array of 2 numbers"};
  return {ReadNumber(value[0], path + "[0]"), ReadNumber(value[1], path + "[1]")};
}

bool ReadBool(const Json& value, const std::string& path) {
  if (!value.is_boolean()) throw SceneError{path, "must be true or false"};
  return value.get<bool>();
}

std::string ReadString(const Json& value, const std::string& path) {
  if (!value.is_string()) throw SceneError{path, "must be a string"};
  return value.get<std::string>();
}

}  // namespace game::scene_values
