// The colours a scene gives the renderer: one per body and the particle style (soft bodies'
// fills, the liquid's colour), built in one place for `ballbox render` and `ballbox play`.
#pragma once

#include <vector>

#include "game/scene.h"
#include "render/color.h"
#include "render/particle_style.h"

namespace game {

/// What Renderer::Draw takes besides the world and the camera.
struct SceneColors {
  std::vector<render::Color> bodies;  ///< bodies[i] fills body i (BodyId = scene index)
  render::ParticleStyle particles;    ///< soft bodies by slot (scene order), the fluid
};

/// The scene's colours, its defaults already filled in by the loader; the fluid's opacity is
/// the renderer's (a scene has no key for it).
SceneColors ColorsOf(const Scene& scene);

}  // namespace game
