// A film as one video file, encoded on a worker thread while the simulation and drawing run
// ahead; a bounded queue keeps memory flat. The file appears whole or not at all: it is written
// under a temporary name and renamed by Finish, and removed on failure, interruption or
// destruction before Finish.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <thread>

#include "game/status.h"
#include "game/work_queue.h"
#include "render/image.h"
#include "render/video_encoder.h"

namespace game {

class VideoWriter {
 public:
  /// Creates the folder it goes in when missing and starts the encoder; failures exit 1.
  static Expected<std::unique_ptr<VideoWriter>> Open(const std::string& path,
                                                     const render::VideoSettings& settings);
  /// Without Finish: stops the encoder and removes the temporary file.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  /// Queues the next frame; blocks while the queue is full. False once encoding has failed.
  bool Submit(render::Image frame);
  /// Encodes what is queued, completes the file and gives it its name; the first failure, if any.
  Status Finish();
  /// Frames in the file (a GIF keeps only frames 2/100 s apart).
  std::int64_t FramesKept() const { return encoder_->FramesKept(); }

 private:
  VideoWriter(std::string path, std::string temp_path, std::unique_ptr<render::VideoEncoder> encoder);
  void WorkerLoop();

  const std::string path_;
  const std::string temp_path_;
  std::unique_ptr<render::VideoEncoder> encoder_;
  WorkQueue<render::Image> queue_;
  bool finished_ = false;
  std::thread worker_;
};

}  // namespace game
