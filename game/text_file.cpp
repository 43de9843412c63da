// Whole-file reads for scene and script files.
#include "game/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace game {

Expected<std::string> ReadTextFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return BadInput(path + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return BadInput(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return BadInput(path + ": cannot read: " + std::strerror(errno));
  return text.str();
}

}  // namespace game
