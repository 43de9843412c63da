// The commands behind the command line; each returns nothing or the failure to report.
#pragma once

#include "game/cli.h"
#include "game/event_log.h"
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

/// The body `--follow` names, by index, or nothing without the flag; an unknown id is bad input.
Expected<std::optional<engine::BodyId>> FollowedBody(const Scene& scene, const ViewOptions& view,
                                                     const std::string& scene_label);

/// Prints the events summary to stdout (after a line per miss when `list_misses`).
void PrintEventSummary(const Scene& scene, const EventLog& log, const EventsAfterEnd& late,
                       bool list_misses);

Status RunSim(const SimOptions& options);
Status RunRender(const RenderOptions& options);
Status RunPlay(const PlayOptions& options);

}  // namespace game
