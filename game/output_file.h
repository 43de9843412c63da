// Output files that appear whole or not at all: written under a temporary name, then renamed.
#pragma once

#include <cstdio>
#include <string>

#include "game/status.h"

namespace game {

/// The temporary name a file is written under before it is renamed: "`path`.tmp-<pid>".
std::string TemporaryPath(const std::string& path);

/// Whether `path` is written in place rather than under a temporary name renamed over it: a
/// device or pipe, or any path under /dev or /proc (/dev/stdout redirected to a file looks like
/// a regular file, but renaming over it would replace the link itself).
bool WritesInPlace(const std::string& path);

class AtomicOutputFile {
 public:
  /// Opens `path`.tmp-<pid> beside `path` for writing; a device or pipe (/dev/stdout) is
  /// written in place instead (WritesInPlace), since renaming over it would replace the device
  /// node.
  static Expected<AtomicOutputFile> Open(const std::string& path);
  AtomicOutputFile(AtomicOutputFile&& other) noexcept;
  AtomicOutputFile& operator=(AtomicOutputFile&&) = delete;
  /// Removes the temporary file unless Commit succeeded.
  ~AtomicOutputFile();

  std::FILE* Stream() { return file_; }
  /// Flushes, closes and renames the temporary file to its final name.
  Status Commit();

 private:
  AtomicOutputFile(std::string path, std::string temp_path, std::FILE* file)
      : path_(std::move(path)), temp_path_(std::move(temp_path)), file_(file) {}
  std::string path_;
  std::string temp_path_;
  std::FILE* file_ = nullptr;
};

}  // namespace game
