// How the renderer colours what is made of particles (soft bodies and fluid), per scene: the game
// fills a ParticleStyle from the scene (the defaults where it gives none) and hands it to
// Renderer::Draw with the bodies' colours. Effect particles carry their own colours in their
// emitters (engine::EmitterDef), so they need nothing here. No GL.
#pragma once

#include <vector>

#include "engine/ids.h"
#include "render/color.h"

namespace render {

/// A soft body's fill when its scene gives none: a jelly pink that none of the palette's
/// colours is close to, so a soft body never looks like a rigid one.
inline constexpr Color kSoftBodyColor{0xe8, 0x6f, 0xa5};

/// The liquid's colour when the scene gives none: water blue.
inline constexpr Color kFluidColor{0x2f, 0x86, 0xd6};

/// How much the liquid covers what lies behind it by default: bodies in it stay visible, tinted.
inline constexpr float kFluidOpacity = 0.7f;

struct ParticleStyle {
  /// soft_bodies[i] fills the soft body in slot i (SoftBodyId::index: the order the soft bodies
  /// were made in, as long as none was destroyed, like the bodies' colours); a slot past the
  /// end is filled with soft_body_default. Every soft body is outlined in its fill, darker, as
  /// the rigid bodies are.
  std::vector<Color> soft_bodies;
  Color soft_body_default = kSoftBodyColor;
  /// The colour of the liquid the fluid's particles make, every block alike.
  Color fluid = kFluidColor;
  /// 0..1: 1 hides what is behind the liquid, 0 makes it invisible.
  float fluid_opacity = kFluidOpacity;

  Color SoftBodyColor(engine::SoftBodyId id) const {
    return id.index < soft_bodies.size() ? soft_bodies[id.index] : soft_body_default;
  }
};

}  // namespace render
