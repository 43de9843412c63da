// The built-in default scene and its demo script, compiled in from assets/.
#pragma once

#include <string_view>

namespace game {

std::string_view DefaultSceneJson();
std::string_view DefaultScriptText();

}  // namespace game
