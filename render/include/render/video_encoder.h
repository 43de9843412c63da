// Films as one video file, through FFmpeg's libraries: H.264 in MP4 (yuv420p, which browsers
// play), VP9 in WebM, or GIF with a palette of its own (render/gif_palette.h). No FFmpeg header
// here: the encoder lives in video_encoder_ffmpeg.cpp (video_encoder_none.cpp stands in for it
// in a build without the libraries).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/color.h"
#include "render/image.h"

namespace render {

enum class VideoFormat { kMp4, kWebm, kGif };

/// The format a file name asks for by its extension (.mp4, .webm, .gif; any case), or nothing.
std::optional<VideoFormat> VideoFormatOf(const std::string& path);

/// Whether this build can write videos at all (it was built with FFmpeg's libraries).
bool VideoSupportBuilt();

/// What cannot be encoded at this size in this format (e.g. H.264 in yuv420p needs even sides),
/// as a reason without "error: ", or nothing.
std::optional<std::string> VideoSizeProblem(VideoFormat format, int width, int height);

struct VideoSettings {
  VideoFormat format = VideoFormat::kMp4;
  int width = 0;
  int height = 0;
  double frame_seconds = 1.0 / 60.0;  ///< how long each frame shows: dt · K, so it plays in real time
  std::vector<Color> gif_keep;        ///< GIF: colours the palette must hold exactly
};

class VideoEncoder {
 public:
  /// Creates `path` (the format comes from `settings`, not from the name, so a temporary name
  /// works). Returns nullptr and sets `error` when FFmpeg cannot.
  static std::unique_ptr<VideoEncoder> Open(const std::string& path, const VideoSettings& settings,
                                            std::string& error);
  virtual ~VideoEncoder() = default;

  /// Encodes the next frame (frame k shows from k · frame_seconds). A GIF keeps only frames at
  /// least 2/100 s after the last it kept: browsers slow shorter GIF frames down to 1/10 s.
  virtual bool Write(const Image& frame, std::string& error) = 0;
  /// Flushes the encoder and completes the file; nothing may be written after.
  virtual bool Finish(std::string& error) = 0;
  /// Frames in the file so far (a GIF may keep fewer than it was given).
  virtual std::int64_t FramesKept() const = 0;
};

}  // namespace render
