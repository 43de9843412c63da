// `--save-state` and `--load-state`: a world's snapshot in a file, tied to the scene it came from.
#pragma once

#include <string>

#include "engine/world.h"
#include "game/scene.h"
#include "game/status.h"

namespace game {

/// Writes `world`'s whole state to `path` (whole or not at all), marked with the scene's
/// fingerprint so that only the same scene can load it.
Status SaveState(const std::string& path, const Scene& scene, const engine::World& world);

/// Replaces `world`'s state with the one saved in `path`. A file that is not a saved state, was
/// saved from another scene, or is truncated or corrupt is bad input naming the file.
Status LoadState(const std::string& path, const Scene& scene, engine::World* world);

}  // namespace game
