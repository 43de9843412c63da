// What a video file name asks for, and which sizes each format can hold: no FFmpeg needed, so
// flags are checked the same way in every build.
#include <algorithm>
#include <cctype>

#include "render/video_encoder.h"

namespace render {

std::optional<VideoFormat> VideoFormatOf(const std::string& path) {
  std::string lower = path;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  auto ends_with = [&](const std::string& ext) {
    return lower.size() > ext.size() && lower.compare(lower.size() - ext.size(), ext.size(), ext) == 0;
  };
  if (ends_with(".mp4")) return VideoFormat::kMp4;
  if (ends_with(".webm")) return VideoFormat::kWebm;
  if (ends_with(".gif")) return VideoFormat::kGif;
  return std::nullopt;
}

std::optional<std::string> VideoSizeProblem(VideoFormat format, int width, int height) {
  // 4:2:0 chroma covers 2x2 pixels; libx264 refuses an odd side (libvpx rounds up, GIF has none).
  if (format == VideoFormat::kMp4 && (width % 2 != 0 || height % 2 != 0)) {
    return "an .mp4 film (H.264 in yuv420p) needs an even width and height, got " +
           std::to_string(width) + "x" + std::to_string(height) + " (try " +
           std::to_string(width + width % 2) + "x" + std::to_string(height + height % 2) + ")";
  }
  return std::nullopt;
}

}  // namespace render
