// Scene files (JSON, see docs/scene-format.md): parsed and validated into plain structs.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/world.h"
#include "game/status.h"
#include "render/camera.h"
#include "render/color.h"

namespace game {

struct SceneBody {
  std::string id;
  bool id_given = false;  ///< false: the id is the default body<index>
  engine::BodyDef def;
  render::Color color;
};

/// The scene's camera; what it leaves out comes from a fit of all bodies.
struct CameraDef {
  std::optional<engine::Vec2> center;
  std::optional<double> width;
};

struct Scene {
  std::string name;
  engine::WorldDef world;
  CameraDef camera;
  double click_max_impulse = 10.0;       ///< N·s at a ball's rim
  std::vector<SceneBody> bodies;
  std::vector<engine::SpringDef> springs;  ///< bodies named by index into `bodies`
};

/// Parses scene JSON. `file_label` names the source in messages; `default_name` is used when
/// the scene has no "name". Every failure is bad input, with a line:column or a key path.
Expected<Scene> ParseScene(std::string_view json, const std::string& file_label,
                           const std::string& default_name);

/// Reads and parses a scene file; its name defaults to the file's stem.
Expected<Scene> LoadScene(const std::string& path);

/// The engine world a scene describes, bodies in scene order (BodyId = index in `bodies`).
engine::World BuildWorld(const Scene& scene);

}  // namespace game
