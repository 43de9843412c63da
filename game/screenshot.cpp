// link(2) gives the final name atomically and fails when it exists, so two screenshots (or a
// user's own file) can never be silently replaced, even by a concurrent writer.
#include "game/screenshot.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <vector>

#include "render/png_writer.h"

namespace game {

Expected<std::string> SaveScreenshot(const render::Image& image, const std::string& dir,
                                     const std::string& stem) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    return RuntimeFailure(dir + ": cannot create the screenshot folder: " +
                          (ec ? ec.message() : "a file of that name is in the way"));
  }
  const std::vector<std::uint8_t> png = render::EncodePng(image);
  if (png.empty()) return RuntimeFailure("cannot encode the screenshot: out of memory");

  const std::string temp = dir + "/." + stem + ".png.tmp-" + std::to_string(::getpid());
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (file == nullptr) return RuntimeFailure(temp + ": cannot write: " + std::strerror(errno));
  const bool written = std::fwrite(png.data(), 1, png.size(), file) == png.size();
  const int write_errno = errno;
  if (std::fclose(file) != 0 || !written) {
    std::remove(temp.c_str());
    return RuntimeFailure(temp + ": cannot write: " + std::strerror(written ? errno : write_errno));
  }
  for (int n = 1;; ++n) {
    const std::string path = dir + "/" + stem + (n == 1 ? "" : "-" + std::to_string(n)) + ".png";
    if (::link(temp.c_str(), path.c_str()) == 0) {
      std::remove(temp.c_str());
      return path;
    }
    int link_errno = errno;
    if (link_errno == EEXIST) continue;
    // A file system without hard links: rename, after looking (a narrow race, not a silent one).
    if (link_errno == EPERM || link_errno == ENOTSUP) {
      if (std::filesystem::exists(path, ec)) continue;
      if (std::rename(temp.c_str(), path.c_str()) == 0) return path;
      link_errno = errno;
    }
    const std::string reason = std::strerror(link_errno);
    std::remove(temp.c_str());
    return RuntimeFailure(path + ": cannot write: " + reason);
  }
}

}  // namespace game
