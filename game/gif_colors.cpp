// The GIF palette's kept colours (gif_colors.h). The particle colours are what the renderer's
// blending makes of them over the background (docs/rendering.md: the liquid at its opacity,
// sprites by alpha or by adding light), so the pixels a particle leaves on the light background
// map onto an entry close to them instead of onto whatever the first frame held.
#include "game/gif_colors.h"

#include <algorithm>
#include <cmath>

#include "game/scene_colors.h"
#include "render/bitmap_text.h"

namespace game {

namespace {

std::uint8_t Channel(double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); }

// `c` (0..1 channels) laid on `under` by `alpha`, or added to it by `alpha` (kAdditive), in the
// 8-bit colour and alpha the renderer hands GL.
render::Color Blend(engine::Rgba c, double alpha, render::Color under, engine::EffectBlend blend) {
  const double a = Channel(255.0 * alpha) / 255.0;
  auto mix = [&](float over, std::uint8_t below) {
    const double light = Channel(255.0 * over) * a;
    return Channel(blend == engine::EffectBlend::kAdditive ? below + light : light + (1.0 - a) * below);
  };
  return {mix(c.r, under.r), mix(c.g, under.g), mix(c.b, under.b)};
}

engine::Rgba ColorAt(const engine::EmitterDef& def, double life) {
  auto lerp = [life](float a, float b) { return static_cast<float>(a + (b - a) * life); };
  const engine::Rgba& a = def.color_start;
  const engine::Rgba& b = def.color_end;
  return {lerp(a.r, b.r), lerp(a.g, b.g), lerp(a.b, b.b), lerp(a.a, b.a)};
}

// A sprite at a fraction `life` of its life, seen over `under` where its falloff leaves
// `coverage` of its alpha: the grid keeps the ramp from `under` to the sprite's colour short
// between entries.
void AddEffectColors(const engine::EmitterDef& def, render::Color under, std::vector<render::Color>* keep) {
  for (const double life : {0.0, 0.4}) {
    const engine::Rgba c = ColorAt(def, life);
    for (const double coverage : {1.0, 0.75, 0.5, 0.25}) keep->push_back(Blend(c, c.a * coverage, under, def.blend));
  }
}

// A young sprite at full cover over the background: what lies under the sprites laid after it.
render::Color Young(const engine::EmitterDef& def) {
  const engine::Rgba c = ColorAt(def, 0.25);
  return Blend(c, c.a, render::kBackgroundColor, def.blend);
}

// Sprites over the background and over what they are most often laid on: an alpha sprite
// (spray, smoke) over another of its own, an additive one (fire) over the alpha ones (smoke),
// which is where a flame shows its colour on a light background.
std::vector<render::Color> EffectColors(const std::vector<SceneEmitter>& emitters) {
  std::vector<render::Color> smoke;
  for (const SceneEmitter& emitter : emitters) {
    if (emitter.def.blend == engine::EffectBlend::kAlpha) smoke.push_back(Young(emitter.def));
  }
  std::vector<render::Color> colors;
  for (const SceneEmitter& emitter : emitters) {
    std::vector<render::Color> unders = {render::kBackgroundColor};
    if (emitter.def.blend == engine::EffectBlend::kAlpha) {
      unders.push_back(Young(emitter.def));
    } else {
      unders.insert(unders.end(), smoke.begin(), smoke.end());
    }
    for (const render::Color under : unders) {
      if (colors.size() >= kMaxGifEffectColors) return colors;
      AddEffectColors(emitter.def, under, &colors);
    }
  }
  return colors;
}

}  // namespace

std::vector<render::Color> GifKeepColors(const Scene& scene, const engine::World& world) {
  const SceneColors colors = ColorsOf(scene);
  std::vector<render::Color> keep = {render::kBackgroundColor, render::kPanelBackdrop, render::kPanelText};
  keep.insert(keep.end(), colors.bodies.begin(), colors.bodies.end());
  // Only where there are links or particles, so a film without them keeps its palette, byte for byte.
  if (!world.Springs().empty() || !world.JointIds().empty()) {
    keep.insert(keep.end(), {render::kSpringColor, render::kJointColor});
  }
  keep.insert(keep.end(), colors.particles.soft_bodies.begin(), colors.particles.soft_bodies.end());
  if (!scene.fluids.empty()) {
    const engine::Rgba liquid{colors.particles.fluid.r / 255.0f, colors.particles.fluid.g / 255.0f,
                              colors.particles.fluid.b / 255.0f, 1.0f};
    keep.push_back(Blend(liquid, colors.particles.fluid_opacity, render::kBackgroundColor, engine::EffectBlend::kAlpha));
  }
  const std::vector<render::Color> effects = EffectColors(scene.emitters);
  keep.insert(keep.end(), effects.begin(), effects.end());
  return keep;
}

}  // namespace game
