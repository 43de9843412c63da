// Where a film's frames go: PNG files in a folder, one video file, or both, each written on
// worker threads while the simulation runs ahead.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "game/frame_writer.h"
#include "game/status.h"
#include "game/video_writer.h"
#include "render/image.h"
#include "render/png_writer.h"
#include "render/video_encoder.h"

namespace game {

struct FilmOutputOptions {
  std::string out_dir;  ///< PNG frames into this folder (created when missing); empty: none
  render::PngEncoding encoding = render::PngEncoding::kFast;
  int png_threads = 1;
  std::string video_path;  ///< empty: no video
  render::VideoSettings video;
};

class FilmOutput {
 public:
  /// Creates the folder (clearing dead runs' temporary files from it) and starts the video
  /// encoder. Failures exit 1.
  static Expected<std::unique_ptr<FilmOutput>> Open(const FilmOutputOptions& options);

  /// Hands frame `index` to every output. False once one of them has failed.
  bool Submit(std::int64_t index, render::Image frame);
  /// Waits for the PNG files, then removes frames of an earlier, longer run (numbered `frames`
  /// or more) and completes the video. The first failure, if any.
  Status Finish(std::int64_t frames);
  /// Waits for the PNG files queued so far and drops the video (interrupted or failed run).
  Status Abandon();
  /// Frames the video holds, once finished.
  std::int64_t VideoFrames() const { return video_ ? video_->FramesKept() : 0; }

 private:
  std::string out_dir_;
  std::unique_ptr<FrameWriter> png_;
  std::unique_ptr<VideoWriter> video_;
};

}  // namespace game
