// Opens a video file back with libavformat and libavcodec (an independent path from the
// encoder's): codec, pixel format, size, frame rate, every frame's time, and frames as RGB.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace testing {

struct ProbedVideo {
  bool opened = false;
  std::string error;
  std::string codec;       ///< libavcodec's name: "h264", "vp9", "gif"
  std::string pixel_format;  ///< of the stream: "yuv420p", "pal8", ...
  int width = 0;
  int height = 0;
  int rate_num = 0;  ///< the stream's average frame rate, num / den
  int rate_den = 1;
  std::vector<double> frame_seconds;  ///< each decoded frame's time, in order
  std::vector<std::vector<std::uint8_t>> rgb;  ///< the first frames as RGB24, top-down
};

/// Decodes every frame of `path`, keeping the first `keep_rgb` as RGB.
ProbedVideo ProbeVideo(const std::string& path, int keep_rgb);

}  // namespace testing
