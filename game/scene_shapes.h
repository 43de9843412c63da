// What a scene body is made of: `shape` with its own keys, or `shapes`, a list of parts
// (docs/scene-format.md#shapes). Circles and boxes stay whole-body shapes, as before; polygons,
// capsules, segments and every entry of `shapes` become engine::ShapePart values.
#pragma once

#include <string>

#include "engine/body.h"
#include "game/scene_values.h"

namespace game::scene_values {

/// Reads `shape` (or `shapes`) and the shape keys of `body` into `def`: a circle or box into
/// def->shape, anything else into def->parts. Reads def->is_static and def->is_kinematic, so
/// they must be set first. Throws SceneError naming the key path of the first fault.
void ReadBodyShape(const Json& body, const std::string& path, engine::BodyDef* def);

/// kg: density × area over the body's shape or parts (each part with its own density, if it
/// has one), for the least-mass check. A segment has no area.
double MassFromDensity(const engine::BodyDef& def);

}  // namespace game::scene_values
