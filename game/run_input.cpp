// Where a run's scene and events come from: files, or the embedded default and its demo script.
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

}  // namespace game
