// Reading a whole input file, with the failure the contract asks for when it cannot be read.
#pragma once

#include <string>

#include "game/status.h"

namespace game {

/// The file's bytes, or a bad-input failure naming the file (a missing input is bad usage).
Expected<std::string> ReadTextFile(const std::string& path);

}  // namespace game
