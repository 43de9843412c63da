// A particle's look at its age: every property of its emitter's start and end, blended by the
// fraction of its life gone.
#include "particle_sprites.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

std::uint8_t ToByte(double channel) {
  return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(channel, 0.0, 1.0)));
}

double Lerp(double a, double b, double t) { return a + (b - a) * t; }

SpriteInstance MakeSprite(const engine::EffectParticle& particle, const engine::EmitterDef& emitter,
                          const Camera& camera, double pixel_size) {
  const double life = particle.lifetime > 0.0 ? std::clamp(particle.age / particle.lifetime, 0.0, 1.0)
                                              : 1.0;
  const double radius = 0.5 * std::max(Lerp(emitter.size_start, emitter.size_end, life), 0.0);
  const double drawn = std::max(radius, kMinSpriteRadiusPixels * pixel_size);
  const engine::Rgba& a = emitter.color_start;
  const engine::Rgba& b = emitter.color_end;
  const double coverage = (radius / drawn) * (radius / drawn);
  SpriteInstance sprite{};
  // Relative to the camera in double before going to float, as the bodies are.
  sprite.center[0] = static_cast<float>(particle.position.x - camera.center.x);
  sprite.center[1] = static_cast<float>(particle.position.y - camera.center.y);
  sprite.radius = static_cast<float>(drawn);
  sprite.color[0] = ToByte(Lerp(a.r, b.r, life));
  sprite.color[1] = ToByte(Lerp(a.g, b.g, life));
  sprite.color[2] = ToByte(Lerp(a.b, b.b, life));
  sprite.color[3] = ToByte(coverage * Lerp(a.a, b.a, life));
  return sprite;
}

}  // namespace

void ParticleSprites::Build(const engine::World& world,
                            std::span<const engine::EffectParticle> effects, const Camera& camera,
                            double pixel_size) {
  alpha_.clear();
  additive_.clear();
  for (const engine::EffectParticle& particle : effects) {
    if (!world.IsValid(particle.emitter)) continue;
    const engine::EmitterDef& emitter = world.GetEmitterDef(particle.emitter);
    const SpriteInstance sprite = MakeSprite(particle, emitter, camera, pixel_size);
    // A sprite that adds nothing is not worth a quad.
    if (sprite.color[3] == 0) continue;
    (emitter.blend == engine::EffectBlend::kAdditive ? additive_ : alpha_).push_back(sprite);
  }
}

}  // namespace render
