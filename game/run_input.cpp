// Where a run's scene and events come from (files, or the embedded default and its demo script),
// and what became of the events at its end.
#include <cstdio>

#include "game/commands.h"
#include "game/default_scene.h"

namespace game {

Expected<RunInput> LoadRunInput(const RunOptions& options) {
  Expected<Scene> scene = options.scene_path
                              ? LoadScene(*options.scene_path)
                              : ParseScene(DefaultSceneJson(), "<default scene>", "default");
  if (!scene.HasValue()) return scene.Error();
  RunInput input{std::move(scene.Value()), {}};
  if (options.script_path || !options.scene_path) {
    Expected<std::vector<InputEvent>> events =
        options.script_path ? LoadScript(*options.script_path)
                            : ParseScript(DefaultScriptText(), "<default script>");
    if (!events.HasValue()) return events.Error();
    input.events = std::move(events.Value());
  }
  return input;
}

void PrintEventSummary(const Scene& scene, const EventLog& log, const EventsAfterEnd& late,
                       bool list_misses) {
  if (list_misses) {
    std::vector<std::string> ids;
    for (const SceneBody& body : scene.bodies) ids.push_back(body.id);
    for (const MissedClick& miss : log.Misses()) std::printf("%s\n", MissLine(miss, ids).c_str());
  }
  std::printf("%s\n", EventSummary(log, late, list_misses).c_str());
}

}  // namespace game
