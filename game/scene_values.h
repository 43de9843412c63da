// The scene reader's checked reads of single JSON values (numbers, vectors, choices, ...), shared
// by scene.cpp and scene_shapes.cpp. Each failure is a SceneError naming the key path.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "engine/math.h"
#include "engine/particles.h"
#include "render/color.h"

namespace game::scene_values {

using Json = nlohmann::json;

/// Thrown inside the reader and turned into a Failure at its top: validation reads straight down.
struct SceneError {
  std::string path;
  std::string message;
};

/// "bodies[2]" + "radius" -> "bodies[2].radius"; the root's keys stand alone.
std::string Join(const std::string& path, const std::string& key);

/// Text from the file, quoted and escaped as JSON, so a message stays on one line.
std::string Quote(const std::string& text);

/// Throws for the first key of `object` not in `known`, suggesting a close one.
void RejectUnknownKeys(const Json& object, const std::string& path, std::initializer_list<const char*> known);

const Json* Find(const Json& object, const char* key);

/// A finite number within ±kMaxSceneMagnitude.
double ReadNumber(const Json& value, const std::string& path);
double ReadPositive(const Json& value, const std::string& path);
double ReadNonNegative(const Json& value, const std::string& path);
engine::Vec2 ReadVec2(const Json& value, const std::string& path);
bool ReadBool(const Json& value, const std::string& path);
std::string ReadString(const Json& value, const std::string& path);

/// "#rgb" or "#rrggbb" (a body's, a soft body's or a fluid's colour).
render::Color ReadColor(const Json& value, const std::string& path);
/// "#rgb", "#rgba", "#rrggbb" or "#rrggbbaa": an effect colour with straight alpha (opaque when
/// the alpha digits are left out).
engine::Rgba ReadRgba(const Json& value, const std::string& path);

/// A whole number from `least` to `most`, e.g. a count or a seed.
double ReadWhole(const Json& value, const std::string& path, double least, double most);

/// The message for a length under kMinBodySize.
std::string TooSmall();

template <class Enum>
Enum ReadChoice(const Json& value, const std::string& path,
                std::initializer_list<std::pair<const char*, Enum>> choices) {
  const std::string name = ReadString(value, path);
  std::string expected;
  for (const auto& [label, choice] : choices) {
    if (name == label) return choice;
    expected += (expected.empty() ? "\"" : ", \"") + std::string(label) + "\"";
  }
  throw SceneError{path, "unknown value " + Quote(name) + " (expected one of " + expected + ")"};
}

}  // namespace game::scene_values
