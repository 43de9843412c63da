// Temporary-then-rename output, so an interrupted or failed run leaves no half-written file.
#include "game/output_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace game {

std::string TemporaryPath(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}

bool WritesInPlace(const std::string& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) return true;
  std::error_code error;
  const std::string absolute = std::filesystem::absolute(path, error).lexically_normal().string();
  return !error && (absolute.rfind("/dev/", 0) == 0 || absolute.rfind("/proc/", 0) == 0);
}

Expected<AtomicOutputFile> AtomicOutputFile::Open(const std::string& path) {
  // A device or pipe (/dev/stdout, /dev/null, a FIFO) is written in place: a temporary file
  // renamed over it would replace the device node itself, which root is allowed to do.
  struct stat info;
  if (WritesInPlace(path)) {
    if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
      return RuntimeFailure(path + ": cannot write: is a folder");
    }
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) return RuntimeFailure(path + ": cannot write: " + std::strerror(errno));
    return AtomicOutputFile(path, std::string(), file);
  }
  std::string temp_path = TemporaryPath(path);
  std::FILE* file = std::fopen(temp_path.c_str(), "wb");
  if (!file) return RuntimeFailure(path + ": cannot write: " + std::strerror(errno));
  return AtomicOutputFile(path, std::move(temp_path), file);
}

AtomicOutputFile::AtomicOutputFile(AtomicOutputFile&& other) noexcept
    : path_(std::move(other.path_)), temp_path_(std::move(other.temp_path_)), file_(other.file_) {
  other.file_ = nullptr;
  other.temp_path_.clear();
}

AtomicOutputFile::~AtomicOutputFile() {
  if (file_) std::fclose(file_);
  if (!temp_path_.empty()) std::remove(temp_path_.c_str());
}

Status AtomicOutputFile::Commit() {
  const bool written = std::fflush(file_) == 0 && !std::ferror(file_);
  const int saved_errno = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!written || !closed) {
    return RuntimeFailure(path_ + ": cannot write: " + std::strerror(written ? errno : saved_errno));
  }
  if (!temp_path_.empty() && std::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    return RuntimeFailure(path_ + ": cannot write: " + std::strerror(errno));
  }
  temp_path_.clear();
  return std::nullopt;
}

}  // namespace game
