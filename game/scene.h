// Scene files (JSON, see docs/scene-format.md): parsed and validated into plain structs.
#pragma once

#include <cstddef>
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

/// A joint of the scene's `joints` list (docs/scene-format.md#joints).
struct SceneJoint {
  /// Names the joint for programs that drive it (FindJoint, then World::SetMotorSpeed); unique
  /// among the scene's joints (body ids are another list: a joint may share a body's id).
  std::string id;
  bool id_given = false;  ///< false: the id is the default joint<index>
  engine::JointDef def;   ///< bodies as BodyId{index into Scene::bodies}
};

/// A soft body of the scene's `soft_bodies` list (docs/scene-format.md#soft-bodies).
struct SceneSoftBody {
  std::string id;         ///< unique among the soft bodies; names its particles in the dump
  bool id_given = false;  ///< false: the id is the default soft<index>
  engine::SoftBodyDef def;  ///< attach_to as BodyId{index into Scene::bodies}
  render::Color color;      ///< its fill; render::kSoftBodyColor when the scene gives none
};

/// A block of the scene's `fluids` list (docs/scene-format.md#fluids).
struct SceneFluid {
  std::string id;         ///< unique among the fluids; names its particles in the dump
  bool id_given = false;  ///< false: the id is the default fluid<index>
  engine::FluidDef def;
  /// The liquid's colour, the same in every block (the renderer draws one liquid): the first
  /// block's, else render::kFluidColor.
  render::Color color;
  std::size_t particles = 0;  ///< how many the engine makes of it (FluidParticleCount)
};

/// An emitter of the scene's `emitters` list (docs/scene-format.md#emitters); its colours are
/// in the def (color_start, color_end).
struct SceneEmitter {
  std::string id;         ///< unique among the emitters; names its particles in the dump
  bool id_given = false;  ///< false: the id is the default emitter<index>
  engine::EmitterDef def;   ///< body as BodyId{index into Scene::bodies}
};

/// How a click pushes soft-body and fluid particles when it hits no ball (docs/click-rule.md).
struct ParticleClick {
  double radius = 1.0;  ///< m: particles farther than this from the click are not pushed
  double speed = 5.0;   ///< m/s: the largest velocity change, at half the radius
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
  std::vector<SceneJoint> joints;          ///< in file order, made after every body
  ParticleClick particle_click;
  /// Made after the joints, each list in file order: SoftBodyId{i} is soft_bodies[i],
  /// EmitterId{i} is emitters[i], and the fluid's particles come block by block.
  std::vector<SceneSoftBody> soft_bodies;
  std::vector<SceneFluid> fluids;
  std::vector<SceneEmitter> emitters;

  /// Whether the scene has soft bodies, fluid or emitters (its dump then has a particle file).
  bool HasParticles() const { return !soft_bodies.empty() || !fluids.empty() || !emitters.empty(); }
};

/// Parses scene JSON. `file_label` names the source in messages; `default_name` is used when
/// the scene has no "name". Every failure is bad input, with a line:column or a key path.
Expected<Scene> ParseScene(std::string_view json, const std::string& file_label,
                           const std::string& default_name);

/// Reads and parses a scene file; its name defaults to the file's stem.
Expected<Scene> LoadScene(const std::string& path);

/// The engine world a scene describes, bodies in scene order (BodyId = index in `bodies`), then
/// its joints in file order (JointId = index in `joints`), then its soft bodies, fluids and
/// emitters, each in file order.
engine::World BuildWorld(const Scene& scene);

/// The index in `scene.joints` of the joint with this id, which is also its JointId's index in
/// the world BuildWorld makes; none if no joint has it.
std::optional<std::size_t> FindJoint(const Scene& scene, std::string_view id);

}  // namespace game
