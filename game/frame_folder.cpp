// Only names this program writes are touched: frame_ with the index as FrameFileName spells
// it, then .png (or .png.tmp-<pid>); nothing else in the folder, not even names that only look
// similar (frame_00009.jpg).
#include "game/frame_folder.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>
#include <vector>

#include "game/frame_writer.h"

namespace game {

namespace {

bool AllDigits(std::string_view text) {
  return !text.empty() && text.size() <= 18 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The index of a frame file name exactly as FrameFileName writes it, or nothing.
std::optional<std::int64_t> FrameIndex(std::string_view name) {
  constexpr std::string_view kPrefix = "frame_";
  constexpr std::string_view kSuffix = ".png";
  if (!name.starts_with(kPrefix) || !name.ends_with(kSuffix)) return std::nullopt;
  const std::string_view digits =
      name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
  if (!AllDigits(digits)) return std::nullopt;
  const std::int64_t index = std::stoll(std::string(digits));
  if (FrameFileName(index) != name) return std::nullopt;
  return index;
}

bool ProcessRuns(long pid) { return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM; }

}  // namespace

Status CheckOutputFolder(const std::string& out_dir) {
  std::error_code ec;
  for (std::filesystem::path p = out_dir; !p.empty(); p = p.parent_path()) {
    if (std::filesystem::exists(p, ec)) {
      if (std::filesystem::is_directory(p, ec)) return std::nullopt;
      std::string message = out_dir + ": ";
      if (p != out_dir) message += p.string() + " ";
      message += "is a file, not a folder (--out names the folder for the frames)";
      return BadInput(message);
    }
    if (p == p.parent_path()) break;
  }
  return std::nullopt;
}

Status RemoveStaleFrames(const std::string& dir, std::int64_t frames) {
  std::vector<std::filesystem::path> stale;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::optional<std::int64_t> index = FrameIndex(entry.path().filename().string());
    if (index && *index >= frames && entry.is_regular_file()) stale.push_back(entry.path());
  }
  if (ec) return RuntimeFailure(dir + ": cannot list the output folder: " + ec.message());
  for (const std::filesystem::path& path : stale) {
    std::filesystem::remove(path, ec);
    if (ec) {
      return RuntimeFailure(path.string() + ": cannot remove this frame of an earlier run: " +
                            ec.message());
    }
  }
  return std::nullopt;
}

void RemoveDeadTemporaries(const std::string& dir) {
  std::error_code ec;
  std::vector<std::filesystem::path> dead;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const auto tmp = name.rfind(".tmp-");
    if (tmp == std::string::npos || !FrameIndex(std::string_view(name).substr(0, tmp))) continue;
    const std::string_view pid = std::string_view(name).substr(tmp + 5);
    if (AllDigits(pid) && !ProcessRuns(std::stol(std::string(pid))) && entry.is_regular_file()) {
      dead.push_back(entry.path());
    }
  }
  // Best effort: a file that will not go is no reason to refuse the film.
  for (const std::filesystem::path& path : dead) std::filesystem::remove(path, ec);
}

}  // namespace game
