// libFuzzer target: scene JSON through game::ParseScene, and every scene it accepts through
// BuildWorld and a few steps, since a scene the loader lets through must never stop the engine.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "game/scene.h"
#include "game/scene_particles.h"

namespace {

// What the contract promises of a message, checked on every rejected input.
void CheckMessage(const game::Failure& failure) {
  const std::string_view message = failure.message;
  const bool one_line = message.find('\n') == std::string_view::npos;
  const bool names_file = message.rfind("fuzz.json:", 0) == 0;
  if (failure.exit_code != game::kExitBadInput || !one_line || !names_file) {
    std::fprintf(stderr, "bad rejection (exit %d): %s\n", failure.exit_code, failure.message.c_str());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  game::Expected<game::Scene> scene = game::ParseScene(text, "fuzz.json", "fuzz");
  if (!scene.HasValue()) {
    CheckMessage(scene.Error());
    return 0;
  }
  // Few bodies and particles keep each input fast; the limits tests cover large counts.
  const game::Scene& loaded = scene.Value();
  std::size_t particles = 0;
  for (const game::SceneFluid& fluid : loaded.fluids) particles += fluid.particles;
  for (const game::SceneSoftBody& soft : loaded.soft_bodies) particles += game::SoftBodyParticleCount(soft.def);
  if (loaded.bodies.size() > 64 || loaded.emitters.size() > 64 || particles > 5000) return 0;
  engine::World world = game::BuildWorld(scene.Value());
  for (int step = 0; step < 4; ++step) world.Step();
  return 0;
}
