// Mutated particle scenes (soft bodies, fluid, emitters): thousands of seeded mutations of one
// scene that uses every particle key (random key deletions, type swaps, out-of-range and extreme
// numbers, unknown keys, lists grown past their limits). Each must either load, build and step
// with every body and particle finite, or be refused as bad input with one line naming the file
// and a key path; an engine precondition stopping the program would end this test binary.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "game/scene.h"
#include "game/scene_particles.h"

namespace {

using Json = nlohmann::json;

// SplitMix64: the same numbers on every platform (std distributions are not).
struct Random {
  std::uint64_t state;
  std::uint64_t Next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t Below(std::size_t n) { return static_cast<std::size_t>(Next() % n); }
};

const char* kBase = R"({
  "rotation": true,
  "dt": 0.016666666666666666,
  "particles": {"substep": 0.005, "iterations": 2},
  "click": {"max_impulse": 10, "particle_radius": 0.8, "particle_speed": 4},
  "bodies": [
    {"id": "floor", "shape": "box", "size": [12, 1], "position": [0, -0.5], "static": true},
    {"id": "wall", "shape": "box", "size": [0.4, 3], "position": [-3, 1.5], "static": true},
    {"id": "crate", "shape": "box", "size": [0.6, 0.6], "position": [2, 1], "density": 500},
    {"id": "ball", "shape": "circle", "radius": 0.3, "position": [0, 3]}
  ],
  "soft_bodies": [
    {"id": "jelly", "shape": "circle", "radius": 0.4, "position": [-1, 2], "angle": 0.3, "velocity": [0.5, 0],
     "density": 2, "spacing": 0.1, "stretch_compliance": 0.001, "area_compliance": 0.01, "pressure": 1.2,
     "damping": 2, "friction": 0.4, "color": "#3c8"},
    {"id": "beam", "shape": "box", "size": [1.2, 0.3], "position": [-2.4, 2], "spacing": 0.1,
     "stretch_compliance": 0.0001, "shear_compliance": 0.0002, "attach_to": "wall", "color": "#884422"}
  ],
  "fluids": [
    {"id": "pool", "region": [[0.5, 0], [1.5, 0.6]], "spacing": 0.1, "density": 1000, "velocity": [0, -1],
     "viscosity": 0.05, "vorticity": 0.1, "friction": 0.1, "color": "#36c"},
    {"region": [[-0.5, 0], [0, 0.3]], "density": 800}
  ],
  "emitters": [
    {"id": "torch", "position": [3, 0.2], "direction": 1.5, "spread": 0.4, "speed": 2, "speed_spread": 0.5,
     "rate": 60, "lifetime": 1, "lifetime_spread": 0.2, "size": [0.05, 0.2], "color": ["#ff8000ff", "#ff000000"],
     "blend": "additive", "drag": 0.5, "buoyancy": 1.5, "restitution": 0.2, "friction": 0.3, "collide": true,
     "seed": 7, "max_particles": 500},
    {"body": "crate", "position": [0, 0.3], "blend": "alpha", "color": "#8888", "size": 0.1}
  ]
})";

// Every value's place in the document, as JSON pointers.
void Pointers(const Json& value, const Json::json_pointer& at, std::vector<Json::json_pointer>* out) {
  out->push_back(at);
  if (value.is_object()) {
    for (const auto& item : value.items()) Pointers(item.value(), at / item.key(), out);
  } else if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) Pointers(value[i], at / i, out);
  }
}

const double kNumbers[] = {0.0, -0.0, -1.0, 1e-300, 5e-324, 1e-9, 1e-12, 0.5, 1.0, 2.0, 7.0, 1e6, 1e9, -1e9, 1.5e9, 1e300, 0.05, 1e-4};

// One mutation somewhere in `doc`.
void Mutate(Json& doc, Random& random) {
  std::vector<Json::json_pointer> places;
  Pointers(doc, Json::json_pointer(), &places);
  const Json::json_pointer at = places[random.Below(places.size())];
  Json& value = doc[at];
  switch (random.Below(8)) {
    case 0: {  // delete it
      if (at.empty()) return;
      Json& parent = doc[at.parent_pointer()];
      if (parent.is_object()) parent.erase(at.back());
      if (parent.is_array()) parent.erase(static_cast<std::size_t>(std::stoul(at.back())));
      return;
    }
    case 1: {  // another type
      const Json others[] = {nullptr, true, "x", Json::array(), Json::object(), Json::array({1, 2, 3}), "#zzz",
                             Json::array({Json::array({0, 0}), Json::array({0, 0})})};
      value = others[random.Below(std::size(others))];
      return;
    }
    case 2:
    case 3: value = kNumbers[random.Below(std::size(kNumbers))]; return;
    case 4:  // scaled
      if (value.is_number()) value = value.get<double>() * (random.Below(2) ? 1e4 : 1e-4);
      return;
    case 5:  // an unknown key
      if (value.is_object()) value["densty"] = 1;
      return;
    case 6:  // every number inside it extreme at once
      for (const Json::json_pointer& inner : places) {
        const std::string here = inner.to_string(), top = at.to_string();
        if (here.rfind(top, 0) == 0 && doc[inner].is_number()) doc[inner] = kNumbers[random.Below(std::size(kNumbers))];
      }
      return;
    default: {  // a list grown, past its limit now and then
      if (!value.is_array() || value.empty()) return;
      const std::size_t copies = random.Below(4) == 0 ? 10001 : 1 + random.Below(20);
      const Json first = value[0];
      for (std::size_t i = 0; i < copies; ++i) value.push_back(first);
      return;
    }
  }
}

bool Finite(engine::Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// Steps an accepted scene and requires everything in it to stay finite.
void StepAccepted(const game::Scene& scene, const std::string& text) {
  std::size_t particles = 0;
  for (const game::SceneFluid& fluid : scene.fluids) particles += fluid.particles;
  for (const game::SceneSoftBody& soft : scene.soft_bodies) particles += game::SoftBodyParticleCount(soft.def);
  // Large scenes only cost time here (a fine soft body beside a coarse fluid takes seconds a
  // step: every particle's neighbours are found within the fluid's kernel); the limits tests
  // load the largest.
  if (particles > 5000 || scene.bodies.size() > 64 || scene.emitters.size() > 64) return;
  engine::World world = game::BuildWorld(scene);
  for (int step = 0; step < 3; ++step) world.Step();
  INFO(text);
  CHECK_FALSE(world.Fault().has_value());
  for (const engine::BodyId id : world.BodyIds()) CHECK(Finite(world.State(id).position));
  for (const engine::Vec2 x : world.FluidPositions()) CHECK(Finite(x));
  for (const engine::SoftBodyId id : world.SoftBodyIds()) {
    for (const engine::Vec2 x : world.SoftBodyPositions(id)) CHECK(Finite(x));
  }
}

}  // namespace

TEST_CASE("scene particles fuzz: mutated scenes load and step finite, or fail with one keyed line",
          "[scene][particles][fuzz]") {
  const Json base = Json::parse(kBase);
  {
    const game::Expected<game::Scene> scene = game::ParseScene(kBase, "fuzz.json", "fuzz");
    if (!scene.HasValue()) FAIL(scene.Error().message);
  }
  // BALLBOX_FUZZ_ROUNDS and BALLBOX_FUZZ_SEED run it longer or elsewhere by hand.
  const char* rounds_text = std::getenv("BALLBOX_FUZZ_ROUNDS");
  const char* seed_text = std::getenv("BALLBOX_FUZZ_SEED");
  const int rounds = rounds_text ? std::atoi(rounds_text) : 3000;
  Random random{seed_text ? std::strtoull(seed_text, nullptr, 10) : 20240601};
  int accepted = 0, refused = 0;
  for (int round = 0; round < rounds; ++round) {
    Json doc = base;
    const std::size_t mutations = 1 + random.Below(3);
    for (std::size_t m = 0; m < mutations; ++m) Mutate(doc, random);
    const std::string text = doc.dump();
    const game::Expected<game::Scene> scene = game::ParseScene(text, "fuzz.json", "fuzz");
    if (!scene.HasValue()) {
      ++refused;
      const std::string& message = scene.Error().message;
      INFO(text);
      CHECK(scene.Error().exit_code == game::kExitBadInput);
      CHECK(message.rfind("fuzz.json: ", 0) == 0);
      CHECK(message.find('\n') == std::string::npos);
      continue;
    }
    ++accepted;
    StepAccepted(scene.Value(), text);
  }
  // Both sides are exercised.
  CHECK(accepted > rounds / 10);
  CHECK(refused > rounds / 10);
}
