// `ballbox play`: the windowed game. Not built yet: the window issue brings GLFW play.
#include "game/commands.h"

namespace game {

Status RunPlay(const PlayOptions&) {
  return RuntimeFailure("ballbox play is not available in this build yet; use `ballbox render`");
}

}  // namespace game
