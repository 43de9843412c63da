// Where a run's scene and events come from (files, or the embedded default and its demo script),
// and what became of the events at its end.
#include <algorithm>
#include <cstdio>
#include <thread>

#include "game/commands.h"
#include "game/default_scene.h"

namespace game {

Expected<RunInput> LoadRunInput(const RunOptions& options) {
  Expected<Scene> scene = options.scene_path
                              ? LoadScene(*options.scene_path)
                              : ParseScene(DefaultSceneJson(), "<default scene>", "default");
  if (!scene.HasValue()) return scene.Error();
  RunInput input{std::move(scene.Value()), {}};
  // Not part of the scene: any count steps to the same bits.
  input.scene.world.threads =
      options.threads > 0 ? options.threads
                          : std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, engine::kMaxThreads);
  if (options.script_path || !options.scene_path) {
    Expected<std::vector<InputEvent>> events =
        options.script_path ? LoadScript(*options.script_path)
                            : ParseScript(DefaultScriptText(), "<default script>");
    if (!events.HasValue()) return events.Error();
    input.events = std::move(events.Value());
  }
  return input;
}

Expected<std::optional<engine::BodyId>> FollowedBody(const Scene& scene, const ViewOptions& view,
                                                     const std::string& scene_label) {
  if (!view.follow) return std::optional<engine::BodyId>();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].id == *view.follow) return std::optional<engine::BodyId>(engine::BodyId{static_cast<engine::BodyIndex>(i)});
  }
  return BadInput("--follow: " + scene_label + " has no body with the id \"" + *view.follow + "\"");
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
