// The commands behind the command line; each returns nothing or the failure to report.
#pragma once

#include "game/cli.h"
#include "game/scene.h"
#include "game/script.h"
#include "game/status.h"

namespace game {

/// The scene and events a run starts from: the given files, or the embedded default scene
/// with its demo script when no scene is given.
struct RunInput {
  Scene scene;
  std::vector<InputEvent> events;
};
Expected<RunInput> LoadRunInput(const RunOptions& options);

Status RunSim(const SimOptions& options);
Status RunRender(const RenderOptions& options);
Status RunPlay(const PlayOptions& options);

}  // namespace game
