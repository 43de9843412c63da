// The scene's colours as the renderer takes them (scene_colors.h).
#include "game/scene_colors.h"

namespace game {

SceneColors ColorsOf(const Scene& scene) {
  SceneColors colors;
  for (const SceneBody& body : scene.bodies) colors.bodies.push_back(body.color);
  // Soft bodies take slots in scene order (BuildWorld), so slot i is soft_bodies[i].
  for (const SceneSoftBody& soft : scene.soft_bodies) colors.particles.soft_bodies.push_back(soft.color);
  // Every block has the same colour (the loader holds them to the first's).
  if (!scene.fluids.empty()) colors.particles.fluid = scene.fluids.front().color;
  return colors;
}

}  // namespace game
