// Effect particles as the renderer draws them: each a soft round sprite, its diameter and
// colour taken from its emitter and blended linearly from birth to death, sorted into the two
// ways they are laid over the picture. No GL.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/world.h"
#include "render/camera.h"

namespace render {

/// Sprites are never drawn smaller than this radius: a smaller particle would fall between
/// pixel centres and flicker, so it is drawn this big with its alpha cut by the area ratio,
/// which keeps the light (or cover) it adds.
inline constexpr double kMinSpriteRadiusPixels = 1.0;

/// One sprite: the per-instance attributes the sprite shader reads.
struct SpriteInstance {
  float center[2];        // m, relative to the camera centre
  float radius;           // m: the falloff reaches 0 here
  std::uint8_t color[4];  // straight alpha, at the sprite's centre
};

/// One frame's sprites: those laid over by their alpha (smoke) first, then the additive ones
/// (fire, sparks), each group oldest first as World::Effects gives them.
class ParticleSprites {
 public:
  /// Collects `effects`, looking their emitters up in `world`, for `camera` at `pixel_size`
  /// metres per pixel. A particle whose emitter has been destroyed is left out: its colours
  /// and sizes went with the emitter, and any stand-in would draw it as something it is not.
  void Build(const engine::World& world, std::span<const engine::EffectParticle> effects,
             const Camera& camera, double pixel_size);
  /// The sprites laid over by their alpha (EffectBlend::kAlpha), drawn first.
  const std::vector<SpriteInstance>& Alpha() const { return alpha_; }
  /// The sprites whose light adds up (EffectBlend::kAdditive), drawn over them.
  const std::vector<SpriteInstance>& Additive() const { return additive_; }

 private:
  std::vector<SpriteInstance> alpha_;
  std::vector<SpriteInstance> additive_;
};

}  // namespace render
