// Whole-file reads for scene and script files.
#include "game/text_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "game/limits.h"

namespace game {

Expected<std::string> ReadTextFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return BadInput(path + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return BadInput(path + ": cannot open: " + std::strerror(errno));
  // Read in chunks up to the limit rather than asking the size: /dev/zero or a pipe has none.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxInputFileBytes) {
      return BadInput(path + ": larger than " + std::to_string(kMaxInputFileBytes >> 20) +
                      " MiB, the most an input file may hold (docs/limits.md)");
    }
  }
  if (in.bad()) return BadInput(path + ": cannot read: " + std::strerror(errno));
  return text;
}

}  // namespace game
