// `render` and `play` in a build without rendering (BALLBOX_WITH_RENDER=OFF): they say so and
// exit 1, after the command line was checked as in any build.
#include <string>

#include "game/commands.h"

namespace game {

namespace {

Failure NotBuilt(const std::string& command) {
  return RuntimeFailure("ballbox " + command +
                        ": this ballbox was built without rendering (BALLBOX_WITH_RENDER=OFF); "
                        "ballbox sim runs scenes without it");
}

}  // namespace

Status RunRender(const RenderOptions&) { return NotBuilt("render"); }
Status RunPlay(const PlayOptions&) { return NotBuilt("play"); }

}  // namespace game
