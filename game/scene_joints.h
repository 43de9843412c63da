// Scene joints: the top-level `joints` list (docs/scene-format.md#joints), each joint's type with
// its own keys, read and checked at the edge so that every joint a scene file can give meets
// World::CreateJoint's preconditions.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "game/scene.h"
#include "game/scene_values.h"

namespace game::scene_values {

/// Reads the root's `joints` value. `body_ids` maps each body's id to its index in `bodies`;
/// `rotation` is the scene's. Throws SceneError naming the key path of the first fault.
std::vector<SceneJoint> ReadJoints(const Json& joints, const std::vector<SceneBody>& bodies,
                                   const std::map<std::string, std::size_t>& body_ids, bool rotation);

}  // namespace game::scene_values
