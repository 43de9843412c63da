// The colours a GIF film's palette holds exactly. The palette is built once, from the first
// frame (render/gif_palette.h), so it must be told what later frames will show that the first
// may not: effect particles are born after it, and a small soft body covers too little of it.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/world.h"
#include "game/scene.h"
#include "render/color.h"

namespace game {

/// Effect colours sampled per emitter (ages × coverages); once this many are in, later
/// emitters get none, so a scene of many emitters leaves room for the first frame's colours.
inline constexpr std::size_t kMaxGifEffectColors = 96;

/// The background, the HUD's two colours, every body's fill; the link colours where `world`
/// has springs or joints; and where the scene has particles, each soft body's fill, the liquid
/// over the background, and each emitter's sprites over the background at a few ages and
/// coverages. A scene with none of these keeps the palette it had before they were drawn.
std::vector<render::Color> GifKeepColors(const Scene& scene, const engine::World& world);

}  // namespace game
