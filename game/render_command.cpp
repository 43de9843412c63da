// `ballbox render`: placeholder until the OSMesa renderer lands (being written now).
#include "game/commands.h"

namespace game {

Status RunRender(const RenderOptions&) {
  return RuntimeFailure("ballbox render is not available in this build yet; use `ballbox sim`");
}

}  // namespace game
