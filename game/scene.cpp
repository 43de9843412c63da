// Scene loading: JSON text -> checked Scene. Every value is validated here, at the edge, and
// each failure names the file and the key path (`bodies[2].radius: must be > 0`).
#include "game/scene.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "game/limits.h"
#include "game/scene_joints.h"
#include "game/scene_json.h"
#include "game/scene_particles.h"
#include "game/scene_shapes.h"
#include "game/scene_values.h"
#include "game/text_file.h"

namespace game {

namespace {

using namespace scene_values;  // NOLINT: the reader is made of these

void ReadSolver(const Json& solver, const std::string& path, engine::WorldDef* world) {
  if (!solver.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(solver, path,
                    {"method", "substeps", "push_out_speed",
                     "iterations", "restitution_threshold", "slop", "position_correction"});
  auto read_count = [&](const char* key, int* out) {
    if (const Json* v = Find(solver, key)) {
      const double n = ReadPositive(*v, Join(path, key));
      if (n != std::floor(n) || n > 1000) throw SceneError{Join(path, key), "must be a whole number from 1 to 1000"};
      *out = static_cast<int>(n);
    }
  };
  if (const Json* v = Find(solver, "method")) {
    world->solver = ReadChoice<engine::ContactSolver>(
        *v, Join(path, "method"),
        {{"substep", engine::ContactSolver::kSubstep},
         {"sequential_impulse", engine::ContactSolver::kSequentialImpulse},
         {"seed", engine::ContactSolver::kSequentialImpulse}});
  }
  read_count("substeps", &world->substeps);
  read_count("iterations", &world->velocity_iterations);
  if (const Json* v = Find(solver, "push_out_speed")) {
    world->max_push_out_speed = ReadPositive(*v, Join(path, "push_out_speed"));
  }
  if (const Json* v = Find(solver, "restitution_threshold")) {
    world->restitution_threshold = ReadNonNegative(*v, Join(path, "restitution_threshold"));
  }
  if (const Json* v = Find(solver, "slop")) world->linear_slop = ReadNonNegative(*v, Join(path, "slop"));
  if (const Json* v = Find(solver, "position_correction")) {
    const double c = ReadNonNegative(*v, Join(path, "position_correction"));
    if (c > 1.0) throw SceneError{Join(path, "position_correction"), "must be from 0 to 1"};
    world->position_correction = c;
  }
}

SceneBody ReadBody(const Json& body, const std::string& path, std::size_t index, bool rotation) {
  if (!body.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(body, path,
                    {"id", "shape", "shapes", "radius", "size", "vertices", "length", "points", "loop",
                     "offset", "position", "velocity", "angle",
                     "angular_velocity", "mass", "density", "static", "kinematic", "restitution", "friction",
                     "fixed_rotation", "bullet", "color", "linear_damping", "angular_damping",
                     "drag_coefficient"});
  SceneBody out;
  engine::BodyDef& def = out.def;
  auto key = [&](const char* k) { return Join(path, k); };

  out.id = "body" + std::to_string(index);
  out.id_given = Find(body, "id") != nullptr;
  if (const Json* v = Find(body, "id")) {
    out.id = ReadString(*v, key("id"));
    if (out.id.empty()) throw SceneError{key("id"), "must not be empty"};
  }

  // Read first: what a body may be made of depends on them (segments are static only).
  if (const Json* v = Find(body, "static")) def.is_static = ReadBool(*v, key("static"));
  if (const Json* v = Find(body, "kinematic")) def.is_kinematic = ReadBool(*v, key("kinematic"));
  ReadBodyShape(body, path, &def);

  const Json* position = Find(body, "position");
  if (!position) throw SceneError{path, "needs a \"position\" [x, y]"};
  def.position = ReadVec2(*position, key("position"));

  if (def.is_static && def.is_kinematic) {
    throw SceneError{key("kinematic"), "a body cannot be both static and kinematic"};
  }
  for (const char* moving_key : {"mass", "density", "velocity", "angular_velocity"}) {
    if (def.is_static && Find(body, moving_key)) {
      throw SceneError{key(moving_key), "a static body takes no mass, density or velocity"};
    }
  }
  // A kinematic body moves at the velocity it is given and nothing pushes it: a mass would
  // never be used.
  for (const char* mass_key : {"mass", "density"}) {
    if (def.is_kinematic && Find(body, mass_key)) {
      throw SceneError{key(mass_key), "a kinematic body takes no mass or density (nothing pushes it)"};
    }
  }
  for (const char* angular_key : {"angle", "angular_velocity"}) {
    if (!rotation && Find(body, angular_key)) {
      throw SceneError{key(angular_key), "needs \"rotation\": true in the scene"};
    }
  }
  if (const Json* v = Find(body, "velocity")) def.velocity = ReadVec2(*v, key("velocity"));
  if (const Json* v = Find(body, "angle")) def.angle = ReadNumber(*v, key("angle"));
  if (const Json* v = Find(body, "angular_velocity")) {
    def.angular_velocity = ReadNumber(*v, key("angular_velocity"));
  }
  const Json* mass = Find(body, "mass");
  const Json* density = Find(body, "density");
  if (mass && density) throw SceneError{path, "give \"mass\" or \"density\", not both"};
  if (mass) def.mass = ReadPositive(*mass, key("mass"));
  if (density) def.density = ReadPositive(*density, key("density"));
  if (!def.is_static && !def.is_kinematic) {
    // The engine divides by the mass: one that underflows would make its inverse infinite.
    const double body_mass = mass ? def.mass : MassFromDensity(def);
    if (!(body_mass >= kMinBodyMass)) {
      throw SceneError{mass ? key("mass") : path,
                       std::string(mass ? "" : "its mass, density * area, ") +
                           "must be at least 1e-12 kg (docs/limits.md)"};
    }
  }

  if (const Json* v = Find(body, "restitution")) def.restitution = ReadNonNegative(*v, key("restitution"));
  if (const Json* v = Find(body, "friction")) def.friction = ReadNonNegative(*v, key("friction"));
  if (const Json* v = Find(body, "fixed_rotation")) def.fixed_rotation = ReadBool(*v, key("fixed_rotation"));
  if (const Json* v = Find(body, "bullet")) def.bullet = ReadBool(*v, key("bullet"));
  if (const Json* v = Find(body, "linear_damping")) def.linear_damping = ReadNonNegative(*v, key("linear_damping"));
  if (const Json* v = Find(body, "angular_damping")) def.angular_damping = ReadNonNegative(*v, key("angular_damping"));
  if (const Json* v = Find(body, "drag_coefficient")) def.drag_coefficient = ReadNonNegative(*v, key("drag_coefficient"));

  // Bodies nothing can push (static or kinematic) are slate grey; the others take the palette.
  out.color = def.is_static || def.is_kinematic ? render::kStaticColor : render::PaletteColor(index);
  if (const Json* v = Find(body, "color")) out.color = ReadColor(*v, key("color"));
  return out;
}

// A spring between two bodies named by id, or from one body to a fixed world point.
engine::SpringDef ReadSpring(const Json& spring, const std::string& path,
                             const std::map<std::string, std::size_t>& ids,
                             const std::vector<SceneBody>& bodies) {
  if (!spring.is_object()) throw SceneError{path, "must be an object"};
  RejectUnknownKeys(spring, path, {"a", "b", "anchor_a", "anchor_b", "rest_length", "stiffness", "damping"});
  auto key = [&](const char* k) { return Join(path, k); };
  auto body_index = [&](const char* k) {
    const std::string id = ReadString(spring.at(k), key(k));
    const auto it = ids.find(id);
    if (it == ids.end()) throw SceneError{key(k), "no body has the id " + Quote(id)};
    if (bodies[it->second].def.is_static) {
      throw SceneError{key(k), "body " + Quote(id) + " is static: anchor the spring with \"anchor_b\" instead"};
    }
    return engine::BodyId{static_cast<engine::BodyIndex>(it->second)};  // bodies take slots in scene order
  };
  engine::SpringDef def;
  if (!Find(spring, "a")) throw SceneError{path, "needs \"a\", the id of the body it pulls"};
  def.body_a = body_index("a");
  if (const Json* v = Find(spring, "anchor_a")) def.local_a = ReadVec2(*v, key("anchor_a"));
  if (Find(spring, "b")) {
    def.body_b = body_index("b");
    if (const Json* v = Find(spring, "anchor_b")) def.local_b = ReadVec2(*v, key("anchor_b"));
  } else {
    const Json* anchor = Find(spring, "anchor_b");
    if (!anchor) throw SceneError{path, "needs \"b\" (a body id) or \"anchor_b\" (a fixed world point)"};
    def.local_b = ReadVec2(*anchor, key("anchor_b"));
  }
  const Json* stiffness = Find(spring, "stiffness");
  if (!stiffness) throw SceneError{path, "needs \"stiffness\" (N/m)"};
  def.stiffness = ReadNonNegative(*stiffness, key("stiffness"));
  if (const Json* v = Find(spring, "damping")) def.damping = ReadNonNegative(*v, key("damping"));
  // The rest length defaults to the distance between the attachment points as placed.
  auto world_point = [&](engine::BodyId id, engine::Vec2 local) {
    const engine::BodyDef& b = bodies[id.index].def;
    return b.position + engine::Rotate(engine::MakeRot(b.angle), local);
  };
  const engine::Vec2 pa = world_point(def.body_a, def.local_a);
  const engine::Vec2 pb = def.body_b ? world_point(*def.body_b, def.local_b) : def.local_b;
  def.rest_length = engine::Length(pb - pa);
  if (const Json* v = Find(spring, "rest_length")) def.rest_length = ReadNonNegative(*v, key("rest_length"));
  return def;
}

// The soft bodies, fluids and emitters, after the bodies they may name.
void ReadParticleLists(const Json& root, const std::map<std::string, std::size_t>& body_ids, Scene* scene) {
  std::size_t particles = 0;  // soft-body and fluid particles, against kMaxParticles
  if (const Json* v = Find(root, "soft_bodies")) scene->soft_bodies = ReadSoftBodies(*v, body_ids, &particles);
  if (const Json* v = Find(root, "fluids")) scene->fluids = ReadFluids(*v, &particles);
  if (const Json* v = Find(root, "emitters")) scene->emitters = ReadEmitters(*v, body_ids);
  CheckParticleSubsteps(root, *scene);
}

Scene ReadScene(const Json& root, const std::string& default_name) {
  if (!root.is_object()) throw SceneError{"", "a scene must be a JSON object"};
  RejectUnknownKeys(root, "",
                    {"name", "gravity", "dt", "rotation", "camera", "click", "bodies", "integrator",
                     "broad_phase", "solver", "sleep", "springs", "fluid_density",
                     "gravitational_constant", "continuous", "joints", "particles", "soft_bodies", "fluids",
                     "emitters"});
  Scene scene;
  scene.name = default_name;
  if (const Json* v = Find(root, "name")) {
    scene.name = ReadString(*v, "name");
    if (scene.name.empty()) throw SceneError{"name", "must not be empty"};
  }
  engine::WorldDef& world = scene.world;
  if (const Json* v = Find(root, "gravity")) world.gravity = ReadVec2(*v, "gravity");
  if (const Json* v = Find(root, "dt")) world.dt = ReadPositive(*v, "dt");
  if (const Json* v = Find(root, "rotation")) world.rotation = ReadBool(*v, "rotation");
  if (const Json* v = Find(root, "integrator")) {
    world.integrator = ReadChoice<engine::Integrator>(
        *v, "integrator",
        {{"semi_implicit_euler", engine::Integrator::kSemiImplicitEuler},
         {"explicit_euler", engine::Integrator::kExplicitEuler},
         {"velocity_verlet", engine::Integrator::kVelocityVerlet},
         {"midpoint", engine::Integrator::kMidpoint},
         {"rk4", engine::Integrator::kRungeKutta4}});
  }
  if (const Json* v = Find(root, "broad_phase")) {
    world.broad_phase = ReadChoice<engine::BroadPhaseType>(
        *v, "broad_phase",
        {{"auto", engine::BroadPhaseType::kAuto},
         {"all_pairs", engine::BroadPhaseType::kAllPairs},
         {"sweep_and_prune", engine::BroadPhaseType::kSweepAndPrune},
         {"uniform_grid", engine::BroadPhaseType::kUniformGrid},
         {"quadtree", engine::BroadPhaseType::kQuadtree},
         {"aabb_tree", engine::BroadPhaseType::kAabbTree}});
  }
  if (const Json* v = Find(root, "solver")) ReadSolver(*v, "solver", &world);
  if (const Json* v = Find(root, "particles")) ReadParticleSettings(*v, "particles", &world);
  if (const Json* v = Find(root, "sleep")) world.sleeping = ReadBool(*v, "sleep");
  if (const Json* v = Find(root, "continuous")) world.continuous = ReadBool(*v, "continuous");
  if (const Json* v = Find(root, "fluid_density")) world.fluid_density = ReadNonNegative(*v, "fluid_density");
  if (const Json* v = Find(root, "gravitational_constant")) {
    world.gravitational_constant = ReadNonNegative(*v, "gravitational_constant");
  }

  if (const Json* camera = Find(root, "camera")) {
    if (!camera->is_object()) throw SceneError{"camera", "must be an object"};
    RejectUnknownKeys(*camera, "camera", {"center", "width"});
    if (const Json* v = Find(*camera, "center")) scene.camera.center = ReadVec2(*v, "camera.center");
    if (const Json* v = Find(*camera, "width")) scene.camera.width = ReadPositive(*v, "camera.width");
  }
  if (const Json* click = Find(root, "click")) {
    if (!click->is_object()) throw SceneError{"click", "must be an object"};
    RejectUnknownKeys(*click, "click", {"max_impulse", "particle_radius", "particle_speed"});
    if (const Json* v = Find(*click, "max_impulse")) {
      scene.click_max_impulse = ReadNonNegative(*v, "click.max_impulse");
    }
    if (const Json* v = Find(*click, "particle_radius")) {
      scene.particle_click.radius = ReadPositive(*v, "click.particle_radius");
    }
    if (const Json* v = Find(*click, "particle_speed")) {
      scene.particle_click.speed = ReadNonNegative(*v, "click.particle_speed");
    }
  }

  const Json* bodies = Find(root, "bodies");
  if (!bodies) throw SceneError{"", "a scene needs \"bodies\" (an array)"};
  if (!bodies->is_array()) throw SceneError{"bodies", "must be an array"};
  if (bodies->size() > kMaxBodies) {
    throw SceneError{"bodies", std::to_string(bodies->size()) + " bodies, more than the limit of " +
                                   std::to_string(kMaxBodies) + " (docs/limits.md)"};
  }
  std::map<std::string, std::size_t> first_use;  // ordered: no hash-map order anywhere
  for (std::size_t i = 0; i < bodies->size(); ++i) {
    const std::string path = "bodies[" + std::to_string(i) + "]";
    SceneBody body = ReadBody((*bodies)[i], path, i, world.rotation);
    const auto [it, inserted] = first_use.emplace(body.id, i);
    if (!inserted) {
      const std::string other = "bodies[" + std::to_string(it->second) + "]";
      if (!body.id_given) {
        throw SceneError{path, "its default id " + Quote(body.id) + " is taken by " + other +
                                   "; give one of them an \"id\""};
      }
      throw SceneError{path + ".id", "duplicate id " + Quote(body.id) + " (also " + other + ")"};
    }
    scene.bodies.push_back(std::move(body));
  }
  if (const Json* springs = Find(root, "springs")) {
    if (!springs->is_array()) throw SceneError{"springs", "must be an array"};
    for (std::size_t i = 0; i < springs->size(); ++i) {
      scene.springs.push_back(ReadSpring((*springs)[i], "springs[" + std::to_string(i) + "]", first_use, scene.bodies));
    }
  }
  if (const Json* joints = Find(root, "joints")) {
    scene.joints = ReadJoints(*joints, scene.bodies, first_use, world.rotation);
  }
  ReadParticleLists(root, first_use, &scene);
  return scene;
}

}  // namespace

Expected<Scene> ParseScene(std::string_view json, const std::string& file_label,
                           const std::string& default_name) {
  Json root;
  JsonError error;
  if (!ParseJsonChecked(json, root, error)) {
    const std::string where = error.line_column.empty() ? "" : error.line_column + ":";
    return BadInput(file_label + ":" + where + " " + error.message);
  }
  try {
    return ReadScene(root, default_name);
  } catch (const SceneError& e) {
    return BadInput(file_label + ": " + (e.path.empty() ? "" : e.path + ": ") + e.message);
  }
}

Expected<Scene> LoadScene(const std::string& path) {
  Expected<std::string> text = ReadTextFile(path);
  if (!text.HasValue()) return text.Error();
  return ParseScene(text.Value(), path, std::filesystem::path(path).stem().string());
}

engine::World BuildWorld(const Scene& scene) {
  engine::World world(scene.world);
  for (const SceneBody& body : scene.bodies) world.CreateBody(body.def);
  for (const engine::SpringDef& spring : scene.springs) world.AddSpring(spring);
  // After every body, since a joint may name a later one; in file order, so JointId{i} is
  // joints[i].
  for (const SceneJoint& joint : scene.joints) world.CreateJoint(joint.def);
  // In file order, so SoftBodyId{i} is soft_bodies[i] and EmitterId{i} is emitters[i].
  for (const SceneSoftBody& soft : scene.soft_bodies) world.CreateSoftBody(soft.def);
  for (const SceneFluid& fluid : scene.fluids) world.AddFluid(fluid.def);
  for (const SceneEmitter& emitter : scene.emitters) world.CreateEmitter(emitter.def);
  return world;
}

std::optional<std::size_t> FindJoint(const Scene& scene, std::string_view id) {
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    if (scene.joints[i].id == id) return i;
  }
  return std::nullopt;
}

}  // namespace game
